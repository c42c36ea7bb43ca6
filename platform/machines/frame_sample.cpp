#include "platform/machines/frame_sample.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>
#include <optional>
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

modules::UnitSchema FrameSample::units() {
  using modules::StatUnit;
  return {{"every", StatUnit::count},
          {"window_rows", StatUnit::count},
          {"window_units", StatUnit::count},
          {"windows", StatUnit::count},
          {"detailed_windows", StatUnit::count},
          {"warmup_windows", StatUnit::count},
          {"workers", StatUnit::count},
          {"silent_windows", StatUnit::count},
          {"half_width_relative", StatUnit::fraction},
          {"systematic.half_width_relative", StatUnit::fraction},
          {"work.frame_tests", StatUnit::count},
          {"work.frame_rays", StatUnit::count},
          {"work.subsample_windows", StatUnit::count},
          {"work.windows.window", StatUnit::count},
          {"work.windows.tests", StatUnit::count},
          {"work.windows.rays", StatUnit::count},
          // The times: the estimate, its interval, its parts, the regression's seconds a test
          // and a ray, and its residual.
          {"*_s", StatUnit::seconds},
          {"*_s_mean", StatUnit::seconds},
          {"*_s_sd", StatUnit::seconds},
          {"work.s_per_test", StatUnit::seconds},
          {"work.s_per_ray", StatUnit::seconds},
          {"work.window_s_fixed", StatUnit::seconds}};
}

