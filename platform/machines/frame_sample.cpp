#include "platform/machines/frame_sample.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <string>

#include "common/input_error.hpp"

namespace rtsim::platform {

FrameSample::FrameSample(int width, int height, int every, int window_rows)
    : width_(static_cast<std::uint32_t>(width)),
      every_(every),
      window_rows_(std::max(1, window_rows)),
      windows_((height + window_rows_ - 1) / window_rows_) {
  const int detailed = detailed_windows();
  if (detailed < 3)
    throw InputError("--sample " + std::to_string(every_), 0,
                     "simulates " + std::to_string(detailed) + " of the frame's " +
                         std::to_string(windows_) + " windows of " + std::to_string(window_rows_) +
                         " rows in detail; the estimate needs at least 3: a smaller K, a "
                         "smaller --sample-window or a taller image");
  detailed_.assign(static_cast<std::size_t>(height), 0);
  functional_.assign(static_cast<std::size_t>(height), 1);
  for (int y = 0; y < height; ++y)
    if ((y / window_rows_) % every_ == 0) {
      detailed_[static_cast<std::size_t>(y)] = 1;
      functional_[static_cast<std::size_t>(y)] = 0;
    }
  done_.assign(static_cast<std::size_t>(windows_), 0);
}

nlohmann::ordered_json FrameSample::estimate(const sc_core::sc_time& begin,
                                             const sc_core::sc_time& end,
                                             double& estimate_s) const {
  std::vector<std::uint64_t> c;
  int silent = 0;
  for (int w = 0; w < windows_; w += every_) {
    if (done_[static_cast<std::size_t>(w)] == 0)
      ++silent;
    else
      c.push_back(done_[static_cast<std::size_t>(w)]);
  }
  std::sort(c.begin(), c.end());
  const double B = begin.to_seconds(), E = end.to_seconds();
  const double tick = sc_core::sc_time::from_value(1).to_seconds();
  nlohmann::ordered_json out;
  out["every"] = every_;
  out["window_rows"] = window_rows_;
  out["windows"] = windows_;
  out["detailed_windows"] = detailed_windows();
  out["detailed_frame_s"] = E - B;
  if (c.size() < 3) {
    // Nothing to extrapolate from: the sampled run's own frame, and no interval.
    estimate_s = E - B;
    out["estimate_s"] = estimate_s;
    out["note"] = "fewer than 3 windows received a contribution: no estimate";
    return out;
  }
  std::vector<double> d;
  for (std::size_t i = 1; i < c.size(); ++i)
    d.push_back(static_cast<double>(c[i] - c[i - 1]) * tick);
  const double n = static_cast<double>(d.size());
  const double mean = std::accumulate(d.begin(), d.end(), 0.0) / n;
  // Neighbouring windows cost alike (the image varies smoothly from row to row), so the
  // variance of the mean of a systematic sample is estimated from successive differences
  // (Wolter, "Introduction to Variance Estimation", the v_3 estimator), not as if the windows
  // were drawn at random, which would take the spread between the scene's empty and busy rows
  // for noise.
  double var = 0;
  for (std::size_t i = 1; i < d.size(); ++i) var += (d[i] - d[i - 1]) * (d[i] - d[i - 1]);
  var /= 2.0 * (n - 1);
  const double N = static_cast<double>(windows_ - 1);
  const double head = static_cast<double>(c.front()) * tick - B;
  const double tail = E - static_cast<double>(c.back()) * tick;
  estimate_s = head + N * mean + tail;
  const double fpc = std::sqrt(std::max(0.0, 1.0 - n / N));
  const double half = 3.0 * N * std::sqrt(var) / std::sqrt(n) * fpc;
  out["estimate_s"] = estimate_s;
  out["ci99_7_s"] = {estimate_s - half, estimate_s + half};
  out["half_width_relative"] = estimate_s > 0 ? half / estimate_s : 0.0;
  out["start_s"] = head;
  out["window_s_mean"] = mean;
  out["drain_s"] = tail;
  if (silent > 0) out["silent_windows"] = silent;
  return out;
}

}  // namespace rtsim::platform
