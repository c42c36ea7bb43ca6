#include "firmware/raster/view_transform.hpp"

#include <algorithm>
#include <cmath>

namespace rtsim::raster {

namespace {

/// An orthonormal frame looking from `from` to `at` with `up` as near as possible to up
/// (PinholeCamera's construction, including its fallback when `up` is parallel to the view).
void look(ViewTransform& v, const Vec3& from, const Vec3& at, const Vec3& up_hint) {
  v.origin = from;
  Vec3 f = at - from;
  if (glm::length(f) < 1e-300) f = Vec3(0.0, 0.0, -1.0);
  v.forward = glm::normalize(f);
  Vec3 r = glm::cross(v.forward, up_hint);
  if (glm::length(r) < 1e-12)
    r = glm::cross(v.forward, std::fabs(v.forward.z) < 0.9 ? Vec3(0, 0, 1) : Vec3(1, 0, 0));
  v.right = glm::normalize(r);
  v.up = glm::cross(v.right, v.forward);
}

/// Near and far from the eye depths of the corners of `bounds`: far just beyond the farthest
/// corner; near at the nearest corner in front, but no nearer than far / 2^20 (the depth word's
/// resolution is then still far below a pixel's footprint) and no farther than `hither`.
void depth_range(ViewTransform& v, const Bounds& bounds, double hither) {
  double lo = kInfinity, hi = 0.0;
  if (!bounds.empty()) {
    for (int c = 0; c < 8; ++c) {
      const Vec3 p((c & 1) ? bounds.hi.x : bounds.lo.x, (c & 2) ? bounds.hi.y : bounds.lo.y,
                   (c & 4) ? bounds.hi.z : bounds.lo.z);
      const double z = glm::dot(p - v.origin, v.forward);
      lo = std::min(lo, z);
      hi = std::max(hi, z);
    }
  }
  if (!(hi > 0.0)) hi = 1.0;
  v.far = hi * 1.001 + 1e-9;
  const double floor = v.far / 1048576.0;
  v.near = std::max(floor, std::min(lo, hither > 0.0 ? hither : lo));
  if (!(v.near < v.far)) v.near = floor;
}

}  // namespace

ViewTransform ViewTransform::camera(const scenes::Camera& cam, int width, int height,
                                    const Bounds& bounds) {
  ViewTransform v;
  look(v, cam.from, cam.at, cam.up);
  v.width = width;
  v.height = height;
  v.centre_x = 0.5 * width;
  v.centre_y = 0.5 * height;
  // PinholeCamera: height - 1 pixel steps between the top and bottom row centres.
  v.pixel = 2.0 * std::tan(0.5 * cam.angle_deg * kPi / 180.0) / std::max(1, height - 1);
  depth_range(v, bounds, cam.hither);
  return v;
}

ViewTransform ViewTransform::enclosing(const Vec3& from, const Bounds& bounds, const Bounds& depths,
                                       int size) {
  ViewTransform v;
  look(v, from, bounds.empty() ? Vec3(0.0) : bounds.center(), Vec3(0.0, 0.0, 1.0));
  v.width = v.height = size;
  v.centre_x = v.centre_y = 0.5 * size;
  const double radius = bounds.empty() ? 1.0 : 0.5 * glm::length(bounds.extent());
  const double distance = glm::length(bounds.center() - from);
  // The half-angle that holds the bounding sphere; a light inside it sees 60 degrees either side.
  const double half = distance > radius * 1.0001 ? std::asin(radius / distance) : kPi / 3.0;
  v.pixel = 2.0 * std::tan(std::min(half, kPi / 3.0)) / size;
  depth_range(v, depths, 0.0);
  return v;
}

ViewTransform ViewTransform::mirrored(const Vec3& point, const Vec3& normal, int size,
                                      const Bounds& bounds) const {
  const Vec3 n = glm::normalize(normal);
  const auto reflect_point = [&](const Vec3& p) { return p - 2.0 * glm::dot(p - point, n) * n; };
  const auto reflect_dir = [&](const Vec3& d) { return d - 2.0 * glm::dot(d, n) * n; };
  ViewTransform v = *this;
  v.origin = reflect_point(origin);
  v.forward = reflect_dir(forward);
  v.up = reflect_dir(up);
  v.right = glm::cross(v.forward, v.up);  // right-handed again
  const double half_w = 0.5 * width * pixel, half_h = 0.5 * height * pixel;
  v.width = v.height = size;
  v.centre_x = v.centre_y = 0.5 * size;
  v.pixel = 2.0 * std::max(half_w, half_h) / size;
  depth_range(v, bounds, near);
  return v;
}

std::uint32_t ViewTransform::depth_word(double z) const {
  const double t = std::clamp((z - near) / (far - near), 0.0, 1.0);
  return static_cast<std::uint32_t>(std::llround(t * static_cast<double>(kFarDepthWord)));
}

double ViewTransform::depth_of(std::uint32_t word) const {
  return near + (far - near) * (static_cast<double>(word) / static_cast<double>(kFarDepthWord));
}

}  // namespace rtsim::raster
