#include "platform/machines/frame_sample.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <string>

#include "common/input_error.hpp"

namespace rtsim::platform {

namespace {
/// The variance of one of `x` (in sample order) from successive differences. Neighbouring
/// windows cost alike (the image varies smoothly from row to row), so the variance of the mean of
/// a systematic sample is estimated this way (Wolter, "Introduction to Variance Estimation", the
/// v_3 estimator), not as if the windows were drawn at random, which would take the spread
/// between the scene's empty and busy rows for noise.
double successive_difference_variance(const std::vector<double>& x) {
  double var = 0;
  for (std::size_t i = 1; i < x.size(); ++i) var += (x[i] - x[i - 1]) * (x[i] - x[i - 1]);
  return var / (2.0 * (static_cast<double>(x.size()) - 1));
}
}  // namespace

FrameSample::FrameSample(int every, int window_size, int windows, const std::string& unit_name,
                         int warmup)
    : every_(every),
      warmup_(std::clamp(warmup, 0, std::max(0, windows - 1))),
      window_size_(std::max(1, window_size)),
      windows_(windows),
      unit_name_(unit_name) {
  const int sampled = sampled_windows(windows_, every_, warmup_);
  if (sampled < 2) {
    std::string what = "simulates " + std::to_string(detailed_windows()) + " of the frame's " +
                       std::to_string(windows_) + " windows of " + std::to_string(window_size_) +
                       " " + unit_name_ + " in detail";
    if (warmup_ > 0)
      what += " (" + std::to_string(warmup_) + " of them a warm-up after window 0, " +
              std::to_string(sampled) + " sampled after it)";
    throw InputError("--sample " + std::to_string(every_), 0,
                     what +
                         "; the estimate needs at least 3 (window 0 and two sampled): a smaller "
                         "K, a smaller --sample-window, a shorter --sample-warmup or a larger "
                         "image");
  }
  done_.assign(static_cast<std::size_t>(windows_), 0);
}

int FrameSample::default_warmup(int width, int window_rows, int windows, int rays) {
  if (rays <= 0) return 0;
  const long per_window = static_cast<long>(std::max(1, width)) * std::max(1, window_rows);
  const int enough = static_cast<int>((rays + per_window - 1) / per_window);
  return std::min(enough, std::max(0, windows - 1) / 8);
}

FrameSample FrameSample::of_units(int units, int every, int window_units,
                                  const std::string& unit_name, int workers) {
  const int per = std::max(1, window_units);
  // No warm-up: the workers' busy times (estimate_shared) do not lengthen as queues fill.
  FrameSample s(every, per, windows_in(units, per), unit_name, 0);
  s.workers_ = std::max(1, workers);
  s.busy_.assign(static_cast<std::size_t>(s.windows_), 0);
  // The machine renders what it does not simulate: no rows, detailed or functional.
  return s;
}

FrameSample::FrameSample(int width, int height, int every, int window_rows, int warmup)
    : FrameSample(every, window_rows, windows_in(height, std::max(1, window_rows)), "rows",
                  warmup) {
  width_ = static_cast<std::uint32_t>(width);
  detailed_.assign(static_cast<std::size_t>(height), 0);
  functional_.assign(static_cast<std::size_t>(height), 1);
  for (int y = 0; y < height; ++y)
    if (detailed_window(y / window_size_)) {
      detailed_[static_cast<std::size_t>(y)] = 1;
      functional_[static_cast<std::size_t>(y)] = 0;
    }
}

nlohmann::ordered_json FrameSample::estimate(const sc_core::sc_time& begin,
                                             const sc_core::sc_time& end,
                                             double& estimate_s) const {
  // The warm-up's completion (the latest of windows 0..W), then the sampled windows'.
  std::vector<std::uint64_t> c;
  int silent = 0;
  std::uint64_t warm = 0;
  for (int w = 0; w <= warmup_; ++w) warm = std::max(warm, done_[static_cast<std::size_t>(w)]);
  if (warm == 0)
    ++silent;
  else
    c.push_back(warm);
  for (int w = (warmup_ / every_ + 1) * every_; w < windows_; w += every_) {
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
  if (unit_name_ == "rows") {
    out["window_rows"] = window_size_;
  } else {
    out["unit"] = unit_name_;
    out["window_units"] = window_size_;
  }
  out["windows"] = windows_;
  out["detailed_windows"] = detailed_windows();
  if (workers_ == 0) out["warmup_windows"] = warmup_;
  out["detailed_frame_s"] = E - B;
  if (workers_ > 0 && c.size() >= 3) {
    out.update(estimate_shared(B, E, estimate_s));
    return out;
  }
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
  const double mean = std::accumulate(d.begin(), d.end(), 0.0) / static_cast<double>(d.size());
  const double var = successive_difference_variance(d);
  const double N = static_cast<double>(windows_ - 1 - warmup_);  // windows after the warm-up
  const double head = static_cast<double>(c.front()) * tick - B;
  const double tail = E - static_cast<double>(c.back()) * tick;
  estimate_s = head + N * mean + tail;
  const double half = half_width(windows_ - warmup_, static_cast<int>(c.size()), std::sqrt(var));
  out["estimate_s"] = estimate_s;
  out["ci99_7_s"] = {estimate_s - half, estimate_s + half};
  out["half_width_relative"] = estimate_s > 0 ? half / estimate_s : 0.0;
  out["start_s"] = head;
  out["window_s_mean"] = mean;
  out["window_s_sd"] = std::sqrt(var);
  out["drain_s"] = tail;
  if (silent > 0) out["silent_windows"] = silent;
  return out;
}

nlohmann::ordered_json FrameSample::estimate_shared(double B, double E, double& estimate_s) const {
  const double tick = sc_core::sc_time::from_value(1).to_seconds();
  std::vector<double> u;
  std::uint64_t last_done = 0;
  for (int w = 0; w < windows_; w += every_) {
    if (done_[static_cast<std::size_t>(w)] == 0) continue;
    u.push_back(static_cast<double>(busy_[static_cast<std::size_t>(w)]) * tick);
    last_done = std::max(last_done, done_[static_cast<std::size_t>(w)]);
  }
  const double n = static_cast<double>(u.size()), N = windows_, P = workers_;
  const double mean = std::accumulate(u.begin(), u.end(), 0.0) / n;
  const double var = successive_difference_variance(u);
  const double head = static_cast<double>(first_start_) * tick - B;
  const double tail = E - static_cast<double>(last_done) * tick;
  // When the last window starts, the other P - 1 workers are half-way through theirs on
  // average: W = P t + u + (P - 1) u / 2, and the work ends at t + u = W / P + (u / 2)(1 - 1/P),
  // u a window's mean. That last term lies between 0 (all finish together) and u (1 - 1/P)
  // (the last window starts as the others end): the interval adds its half-range to the
  // sampling error. No window ends sooner than it is long.
  const double last = 0.5 * mean * (1.0 - 1.0 / P);
  const double work = N * mean / P + last;
  estimate_s = head + std::max(work, *std::max_element(u.begin(), u.end())) + tail;
  const double half =
      3.0 * (N / P) * std::sqrt(var) * std::sqrt(std::max(0.0, 1.0 / n - 1.0 / N)) + last;
  nlohmann::ordered_json out;
  out["workers"] = workers_;
  out["estimate_s"] = estimate_s;
  out["ci99_7_s"] = {estimate_s - half, estimate_s + half};
  out["half_width_relative"] = estimate_s > 0 ? half / estimate_s : 0.0;
  out["start_s"] = head;
  out["window_busy_s_mean"] = mean;
  out["window_s_sd"] = std::sqrt(var) / P;
  out["window_s_mean"] = mean / P;
  out["drain_s"] = tail;
  return out;
}

double FrameSample::half_width(int windows, int detailed, double window_sd) {
  // N - 1 increments in the frame, n - 1 of them measured; with the finite-population correction.
  const double N = windows - 1.0, n = detailed - 1.0;
  if (n <= 0 || N <= 0) return 0.0;
  return 3.0 * N * window_sd * std::sqrt(std::max(0.0, 1.0 / n - 1.0 / N));
}

int FrameSample::pilot_every(int windows) { return std::max(2, windows / kPilotWindows); }

int FrameSample::every_for(const nlohmann::ordered_json& pilot, double target) {
  const int windows = pilot.value("windows", 0);
  const int warmup = pilot.value("warmup_windows", 0);
  const double sd = pilot.value("window_s_sd", 0.0), frame = pilot.value("estimate_s", 0.0);
  if (!pilot.contains("window_s_sd") || frame <= 0) return 1;
  // The largest K first; never fewer windows than the pilot had, so the run's own interval
  // rests on as many differences as the choice did. The run has the pilot's warm-up.
  for (int k = std::max(2, windows / kPilotWindows); k >= 2; --k) {
    const int sampled = sampled_windows(windows, k, warmup);  // after the warm-up
    if (sampled >= 2 && half_width(windows - warmup, 1 + sampled, sd) <= target * frame) return k;
  }
  return 1;
}

}  // namespace rtsim::platform
