#pragma once
// The camera path of a multi-frame pxpl5-raytrace run: the eye turns about the view's vertical
// axis (its up vector through the point it looks at) by `camera.spin` degrees a frame, ending at
// the scene's own camera, so that the last frame -- the image written -- is the scene's view.
#include <cmath>

#include "firmware/math.hpp"
#include "firmware/scene.hpp"
#include "params/registry.hpp"

namespace rtsim::platform::pxpl5 {

/// A run's frames and the camera's path through them (frames, camera.spin, camera.distance).
struct CameraPath {
  int frames = 1;
  double spin_deg = 0.0;  ///< the turn from one frame to the next
  double distance = 1.0;  ///< the eye's distance from the point looked at, times the scene's

  static void declare_params(params::ParamRegistry& r);
  static CameraPath read(const params::ParamRegistry& r);
};

/// The eye moved along the line of sight to `distance` times its distance from the point looked
/// at (camera.distance: VOL2's Fig. 9 varies screen coverage so, L369).
inline void move_eye(scenes::Camera& c, double distance) {
  if (distance != 1.0) c.from = c.at + (c.from - c.at) * distance;
}

/// The camera of frame f of `frames`: the last frame's `last` turned about the vertical axis by
/// (f - (frames - 1)) x `spin_deg`.
inline scenes::Camera frame_camera(const scenes::Camera& last, int f, int frames, double spin_deg) {
  scenes::Camera c = last;
  const double a = (f - (frames - 1)) * spin_deg * kPi / 180.0;
  if (a == 0.0) return c;
  const Vec3 k = glm::normalize(last.up);
  const Vec3 v = last.from - last.at;
  // Rodrigues' rotation of the eye about the axis k through `at`.
  c.from = last.at + v * std::cos(a) + glm::cross(k, v) * std::sin(a) +
           k * glm::dot(k, v) * (1.0 - std::cos(a));
  return c;
}

}  // namespace rtsim::platform::pxpl5
