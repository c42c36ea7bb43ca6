#pragma once
// A viewpoint for rasterization: the camera's (the same pinhole mapping the ray tracers use,
// firmware/shading/camera.hpp, so a rasterized and a traced frame line up pixel for pixel), a
// light's (its shadow map) or a mirrored camera's (a planar reflection map). Eye space has x to
// the right, y up and z the depth along the view direction; screen space is in pixels, (0, 0) the
// top-left corner of the image and pixel centres at +0.5.
//
// Depth is linear eye depth quantized to a 32-bit word over [near, far] (Fig. 8's 4-byte depth,
// seed 004 L99): linear rather than 1/z, so that a shader can rebuild the surface point from the
// depth word and the sample's screen position (the shadow-map lookup does) with the same
// precision near and far.
#include <cstdint>

#include "firmware/bounds.hpp"
#include "firmware/math.hpp"
#include "firmware/scene.hpp"

namespace rtsim::raster {

/// The depth word of a sample no surface covers: farther than every surface.
inline constexpr std::uint32_t kBackgroundDepth = 0xFFFFFFFFu;
/// The largest depth word a surface can have (at `far`).
inline constexpr std::uint32_t kFarDepthWord = 0xFFFFFFFEu;

struct ViewTransform {
  Vec3 origin{0.0};
  Vec3 right{1.0, 0.0, 0.0};
  Vec3 up{0.0, 1.0, 0.0};
  Vec3 forward{0.0, 0.0, 1.0};
  /// The image-plane size of one pixel at depth 1.
  double pixel = 1.0;
  /// The screen position of the view axis, in pixels: (width / 2, height / 2).
  double centre_x = 0.0;
  double centre_y = 0.0;
  int width = 0;
  int height = 0;
  /// The eye depths the depth word spans; surfaces nearer than `near` are clipped away.
  double near = 1e-3;
  double far = 1.0;

  /// The scene camera's view of a `width` x `height` frame (PinholeCamera's mapping: the vertical
  /// angle between the top and bottom pixel centres is the camera's angle), with near and far
  /// taken from `bounds` (the scene's).
  static ViewTransform camera(const scenes::Camera& camera, int width, int height,
                              const Bounds& bounds);
  /// A square `size` x `size` view from `from` towards the centre of `aim` whose field of view
  /// just holds the sphere around `aim` (a point light's shadow map of what the camera sees),
  /// with near and far from `depths` (the whole scene: an occluder outside `aim` still casts).
  static ViewTransform enclosing(const Vec3& from, const Bounds& aim, const Bounds& depths,
                                 int size);
  /// This view mirrored in the plane through `point` with normal `normal` (a planar reflection
  /// map), re-sized to a square `size` x `size` image that holds this view's field (the wider of
  /// its two angles).
  ViewTransform mirrored(const Vec3& point, const Vec3& normal, int size,
                         const Bounds& bounds) const;

  Vec3 to_eye(const Vec3& p) const {
    const Vec3 d = p - origin;
    return {glm::dot(d, right), glm::dot(d, up), glm::dot(d, forward)};
  }
  double screen_x(const Vec3& eye) const { return centre_x + eye.x / (eye.z * pixel); }
  double screen_y(const Vec3& eye) const { return centre_y - eye.y / (eye.z * pixel); }
  /// The world point at screen position (sx, sy) and eye depth z.
  Vec3 world_at(double sx, double sy, double z) const {
    const double ex = (sx - centre_x) * pixel * z;
    const double ey = -(sy - centre_y) * pixel * z;
    return origin + right * ex + up * ey + forward * z;
  }
  /// Eye depth z in [near, far] as its depth word (rounded); outside: clamped.
  std::uint32_t depth_word(double z) const;
  /// The eye depth a depth word stands for (a surface's: not kBackgroundDepth).
  double depth_of(std::uint32_t word) const;
};

}  // namespace rtsim::raster
