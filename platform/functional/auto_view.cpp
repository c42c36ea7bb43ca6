#include "platform/functional/auto_view.hpp"

#include <algorithm>
#include <cmath>

namespace rtsim::functional {

void frame_automatically(scenes::Scene& scene, const Bounds& bounds) {
  const Vec3 centre = bounds.empty() ? Vec3(0.0) : bounds.center();
  double radius = bounds.empty() ? 1.0 : 0.5 * glm::length(bounds.extent());
  if (!(radius > 0.0) || !std::isfinite(radius)) radius = 1.0;
  const Vec3 dir = glm::normalize(Vec3(kAutoViewDir[0], kAutoViewDir[1], kAutoViewDir[2]));
  const double half = 0.5 * kAutoViewAngleDeg * kPi / 180.0;
  // 0.85: the bounding sphere of a box is loose; this frames typical objects snugly.
  const double distance = 0.85 * radius / std::sin(half);
  scene.camera.from = centre + distance * dir;
  scene.camera.at = centre;
  scene.camera.up = Vec3(0.0, 0.0, 1.0);
  scene.camera.angle_deg = kAutoViewAngleDeg;
  scene.camera.hither = 1e-3 * radius;
  scene.camera.width = kAutoViewResolution;
  scene.camera.height = kAutoViewResolution;
  scene.has_camera = true;
  if (scene.lights.empty()) {
    // Key light above and to the left of the eye, fill light from the other side.
    const Vec3 right = glm::normalize(glm::cross(-dir, Vec3(0.0, 0.0, 1.0)));
    scene.lights.push_back({centre + distance * (dir - 0.6 * right + Vec3(0, 0, 0.8)), Color(1.0)});
    scene.lights.push_back({centre + distance * (dir + 1.2 * right), Color(0.5)});
  }
}

void turn_view(scenes::Camera& camera, double azimuth_deg, double elevation_deg) {
  const Vec3 offset = camera.from - camera.at;
  const double distance = glm::length(offset);
  const double up_length = glm::length(camera.up);
  if (!(distance > 0.0) || !(up_length > 0.0)) return;  // no eye to turn
  const Vec3 up = camera.up / up_length;
  // The eye's direction as a horizontal bearing and an elevation above it.
  const double height = glm::dot(offset, up);
  Vec3 level = offset - up * height;
  const double across = glm::length(level);
  if (across < 1e-12 * distance)
    level = glm::cross(up, std::abs(up.x) < 0.9 ? Vec3(1.0, 0.0, 0.0) : Vec3(0.0, 1.0, 0.0));
  level = glm::normalize(level);
  const double elevation = std::atan2(height, across);
  const double a = azimuth_deg * kPi / 180.0;
  // Rodrigues about `up` (level is perpendicular to it).
  const Vec3 turned = level * std::cos(a) + glm::cross(up, level) * std::sin(a);
  const double limit = 89.0 * kPi / 180.0;
  const double e = std::clamp(elevation + elevation_deg * kPi / 180.0, -limit, limit);
  camera.from = camera.at + distance * (turned * std::cos(e) + up * std::sin(e));
}

}  // namespace rtsim::functional