nlohmann::ordered_json FrameSample::estimate(const sc_core::sc_time& begin,
                                             const sc_core::sc_time& end,
                                             double& estimate_s) const {
  // The warm-up's completion (the latest of windows 0..W, window -1 below), then the sampled
  // windows', each with its window.
  std::vector<std::pair<std::uint64_t, int>> c;
  int silent = 0;
  std::uint64_t warm = 0;
  for (int w = 0; w <= warmup_; ++w) warm = std::max(warm, done_[static_cast<std::size_t>(w)]);
  if (warm == 0)
    ++silent;
  else
    c.emplace_back(warm, -1);
  for (int w = (warmup_ / every_ + 1) * every_; w < windows_; w += every_) {
    if (done_[static_cast<std::size_t>(w)] == 0)
      ++silent;
    else
      c.emplace_back(done_[static_cast<std::size_t>(w)], w);
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
  // d_i: the time from one sampled completion to the next, the work of the window completing.
  std::vector<double> d;
  std::vector<int> d_window;
  for (std::size_t i = 1; i < c.size(); ++i) {
    d.push_back(static_cast<double>(c[i].first - c[i - 1].first) * tick);
    d_window.push_back(c[i].second);
  }
  const double mean = std::accumulate(d.begin(), d.end(), 0.0) / static_cast<double>(d.size());
  const double var = successive_difference_variance(d);
  const double N = static_cast<double>(windows_ - 1 - warmup_);  // windows after the warm-up
  const double head = static_cast<double>(c.front().first) * tick - B;
  const double tail = E - static_cast<double>(c.back().first) * tick;
  const double systematic = head + N * mean + tail;
  const double half = half_width(windows_ - warmup_, static_cast<int>(c.size()), std::sqrt(var));
  const std::optional<WorkEstimate> work = work_estimate(d, d_window);
  estimate_s = work ? head + work->total + tail : systematic;
  const double chosen_half = work ? work->half : half;
  out["estimator"] = work ? "work" : "systematic";
  out["estimate_s"] = estimate_s;
  out["ci99_7_s"] = {estimate_s - chosen_half, estimate_s + chosen_half};
  out["half_width_relative"] = estimate_s > 0 ? chosen_half / estimate_s : 0.0;
  out["start_s"] = head;
  out["window_s_mean"] = mean;
  out["window_s_sd"] = std::sqrt(var);
  out["drain_s"] = tail;
  if (work) {
    out["work"] = work->json;
    out["systematic"] = {{"estimate_s", systematic},
                         {"ci99_7_s", {systematic - half, systematic + half}},
                         {"half_width_relative", systematic > 0 ? half / systematic : 0.0}};
  }
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

namespace {
/// Least squares of y on the columns of x (with a column of ones first): the coefficients,
/// or none where the columns are (nearly) dependent. The columns are scaled to unit size first.
std::optional<std::vector<double>> least_squares(const std::vector<std::vector<double>>& x,
                                                 const std::vector<double>& y) {
  const std::size_t p = x.size() + 1, m = y.size();
  std::vector<double> scale(p, 1.0);
  auto col = [&](std::size_t j, std::size_t i) { return j == 0 ? 1.0 : x[j - 1][i] / scale[j]; };
  for (std::size_t j = 1; j < p; ++j) {
    double big = 0;
    for (double v : x[j - 1]) big = std::max(big, std::fabs(v));
    if (big == 0) return std::nullopt;
    scale[j] = big;
  }
  // Normal equations A b = r, solved by elimination with partial pivoting.
  std::vector<std::vector<double>> a(p, std::vector<double>(p + 1, 0.0));
  for (std::size_t i = 0; i < m; ++i)
    for (std::size_t j = 0; j < p; ++j) {
      for (std::size_t k = 0; k < p; ++k) a[j][k] += col(j, i) * col(k, i);
      a[j][p] += col(j, i) * y[i];
    }
  for (std::size_t j = 0; j < p; ++j) {
    std::size_t piv = j;
    for (std::size_t r = j + 1; r < p; ++r)
      if (std::fabs(a[r][j]) > std::fabs(a[piv][j])) piv = r;
    if (std::fabs(a[piv][j]) < 1e-9 * static_cast<double>(m)) return std::nullopt;
    std::swap(a[j], a[piv]);
    for (std::size_t r = 0; r < p; ++r) {
      if (r == j) continue;
      const double f = a[r][j] / a[j][j];
      for (std::size_t k = j; k <= p; ++k) a[r][k] -= f * a[j][k];
    }
  }
  std::vector<double> b(p);
  for (std::size_t j = 0; j < p; ++j) b[j] = a[j][p] / a[j][j] / scale[j];
  return b;
}
}  // namespace

std::optional<FrameSample::WorkEstimate> FrameSample::work_estimate(
    const std::vector<double>& d, const std::vector<int>& d_window) const {
  if (workers_ != 0 || work_.size() != static_cast<std::size_t>(windows_)) return std::nullopt;
  auto at = [&](int w) -> const functional::WindowWork& {
    return work_[static_cast<std::size_t>(w)];
  };
  // Every window not in detail has its subsample (each traced pixel is a ray at least), or
  // the count left them out (the windows in detail did not differ): nothing to weigh by.
  for (const auto& w : work_)
    if (!w.whole && w.sub_rays <= 0) return std::nullopt;
  // The work variables: a window's exact intersection tests and rays, and its columns'.
  using Work = std::array<double, 2>;
  auto exact = [](const functional::WindowWork& w) { return Work{w.tests, w.rays}; };
  auto sub = [](const functional::WindowWork& w) { return Work{w.sub_tests, w.sub_rays}; };
  // Each difference against the exact work of the window it belongs to (-1: the warm-up's
  // windows together).
  std::vector<Work> x;
  for (int w : d_window) {
    Work sum{};
    for (int v = std::max(0, w); v <= (w < 0 ? warmup_ : w); ++v) {
      if (!at(v).whole) return std::nullopt;
      for (std::size_t k = 0; k < sum.size(); ++k) sum[k] += exact(at(v))[k];
    }
    x.push_back(sum);
  }
  const double m = static_cast<double>(d.size());
  // Both variables, else the one that varies (a brute-force search tests every primitive for
  // every ray: its tests are its rays times a constant).
  std::vector<std::size_t> used;
  std::optional<std::vector<double>> coef;
  for (const auto& cols : {std::vector<std::size_t>{0, 1}, {0}, {1}}) {
    if (m < static_cast<double>(cols.size()) + 3) continue;  // 2 degrees of freedom left
    std::vector<std::vector<double>> columns;
    for (std::size_t k : cols) {
      columns.emplace_back();
      for (const Work& xi : x) columns.back().push_back(xi[k]);
    }
    coef = least_squares(columns, d);
    if (coef) {
      used = cols;
      break;
    }
  }
  // Too few differences for a line (a sparse sample of a small frame): the ratio of their time
  // to their windows' tests, a line through the origin (one coefficient, one degree of freedom
  // left from two differences).
  bool ratio = false;
  if (!coef && m < 4 && m >= 2) {
    double sum_d = 0, sum_x = 0;
    for (std::size_t i = 0; i < d.size(); ++i) sum_d += d[i], sum_x += x[i][0];
    if (sum_x > 0) {
      coef = std::vector<double>{0.0, sum_d / sum_x};
      used = {0};
      ratio = true;
    }
  }
  if (!coef) return std::nullopt;
  Work slope{};  // per test, per ray
  for (std::size_t j = 0; j < used.size(); ++j) slope[used[j]] = (*coef)[j + 1];
  const double fixed = (*coef)[0];
  auto fit = [&](const Work& w) { return fixed + slope[0] * w[0] + slope[1] * w[1]; };
  double sse = 0;
  for (std::size_t i = 0; i < d.size(); ++i) sse += (d[i] - fit(x[i])) * (d[i] - fit(x[i]));
  const double s2_e = sse / (m - static_cast<double>(used.size()) - (ratio ? 0 : 1));
  // The subsample's calibration, by whole windows: their work against their columns' (scale),
  // and how far a window's time, so predicted, strays from its exact work's (s_q).
  Work whole{}, whole_sub{};
  double whole_n = 0;
  for (const auto& w : work_)
    if (w.whole) {
      for (std::size_t k = 0; k < whole.size(); ++k) {
        whole[k] += exact(w)[k];
        whole_sub[k] += sub(w)[k];
      }
      whole_n += 1;
    }
  Work scale{};
  for (std::size_t k = 0; k < scale.size(); ++k)
    scale[k] = whole_sub[k] > 0 ? whole[k] / whole_sub[k] : 0.0;
  // A window's work from its columns, so calibrated.
  auto from_sub = [&](const functional::WindowWork& w) {
    return Work{scale[0] * w.sub_tests, scale[1] * w.sub_rays};
  };
  auto predicted = [&](const functional::WindowWork& w) {
    return w.whole ? exact(w) : from_sub(w);
  };
  double ssq = 0;
  for (const auto& w : work_)
    if (w.whole) {
      const double q = fit(exact(w)) - fit(from_sub(w));
      ssq += q * q;
    }
  const double s2_q = whole_n > 1 ? ssq / (whole_n - 1) : 0.0;
  // The population: the windows after the warm-up.
  double unsampled = 0;
  Work frame{};
  for (int w = warmup_ + 1; w < windows_; ++w) {
    const Work p = predicted(at(w));
    for (std::size_t k = 0; k < frame.size(); ++k) frame[k] += p[k];
    if (!at(w).whole) unsampled += 1;
  }
  const double R = static_cast<double>(windows_ - 1 - warmup_);
  WorkEstimate out;
  out.total = R * fixed + slope[0] * frame[0] + slope[1] * frame[1];
  // The regression's error (its residuals, with the finite-population correction) and the
  // subsample's: each unsampled window's own stray, and the calibration's on all of them.
  const double v_reg = R * R * std::max(0.0, 1.0 - m / R) * s2_e / m;
  const double v_sub = s2_q * (unsampled + unsampled * unsampled / std::max(1.0, whole_n));
  out.half = 3.0 * std::sqrt(v_reg + v_sub);
  out.json["variables"] = ratio              ? "tests (ratio: too few windows for a line)"
                          : used.size() == 2 ? "tests, rays"
                          : used[0] == 0     ? "tests"
                                             : "rays";
  out.json["window_s_fixed"] = fixed;
  out.json["s_per_test"] = slope[0];
  out.json["s_per_ray"] = slope[1];
  out.json["residual_s_sd"] = std::sqrt(s2_e);
  out.json["frame_tests"] = frame[0];
  out.json["frame_rays"] = frame[1];
  out.json["subsample_windows"] = unsampled;
  out.json["half_width_regression_s"] = 3.0 * std::sqrt(v_reg);
  out.json["half_width_subsample_s"] = 3.0 * std::sqrt(v_sub);
  // The regression's points, for a plot of time against work.
  for (std::size_t i = 0; i < d.size(); ++i)
    out.json["windows"].push_back(
        {{"window", d_window[i]}, {"time_s", d[i]}, {"tests", x[i][0]}, {"rays", x[i][1]}});
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
  // A work-weighted pilot: the run's interval at K from the pilot's residuals (the regression's
  // part, which shrinks as more windows are sampled) and its subsample's part (which does not
  // grow as K falls: fewer windows are left to the subsample).
  const auto work = pilot.find("work");
  const bool weighted = pilot.value("estimator", "") == "work" && work != pilot.end() &&
                        work->contains("residual_s_sd") && work->contains("half_width_subsample_s");
  for (int k = std::max(2, windows / kPilotWindows); k >= 2; --k) {
    const int sampled = sampled_windows(windows, k, warmup);  // after the warm-up
    if (weighted && sampled >= 5) {
      const double R = windows - 1.0 - warmup, m = sampled;
      const double s_e = work->at("residual_s_sd").get<double>();
      const double regression = 3.0 * R * s_e * std::sqrt(std::max(0.0, 1.0 / m - 1.0 / R));
      const double subsample = work->at("half_width_subsample_s").get<double>();
      if (std::hypot(regression, subsample) <= target * frame) return k;
      continue;
    }
    if (sampled >= 2 && half_width(windows - warmup, 1 + sampled, sd) <= target * frame) return k;
  }
  return 1;
}

}  // namespace rtsim::platform
