#include "firmware/tasks/vision_ray_task.hpp"

#include <cmath>

namespace rtsim::tasks {

void sample_offset(int s, double& dx, double& dy) {
  // R2 sequence (generalised golden ratio in 2-D): alpha = (1/g, 1/g^2), g^3 = g + 1.
  constexpr double a1 = 0.7548776662466927;
  constexpr double a2 = 0.5698402909980532;
  dx = std::fmod(0.5 + a1 * s, 1.0);
  dy = std::fmod(0.5 + a2 * s, 1.0);
}

VisionRayTask::VisionRayTask(const shading::PinholeCamera& camera, int width, int height, int spp,
                             std::uint32_t first_pixel, std::uint32_t end_pixel,
                             const std::vector<char>* rows)
    : camera_(&camera),
      width_(width),
      spp_(spp < 1 ? 1 : spp),
      pixel_(first_pixel),
      end_(std::min<std::uint32_t>(end_pixel, static_cast<std::uint32_t>(width * height))),
      rows_(rows && !rows->empty() ? rows : nullptr) {
  if (pixel_ > end_) pixel_ = end_;
  if (!rows_) {
    pixels_left_ = end_ - pixel_;
    return;
  }
  for (std::uint32_t p = pixel_; p < end_;) {
    const std::uint32_t y = p / static_cast<std::uint32_t>(width_);
    const std::uint32_t row_end = std::min(end_, (y + 1) * static_cast<std::uint32_t>(width_));
    if ((*rows_)[y]) pixels_left_ += row_end - p;
    p = row_end;
  }
  skip_unselected();
}

VisionRayTask::VisionRayTask(const shading::PinholeCamera& camera, int width, int height, int spp,
                             const std::vector<char>* rows)
    : VisionRayTask(camera, width, height, spp, 0, static_cast<std::uint32_t>(width * height),
                    rows) {}

void VisionRayTask::skip_unselected() {
  if (!rows_) return;
  while (pixel_ < end_ && !(*rows_)[pixel_ / static_cast<std::uint32_t>(width_)])
    pixel_ = (pixel_ / static_cast<std::uint32_t>(width_) + 1) * static_cast<std::uint32_t>(width_);
  if (pixel_ > end_) pixel_ = end_;
}

std::uint64_t VisionRayTask::remaining() const {
  if (done()) return 0;
  return pixels_left_ * static_cast<std::uint64_t>(spp_) - static_cast<std::uint64_t>(sample_);
}

shading::TracedRay VisionRayTask::next(int& sample) {
  const int x = static_cast<int>(pixel_ % static_cast<std::uint32_t>(width_));
  const int y = static_cast<int>(pixel_ / static_cast<std::uint32_t>(width_));
  double dx = 0.5, dy = 0.5;
  sample_offset(sample_, dx, dy);
  shading::TracedRay r;
  r.ray = camera_->primary(x + dx, y + dy);
  r.kind = RayKind::Primary;
  r.pixel = pixel_;
  sample = sample_;
  if (++sample_ == spp_) {
    sample_ = 0;
    ++pixel_;
    --pixels_left_;
    skip_unselected();
  }
  return r;
}

}  // namespace rtsim::tasks
