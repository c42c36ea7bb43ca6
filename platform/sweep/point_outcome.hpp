#pragma once
// What came of one point of a sweep, whether it ran now (locally or on an MPI rank) or in an
// earlier run of the same sweep (resumed). Free of paths, so the same point gives the same
// outcome in any --out folder and on any rank.
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "platform/runs/run_request.hpp"
#include "platform/sweep/sweep_points.hpp"

namespace rtsim::sweep {

struct PointOutcome {
  bool ok = false;
  int exit_code = -1;   ///< -1: did not start or was killed by a signal
  double wall_s = 0.0;  ///< wall time of the `rtsim run` process
  /// Empty when ok; else how it ended and the last lines of its log, on one line:
  /// "exit status 2: rtsim: error: ... must be 1 or 3 ..., got 2".
  std::string error{};
  std::string stats_text{};  ///< the run's stats.json as written (ok only)
  bool reused = false;       ///< done by an earlier run of the sweep, not run now
  bool interrupted = false;  ///< the sweep was interrupted before it ended: still to run

  /// For sending between MPI ranks.
  nlohmann::json to_json() const;
  static PointOutcome from_json(const nlohmann::json& j);
};

/// From the run queue's record of a run (reads its stats.json and the tail of its log).
PointOutcome outcome_of(const runs::RunOutcome& run);

/// Name of the marker a point's folder holds once its run succeeded.
inline constexpr const char* kMarkerFile = "done.json";

/// Writes DIR/done.json (to a temporary name, then renamed): the point's hash and command
/// line, and its wall time.
void write_marker(const std::filesystem::path& dir, const Point& point, const PointOutcome& o);

/// The outcome of an earlier successful run of exactly this point in DIR: its marker holds the
/// point's hash and its stats.json reads as JSON. Otherwise nothing (the point must run).
std::optional<PointOutcome> find_done(const std::filesystem::path& dir, const Point& point);

/// Writes `text` to `path` through a temporary file and a rename.
void write_file_atomically(const std::filesystem::path& path, const std::string& text);

}  // namespace rtsim::sweep
