#pragma once
// What a renderer (functional or timed machine) accumulates while it renders a frame: the frame
// buffer (fixed point, order-independent), the primary-hit AOVs and the work counters; turned into
// the same RenderResult the functional renderer produces.
#include <limits>
#include <vector>

#include "firmware/shading/pixel_accumulator.hpp"
#include "firmware/trace_counters.hpp"
#include "platform/functional/functional_renderer.hpp"

namespace rtsim::functional {

class FrameState {
 public:
  FrameState(int width, int height, int spp, bool aov_id, bool aov_depth)
      : width_(width), height_(height), spp_(spp), fb_(width, height) {
    const auto n = static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
    if (aov_id) id_.assign(n, -1.0f);
    if (aov_depth) depth_.assign(n, std::numeric_limits<float>::infinity());
  }

  shading::PixelAccumulator& fb() { return fb_; }
  /// Sampled simulation: one flag per row, set for the rows the machine simulates in detail
  /// (the others are rendered functionally afterwards); empty: every row. VisionRayTask takes it.
  const std::vector<char>* detailed_rows() const { return rows_.empty() ? nullptr : &rows_; }
  void set_detailed_rows(std::vector<char> rows) { rows_ = std::move(rows); }
  /// The pixels the machine traces: all of them, or those of the detailed rows.
  std::uint64_t detailed_pixels() const {
    std::uint64_t rows = 0;
    for (char r : rows_) rows += r ? 1 : 0;
    return static_cast<std::uint64_t>(width_) *
           (rows_.empty() ? static_cast<std::uint64_t>(height_) : rows);
  }
  TraceCounters& counters() { return counters_; }
  int width() const { return width_; }
  int height() const { return height_; }
  int spp() const { return spp_; }

  /// The answer for sample 0's primary ray of a pixel fills the AOVs (as in `rtsim render`).
  void record_primary(std::uint32_t pixel, bool found, const Hit& hit) {
    if (!found) return;
    if (!id_.empty()) id_[pixel] = static_cast<float>(hit.prim_id);
    if (!depth_.empty()) depth_[pixel] = static_cast<float>(hit.surface.t);
  }

  RenderResult finish(double wall_time_s) const {
    RenderResult r;
    r.width = width_;
    r.height = height_;
    r.id = id_;
    r.depth = depth_;
    r.counters = counters_;
    r.wall_time_s = wall_time_s;
    const auto n = static_cast<std::size_t>(width_) * static_cast<std::size_t>(height_);
    r.rgb.resize(n * 3);
    for (std::size_t i = 0; i < n; ++i) {
      const Color c = fb_.value(static_cast<std::uint32_t>(i), spp_);
      r.rgb[3 * i + 0] = static_cast<float>(c.r);
      r.rgb[3 * i + 1] = static_cast<float>(c.g);
      r.rgb[3 * i + 2] = static_cast<float>(c.b);
    }
    return r;
  }

 private:
  int width_, height_, spp_;
  shading::PixelAccumulator fb_;
  std::vector<float> id_, depth_;
  std::vector<char> rows_;
  TraceCounters counters_;
};

}  // namespace rtsim::functional
