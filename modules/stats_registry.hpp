#pragma once
// The stats registry every module reports into (after gem5's): per module, by hierarchical
// name, its busy time and named values; queues add their occupancy. Dumped into stats.json
// under "modules" with utilisation = busy time / frame time.
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <systemc>

#include "modules/busy_timeline.hpp"
#include "modules/occupancy.hpp"

namespace rtsim::modules {

struct ModuleStats {
  sc_core::sc_time busy = sc_core::SC_ZERO_TIME;
  std::map<std::string, double> values;  ///< counts and other figures, sorted by name
  bool has_occupancy = false;
  Occupancy::Summary occupancy;
  std::size_t capacity = 0;  ///< queues: depth
  /// Busy fraction per window of the frame (BusyTimeline::windows); empty values: not recorded.
  UtilizationWindows windows{};
};

/// Windows a frame is cut into for `utilization_windows`: enough to see phases (fill, steady
/// state, drain) in a plot, few enough to keep stats.json small (assumption, not a seed figure).
inline constexpr std::size_t kUtilizationWindows = 100;

class StatsRegistry {
 public:
  ModuleStats& module(const std::string& name) { return modules_[name]; }
  const std::map<std::string, ModuleStats>& modules() const { return modules_; }

  /// {name: {busy_s, utilization, ...values, queue: {capacity, mean_occupancy, max_occupancy},
  ///         utilization_windows: {begin_s, window_s, values}}}
  nlohmann::ordered_json to_json(const sc_core::sc_time& frame_time) const;

 private:
  std::map<std::string, ModuleStats> modules_;
};

/// Per-ray latencies: exact percentiles over all samples (8 bytes a ray).
class LatencyRecorder {
 public:
  void add(const sc_core::sc_time& t) { samples_.push_back(t.to_seconds()); }
  void add_seconds(double s) { samples_.push_back(s); }
  std::size_t count() const { return samples_.size(); }
  /// Nearest-rank percentile `p` in [0, 1] in seconds; 0 with no samples.
  double percentile(double p) const;
  /// {count, mean, p50, p99, max, histogram: {edges_s, counts}} (log-spaced buckets).
  nlohmann::ordered_json to_json() const;

 private:
  std::vector<double> samples_;
};

}  // namespace rtsim::modules
