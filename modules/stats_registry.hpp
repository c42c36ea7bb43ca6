#pragma once
// The stats registry every module reports into (after gem5's): per module, by hierarchical
// name, its busy time and named values; queues add their occupancy. Dumped into stats.json
// under "modules" with utilisation = busy time / frame time.
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <systemc>

#include "modules/occupancy.hpp"

namespace rtsim::modules {

struct ModuleStats {
  sc_core::sc_time busy = sc_core::SC_ZERO_TIME;
  std::map<std::string, double> values;  ///< counts and other figures, sorted by name
  bool has_occupancy = false;
  Occupancy::Summary occupancy;
  std::size_t capacity = 0;  ///< queues: depth
};

class StatsRegistry {
 public:
  ModuleStats& module(const std::string& name) { return modules_[name]; }
  const std::map<std::string, ModuleStats>& modules() const { return modules_; }

  /// {name: {busy_s, utilization, ...values, queue: {capacity, mean_occupancy, max_occupancy}}}
  nlohmann::ordered_json to_json(const sc_core::sc_time& frame_time) const;

 private:
  std::map<std::string, ModuleStats> modules_;
};

/// Per-ray latencies: exact percentiles over all samples (8 bytes a ray).
class LatencyRecorder {
 public:
  void add(const sc_core::sc_time& t) { samples_.push_back(t.to_seconds()); }
  std::size_t count() const { return samples_.size(); }
  /// {count, mean, p50, p99, max, histogram: {edges_s, counts}} (log-spaced buckets).
  nlohmann::ordered_json to_json() const;

 private:
  std::vector<double> samples_;
};

}  // namespace rtsim::modules
