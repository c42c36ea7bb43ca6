#pragma once
// Sampled simulation (`rtsim run --sample K`), in the manner of SMARTS (Wunderlich et al., ISCA
// 2003: systematic sampling of detailed simulation, the rest run functionally, an estimate with
// a confidence interval). The frame's rows are cut into windows of `window_rows` rows; window 0
// and every K-th after it are simulated in detail, back to back, and the other rows are rendered
// functionally afterwards, so the image is whole and the same bytes.
//
// The machine tells the frame buffer of each contribution; a window's completion is the time of
// its last. With c_0 < ... < c_{n-1} the detailed windows' completions in the frame [B, E] of the
// sampled run and d_i = c_i - c_{i-1} (one window's worth of the machine's throughput, the
// windows before it having warmed the queues), the frame of all N windows is estimated as
//
//   T = (c_0 - B) + (N - 1) mean(d) + (E - c_{n-1})
//
// the start-up, N - 1 windows at the sampled rate, and the drain. Its 99.7% confidence interval
// is T +- 3 (N - 1) s_d / sqrt(n - 1) sqrt(1 - (n - 1) / (N - 1)), with s_d^2 from successive
// differences of the d_i (frame_sample.cpp says why) and the finite-population correction. Only the frame time is estimated; the other statistics are the sampled run's.
#include <cstdint>
#include <nlohmann/json.hpp>
#include <systemc>
#include <vector>

namespace rtsim::platform {

class FrameSample {
 public:
  /// Throws InputError when fewer than three windows would be simulated in detail.
  FrameSample(int width, int height, int every, int window_rows);

  /// One flag per row: simulated in detail, or rendered functionally afterwards.
  const std::vector<char>& detailed_rows() const { return detailed_; }
  const std::vector<char>& functional_rows() const { return functional_; }

  /// A contribution to `pixel` at simulated time `ticks`.
  void contribution(std::uint32_t pixel, std::uint64_t ticks) {
    const std::size_t w = (pixel / width_) / static_cast<std::uint32_t>(window_rows_);
    if (done_[w] < ticks) done_[w] = ticks;
  }

  /// The estimate from the sampled run's frame [begin, end]: stats.json `sample`, and the
  /// estimated frame time in `estimate_s`.
  nlohmann::ordered_json estimate(const sc_core::sc_time& begin, const sc_core::sc_time& end,
                                  double& estimate_s) const;

 private:
  /// Windows 0, K, 2K, ... below the frame's count.
  int detailed_windows() const { return (windows_ + every_ - 1) / every_; }
  std::uint32_t width_;
  int every_, window_rows_, windows_;
  std::vector<char> detailed_, functional_;
  std::vector<std::uint64_t> done_;  ///< by window: its last contribution (0: none)
};

}  // namespace rtsim::platform
