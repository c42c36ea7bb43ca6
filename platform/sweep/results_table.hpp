#pragma once
// The results table of a sweep: one row per point, in point order, written as results.csv and
// results.jsonl (docs/sweeps.md lists the columns). Columns:
//   point, machine, scene, width, height       the run options (width/height as rendered)
//   <every swept parameter>                    by name, the value as written in the sweep file
//   status, exit_code, error                   "ok" or "failed", the process's exit status
//                                              (-1 for a signal), what went wrong
//   point_wall_time_s                          wall time of the point's `rtsim run` process
//   dir                                        the point's folder, relative to --out
//   <stats.json>                               headline stats first (simulated_time_s,
//                                              wall_time_s, rays.*, intersection_tests, hits,
//                                              ray_latency_s.*), then every other scalar by its
//                                              dotted path, sorted (modules.NAME.utilization...);
//                                              a class of more than 16 module instances, or of
//                                              a size that varies, by its aggregates
//                                              (module_classes.node*.utilization.mean)
//   command                                    the point's `rtsim run` command line
// The stats columns are the union over the rows; a row without a value has an empty cell (CSV)
// or null (JSON lines).
#include <nlohmann/json.hpp>
#include <set>
#include <string>
#include <string_view>
#include <vector>

#include "modules/stat_unit.hpp"
#include "platform/sweep/point_outcome.hpp"
#include "platform/sweep/sweep_file.hpp"
#include "platform/sweep/sweep_points.hpp"

namespace rtsim::sweep {

struct ResultsTable {
  std::vector<std::string> columns{};
  std::vector<std::vector<nlohmann::ordered_json>> rows{};  ///< null: no value
  /// The units the points' stats.json declare (`units`), every point's: how a stats column's
  /// numbers are shown.
  modules::UnitSchema units{};
};

/// `outcomes[i]` belongs to `points[i]`.
ResultsTable make_results_table(const SweepFile& file, const std::vector<Point>& points,
                                const std::vector<PointOutcome>& outcomes);

/// RFC 4180 CSV with a header line.
std::string to_csv(const ResultsTable& table);
/// One JSON object per line, keys in column order.
std::string to_jsonl(const ResultsTable& table);

/// A stats.json document's scalar leaves by dotted path ("modules.host.utilization"), in
/// document order: its stats columns. Arrays (histograms, windows, messages) and the keys that
/// are not stats (tool, version, command, machine, scene, width, height, params) are left out.
std::vector<std::pair<std::string, nlohmann::ordered_json>> stats_leaves(
    const nlohmann::ordered_json& stats);

/// The module classes (module_classes' names) a table of these stats.json documents keeps as
/// aggregates only: those of more than 16 instances in some document, and those whose size
/// differs between documents (node5 is another node on another array).
std::set<std::string> aggregated_classes(const std::vector<nlohmann::ordered_json>& docs);

/// The leaves a results table keeps of a stats.json document: stats_leaves, but the instances
/// of an `aggregated` class by that class's aggregates (every key's mean); of every class the
/// band of its utilisation and queue depth (min, mean, max, max_instance).
std::vector<std::pair<std::string, nlohmann::ordered_json>> table_leaves(
    const nlohmann::ordered_json& stats, const std::set<std::string>& aggregated);

/// A point's modules.csv: one row per module of stats.json (its name, its class), one column per
/// number any module reports (`queue.mean_occupancy`); the instances the results table leaves
/// out are here.
std::string modules_csv(const nlohmann::ordered_json& stats);

/// Columns that hold wall-clock measurements: the only ones that differ between two runs of the
/// same sweep (point_wall_time_s, wall_time_s, rays_per_second, functional_wall_time_s,
/// overhead_ratio).
bool is_wall_clock_column(std::string_view column);

}  // namespace rtsim::sweep
