#pragma once
// Sampled simulation (`rtsim run --sample K`), in the manner of SMARTS (Wunderlich et al., ISCA
// 2003: systematic sampling of detailed simulation, the rest run functionally, an estimate with
// a confidence interval). The frame's rows are cut into windows of `window_rows` rows; window 0
// and every K-th after it are simulated in detail, back to back, and the other rows are rendered
// functionally afterwards, so the image is whole and the same bytes.
//
// A machine whose work is not rows of vision rays names its own work units (pxpl5-raytrace: the
// screen regions its master hands out, in that order) and says when each is done (unit_done);
// it then renders the units not simulated in detail itself. Units that `workers` processors take
// from a queue side by side are timed by what each took: with u_i a detailed window's busy time
// (its units' sum), the frame is estimated as
//
//   T = (s_0 - B) + max(N mean(u) / P + (mean(u) / 2)(1 - 1/P), max(u)) + (E - c_{n-1})
//
// the start-up to the first unit's start s_0; the N windows' work shared by the P workers, the
// last of them started with the others half-way through theirs (but no sooner done than the
// longest window); and the drain after the last window's completion. Its half-width is
// 3 (N / P) s_u sqrt(1/n - 1/N), s_u from successive differences of the u_i in window order,
// plus (mean(u) / 2)(1 - 1/P): the last window may start anywhere from as the others end to
// with them (frame_sample.cpp).
//
// The machine tells the frame buffer of each contribution; a window's completion is the time of
// its last. Windows 1 to W right after window 0 are simulated in detail too, as a warm-up: a
// machine's queues fill at the start of the frame, and until they have the windows go faster
// than they will (ullner-pipeline on a scene of alike rows: 4% faster for its first ~512 rays).
// With c_0 the completion of the warm-up (the latest of windows 0..W), c_1 < ... < c_m those of
// the sampled windows after it (the windows kK beyond W), all in the frame [B, E] of the sampled
// run, and d_i = c_i - c_{i-1} (one window's worth of the machine's throughput, the
// windows before it having warmed the queues), the frame of all N windows is estimated as
//
//   T = (c_0 - B) + (N - 1 - W) mean(d) + (E - c_m)
//
// the start-up and warm-up (exact), the N - 1 - W windows after it at the sampled rate, and the
// drain. Its 99.7% confidence interval is T +- 3 R s_d / sqrt(m) sqrt(1 - m / R), R = N - 1 - W,
// with s_d^2 from successive differences of the d_i (frame_sample.cpp says why) and the
// finite-population correction. With W = 0 this is the estimate without a warm-up. Only the
// frame time is estimated; the other statistics are the sampled run's.
//
// Given every window's work (set_window_work: the twin's count of each window's intersection
// tests and rays, exact for the windows in detail and from a subsample of columns for the
// others), the estimate is work-weighted instead: d = a + b tests + c rays fitted by least
// squares to the sampled differences and their windows' work, T = (c_0 - B) + R a + b X_tests
// + c X_rays + (E - c_m) over the R windows after the warm-up, its interval from the residuals
// and the subsample's spread (docs/sampling.md "The work-weighted estimate"). The systematic
// estimate is the fallback where the work does not vary or there are too few differences.
#include <cstdint>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <systemc>
#include <vector>

#include "modules/stat_unit.hpp"
#include "platform/functional/window_work.hpp"

namespace rtsim::platform {

class FrameSample {
 public:
  /// `warmup`: windows after window 0 simulated in detail as a warm-up (default_warmup).
  /// Throws InputError when fewer than two windows after the warm-up would be sampled.
  FrameSample(int width, int height, int every, int window_rows, int warmup);
  /// The default warm-up: the windows after window 0 that hold `rays` vision rays (the
  /// machine's Machine::sample_warmup_rays), at most an eighth of the frame's windows.
  static int default_warmup(int width, int window_rows, int windows, int rays);
  /// `units` work units in the machine's order, `window_units` a window (what "rows" are to the
  /// constructor above; every row is the machine's then). Throws as it does.
  static FrameSample of_units(int units, int every, int window_units, const std::string& unit_name,
                              int workers = 1);

  /// Unit `unit` (of_units) is simulated in detail.
  bool detailed_unit(int unit) const { return detailed_window(unit / window_size_); }
  /// Unit `unit` was started at simulated time `start` and done at `end` (ticks).
  void unit_done(int unit, std::uint64_t start, std::uint64_t end) {
    const int w = unit / window_size_;
    done_by(w, end);
    busy_[static_cast<std::size_t>(w)] += end - start;
    first_start_ = std::min(first_start_, start);
  }

