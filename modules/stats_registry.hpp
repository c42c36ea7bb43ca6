#pragma once
// The stats registry every module reports into (after gem5's): per module, by hierarchical
// name, its busy time and named values; queues add their occupancy. Dumped into stats.json
// under "modules" with utilisation = busy time / frame time.
//
// It also remembers where a module's busy time and a queue's occupancy came from (the
// BusyTimeline, the Occupancy), so the traces' busy and depth signals are drawn from the same
// objects under the same names (platform/machines/machine_trace.hpp).
// Used by every machine (MachineRun).
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <systemc>
#include <utility>
#include <vector>

#include "modules/busy_timeline.hpp"
#include "modules/link.hpp"
#include "modules/occupancy.hpp"
#include "modules/processor.hpp"

namespace rtsim::modules {

struct ModuleStats {
  sc_core::sc_time busy = sc_core::SC_ZERO_TIME;
  std::map<std::string, double> values;  ///< counts and other figures, sorted by name
  bool has_occupancy = false;
  Occupancy::Summary occupancy;
  std::size_t capacity = 0;  ///< queues: depth
  /// Busy fraction per window of the frame (BusyTimeline::windows); empty values: not recorded.
  UtilizationWindows windows{};
  /// What the busy time and the occupancy were summarised from (for traces); may be null.
  /// They must outlive the registry's use by the traces.
  const BusyTimeline* busy_source = nullptr;
  const Occupancy* occupancy_source = nullptr;
  /// Other level signals of the module for its traces, by name ("holder": a token ring's
  /// transmitting node); levels are never negative.
  std::vector<std::pair<std::string, const std::vector<LevelChange>*>> level_sources{};
};

/// Windows a frame is cut into for `utilization_windows`: enough to see phases (fill, steady
/// state, drain) in a plot, few enough to keep stats.json small (assumption, not a seed figure).
inline constexpr std::size_t kUtilizationWindows = 100;

class StatsRegistry {
 public:
  StatsRegistry() = default;
  /// The frame: occupancy means and utilisation windows are taken over [begin, end].
  StatsRegistry(const sc_core::sc_time& begin, const sc_core::sc_time& end)
      : begin_(begin), end_(end) {}

  /// A module's group: counters and figures only, unless busy_module or queue adds to it.
  ModuleStats& module(const std::string& name) { return modules_[name]; }
  /// A module that was busy `busy` in total, over the intervals of `timeline`: sets busy,
  /// utilisation windows of the frame, and the source of its trace's busy signal.
  ModuleStats& busy_module(const std::string& name, const sc_core::sc_time& busy,
                           const BusyTimeline& timeline);
  /// A kit processor: busy_module under its name, with where its other time went
  /// (`waiting_for_data_s`, `waiting_for_work_s`, `blocked_s`).
  ModuleStats& processor(const Processor& p);
  /// A kit link: busy while it carries bits, with `messages`, `bits` and `waited_s` (messages
  /// waiting for it to be free).
  ModuleStats& link(const Link& l);
  /// A queue of `capacity` entries: its occupancy over the frame, and the source of its trace's
  /// depth signal.
  ModuleStats& queue(const std::string& name, const Occupancy& occupancy, std::size_t capacity);

  const sc_core::sc_time& begin() const { return begin_; }
  const sc_core::sc_time& end() const { return end_; }
  const std::map<std::string, ModuleStats>& modules() const { return modules_; }

  /// {name: {busy_s, utilization, ...values, queue: {capacity, mean_occupancy, max_occupancy},
  ///         utilization_windows: {begin_s, window_s, values}}}
  nlohmann::ordered_json to_json(const sc_core::sc_time& frame_time) const;

 private:
  std::map<std::string, ModuleStats> modules_;
  sc_core::sc_time begin_ = sc_core::SC_ZERO_TIME;
  sc_core::sc_time end_ = sc_core::SC_ZERO_TIME;
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
