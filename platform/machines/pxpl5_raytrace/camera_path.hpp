#pragma once
// The camera path of a multi-frame pxpl5-raytrace run: the eye turns about the view's vertical
// axis (its up vector through the point it looks at) by `camera.spin` degrees a frame, ending at
// the scene's own camera, so that the last frame -- the image written -- is the scene's view.
#include <cmath>
#include <vector>

#include "firmware/math.hpp"
#include "firmware/scene.hpp"
#include "params/registry.hpp"
#include "platform/machines/camera_turn.hpp"

namespace rtsim::platform::pxpl5 {

/// A run's frames and the camera's path through them (frames, camera.path, camera.spin,
/// camera.distance). The user moves during some frames and rests during others (VOL2's
/// interaction, L288): after a frame during which the user moved, the eye has turned
/// `camera.spin` degrees.
struct CameraPath {
  int frames = 1;
  double spin_deg = 0.0;     ///< the turn after a frame during which the user moves
  double distance = 1.0;     ///< the eye's distance from the point looked at, times the scene's
  std::vector<bool> moving;  ///< by frame: the user moves during it (the next frame's view turns)
  std::vector<int> turns_left;  ///< by frame: the eye's turns between it and the last (read())

  /// Turns of the eye between frame f and the last.
  int turns_after(int f) const { return turns_left[static_cast<std::size_t>(f)]; }

  static void declare_params(params::ParamRegistry& r);
  /// camera.path ("move 4, rest 6": segments of frames during which the user moves or rests)
  /// or, without one, `frames` frames all moving when camera.spin is not 0. A path that cannot
  /// be read, or `frames` set to another count, is bad input (exit 2).
  static CameraPath read(const params::ParamRegistry& r);
};

/// The eye moved along the line of sight to `distance` times its distance from the point looked
/// at (camera.distance: VOL2's Fig. 9 varies screen coverage so, L369).
inline void move_eye(scenes::Camera& c, double distance) {
  if (distance != 1.0) c.from = c.at + (c.from - c.at) * distance;
}

/// The camera of frame f: the last frame's `last` turned back about the vertical axis by the
/// turns between f and the last frame.
inline scenes::Camera frame_camera(const scenes::Camera& last, const CameraPath& path, int f) {
  return turned_about_up(last, -path.turns_after(f) * path.spin_deg);
}

}  // namespace rtsim::platform::pxpl5
