#pragma once
// Ullner's host task 1 (seed 000 L474-L476), Gaudet's ray spawning of initial rays: vision rays
// for the pixels, in scan-line order, `spp` per pixel. Sample 0 is the pixel centre; later
// samples follow the R2 low-discrepancy sequence.
#include <cstdint>
#include <vector>

#include "firmware/cost.hpp"
#include "firmware/shading/camera.hpp"
#include "firmware/shading/traced_ray.hpp"

namespace rtsim::tasks {

/// Offset of sample `s` inside its pixel, in [0,1)^2.
void sample_offset(int s, double& dx, double& dy);

class VisionRayTask {
 public:
  /// Rays for pixels [first_pixel, end_pixel) of a width x height image. With `rows` (one flag
  /// per image row; sampled simulation, platform/machines/frame_sample.hpp) only the pixels of
  /// flagged rows.
  VisionRayTask(const shading::PinholeCamera& camera, int width, int height, int spp,
                std::uint32_t first_pixel, std::uint32_t end_pixel,
                const std::vector<char>* rows = nullptr);
  VisionRayTask(const shading::PinholeCamera& camera, int width, int height, int spp,
                const std::vector<char>* rows = nullptr);

  bool done() const { return pixels_left_ == 0; }
  std::uint64_t remaining() const;
  /// The next vision ray; `sample` receives its sample index within the pixel.
  shading::TracedRay next(int& sample);

  /// Cost of generating one vision ray: d = f + x r + y u, then normalise.
  static constexpr Cost kCost{
      .fp_add = 8, .fp_mul = 9, .fp_div = 1, .fp_sqrt = 1, .mem_words = 8, .instructions = 10};

 private:
  const shading::PinholeCamera* camera_;
  int width_;
  int spp_;
  std::uint32_t pixel_;
  std::uint32_t end_;
  int sample_ = 0;
  const std::vector<char>* rows_ = nullptr;
  std::uint64_t pixels_left_ = 0;  ///< selected pixels from pixel_ on
  /// Moves pixel_ to the next selected pixel at or after it.
  void skip_unselected();
};

}  // namespace rtsim::tasks
