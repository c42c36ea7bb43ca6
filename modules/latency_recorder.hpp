#pragma once
// Per-item latencies (a ray's, a job's): exact nearest-rank percentiles over all samples, 8 bytes
// a sample, and a log-spaced histogram for plots.
// Used by every machine's ray latency (stats.json ray_latency_s) and by Distribution statistics.
#include <nlohmann/json.hpp>
#include <systemc>
#include <vector>

#include "modules/stat_unit.hpp"

namespace rtsim::modules {

class LatencyRecorder {
 public:
  void add(const sc_core::sc_time& t) { samples_.push_back(t.to_seconds()); }
  void add_seconds(double s) { samples_.push_back(s); }
  std::size_t count() const { return samples_.size(); }
  /// Nearest-rank percentile `p` in [0, 1] in seconds; 0 with no samples.
  double percentile(double p) const;
  /// {count, mean, p50, p99, max, histogram: {edges_s, counts}} (log-spaced buckets).
  nlohmann::ordered_json to_json() const;
  /// The units of to_json's keys (modules/stat_unit.hpp): seconds, but the counts.
  static UnitSchema units();

 private:
  std::vector<double> samples_;
};

}  // namespace rtsim::modules
