#include "firmware/shading/camera.hpp"

#include <algorithm>
#include <cmath>

namespace rtsim::shading {

PinholeCamera::PinholeCamera(const scenes::Camera& view, int width, int height)
    : origin_(view.from), half_w_(0.5 * width), half_h_(0.5 * height) {
  forward_ = glm::normalize(view.at - view.from);
  Vec3 right = glm::cross(forward_, view.up);
  if (glm::length(right) < 1e-12) {
    // up parallel to the view direction: pick any perpendicular (the reader rejects this case
    // for files; generated cameras may still hit it)
    right = glm::cross(forward_, std::fabs(forward_.z) < 0.9 ? Vec3(0, 0, 1) : Vec3(1, 0, 0));
  }
  right = glm::normalize(right);
  const Vec3 up = glm::cross(right, forward_);
  const double tan_half = std::tan(0.5 * view.angle_deg * kPi / 180.0);
  // image plane at distance 1; height-1 pixel steps between the top and bottom row centres
  const double pixel = 2.0 * tan_half / std::max(1, height - 1);
  right_ = right * pixel;
  down_ = -up * pixel;
}

Ray PinholeCamera::primary(double x, double y) const {
  const Vec3 d = forward_ + (x - half_w_) * right_ + (y - half_h_) * down_;
  return Ray{origin_, glm::normalize(d)};
}

}  // namespace rtsim::shading