  /// One flag per row: simulated in detail, or rendered functionally afterwards (both empty
  /// with of_units: the machine renders every unit itself).
  const std::vector<char>& detailed_rows() const { return detailed_; }
  const std::vector<char>& functional_rows() const { return functional_; }

  /// A contribution to `pixel` at simulated time `ticks`.
  void contribution(std::uint32_t pixel, std::uint64_t ticks) {
    done_by(static_cast<int>(pixel / width_) / window_size_, ticks);
  }

  /// The work of every window (functional::window_work), for the work-weighted estimate;
  /// without it (or with of_units) the estimate is the systematic one.
  void set_window_work(std::vector<functional::WindowWork> work) { work_ = std::move(work); }
  /// Windows of rows: the window each completion belongs to is known (FrameSample(width, ...)).
  bool rows_sampled() const { return workers_ == 0; }
  int window_rows() const { return window_size_; }

  /// The estimate from the sampled run's frame [begin, end]: stats.json `sample`, and the
  /// estimated frame time in `estimate_s`.
  /// The units of estimate()'s keys (modules/stat_unit.hpp; stats.json `sample`).
  static modules::UnitSchema units();
  nlohmann::ordered_json estimate(const sc_core::sc_time& begin, const sc_core::sc_time& end,
                                  double& estimate_s) const;

  /// `--sample-error`: from a pilot's estimate (its stats.json `sample`), the largest K whose
  /// 99.7% half-width, by the pilot's window spread, is at most `target` of the frame time; 1
  /// (the whole frame in detail) if even K = 2 is not expected to reach it. The pilot's
  /// successive windows lie K0 apart, so its spread is, if anything, larger than a denser
  /// sample's: the choice errs towards smaller K. A work-weighted pilot (its `work`) predicts
  /// the work-weighted interval instead: its residuals' part at K, and its subsample's part.
  static int every_for(const nlohmann::ordered_json& pilot, double target);
  /// The pilot's K for a frame of `windows` windows: about kPilotWindows of them in detail (at
  /// least 3). every_for chooses no larger K.
  static constexpr int kPilotWindows = 10;
  static int pilot_every(int windows);
  /// Windows of `window_rows` rows in a frame of `height` rows.
  static int windows_in(int height, int window_rows) {
    return (height + window_rows - 1) / window_rows;
  }
  /// The half-width of the 99.7% interval of a frame of `windows` windows, `detailed` of them in
  /// detail, whose windows take `window_sd` apart (successive differences) on average. After a
  /// warm-up of W windows: a frame of windows - W windows, 1 + (sampled windows) in detail.
  static double half_width(int windows, int detailed, double window_sd);

 private:
  /// The windows in detail: the warm-up (0..W) and the sampled windows after it.
  int detailed_windows() const { return warmup_ + 1 + sampled_windows(windows_, every_, warmup_); }
  bool detailed_window(int w) const { return w <= warmup_ || w % every_ == 0; }
  /// The windows K, 2K, ... after a warm-up of `warmup` windows, below `windows`.
  static int sampled_windows(int windows, int every, int warmup) {
    return windows_in(windows, every) - (warmup / every + 1);
  }
  /// Window `w` has done work by simulated time `ticks`.
  void done_by(int w, std::uint64_t ticks) {
    auto& done = done_[static_cast<std::size_t>(w)];
    if (done < ticks) done = ticks;
  }
  FrameSample(int every, int window_size, int windows, const std::string& unit_name, int warmup);
  /// The work-weighted estimate of the windows after the warm-up: their total time and the
  /// half-width of its 99.7% interval, from the differences `d` and their windows.
  struct WorkEstimate {
    double total = 0, half = 0;
    nlohmann::ordered_json json;
  };
  std::optional<WorkEstimate> work_estimate(const std::vector<double>& d,
                                            const std::vector<int>& d_window) const;
  std::uint32_t width_ = 1;
  /// The estimate of of_units: windows shared by `workers_` processors (1 or more).
  nlohmann::ordered_json estimate_shared(double B, double E, double& estimate_s) const;
  int every_;
  int warmup_ = 0;   ///< windows 1..warmup_ in detail, not sampled
  int window_size_;  ///< rows a window, or the machine's units (of_units)
  int windows_;
  std::string unit_name_ = "rows";  ///< what a window is made of
  int workers_ = 0;  ///< of_units: processors taking units side by side (0: windows of rows)
  std::vector<std::uint64_t> busy_;  ///< by window: its units' time (unit_done)
  std::uint64_t first_start_ = UINT64_MAX;
  std::vector<char> detailed_, functional_;
  std::vector<std::uint64_t> done_;           ///< by window: its last contribution (0: none)
  std::vector<functional::WindowWork> work_;  ///< by window: set_window_work, or empty
};

}  // namespace rtsim::platform
