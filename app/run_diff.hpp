#pragma once
// `rtsim diff A B`: what differs between two runs, from their stats.json documents — the run
// (machine, scene, size), the parameters, and every statistic that changed with its relative
// change, largest first. Wall-clock numbers (which differ between any two runs) are apart.
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "modules/stat_unit.hpp"

namespace rtsim::app {

struct RunDiff {
  struct Change {
    std::string name;
    nlohmann::ordered_json a, b;  ///< null: absent on that side
    /// (b - a) / |a| for numbers; empty when a is 0, absent, or either is not a number.
    std::optional<double> relative;
  };
  std::vector<Change> run;         ///< machine, scene, width, height, spp, command
  std::vector<Change> params;      ///< by name
  std::vector<Change> stats;       ///< largest |relative| first; new, gone or non-numeric last
  std::vector<Change> wall_clock;  ///< wall_time_s, overhead_ratio, ...
  std::size_t stats_compared = 0;  ///< statistics present on either side
  /// The units the two files declare (B's first): how the numbers are shown.
  modules::UnitSchema units;
};

/// Compares two stats.json documents; numbers equal within `tolerance` relative are the same.
RunDiff diff_runs(const nlohmann::ordered_json& a, const nlohmann::ordered_json& b,
                  double tolerance = 0.0);

/// The comparison as `rtsim diff` prints it, `label_a` and `label_b` naming the two runs; at most
/// `max_stats` statistics (0: all).
std::string format_run_diff(const RunDiff& d, const std::string& label_a,
                            const std::string& label_b, std::size_t max_stats = 0);

}  // namespace rtsim::app
