#pragma once
// Pinhole camera from the NFF view block.
#include "firmware/ray.hpp"
#include "firmware/scene.hpp"

namespace rtsim::shading {

class PinholeCamera {
 public:
  /// NFF defines `angle` "from the center of top pixel row to bottom pixel row and left column
  /// to right column" (square images); we apply it to the rows, so the vertical angle between
  /// the top and bottom pixel centres is `angle_deg` and the horizontal extent follows from the
  /// aspect ratio (square pixels).
  PinholeCamera(const scenes::Camera& view, int width, int height);

  /// Ray through image position (x, y) in pixel units: (0,0) is the top-left corner of the
  /// image, (width, height) the bottom-right; pixel centres are at +0.5.
  Ray primary(double x, double y) const;

 private:
  Vec3 origin_;
  Vec3 forward_;
  Vec3 right_;  ///< scaled: one pixel step
  Vec3 down_;   ///< scaled: one pixel step
  double half_w_;
  double half_h_;
};

}  // namespace rtsim::shading
