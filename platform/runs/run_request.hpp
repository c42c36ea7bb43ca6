#pragma once
// One run of the rtsim binary and what came of it: the requests `rtsim validate` and `rtsim
// sweep` hand to the run queue (run_queue.hpp), and the command line a user would type for one.
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

namespace rtsim::runs {

/// One invocation of the rtsim binary. The runner appends `--out FOLDER`.
struct RunRequest {
  std::string key;                ///< unique in a plan; also the name of its folder
  std::vector<std::string> args;  ///< e.g. {"run", "--machine", NAME, "--scene", ...}
  /// Expected relative run time; the queue starts the biggest first so the slowest runs do not
  /// end up alone at the end.
  double cost_hint = 1.0;
  /// The command line as a user would type it (args shell-quoted where needed).
  std::string command_line() const;
};

/// What came of one run.
struct RunOutcome {
  RunRequest request;
  std::filesystem::path out_dir;  ///< the --out folder given to the run
  std::filesystem::path log;      ///< its stdout and stderr
  int exit_code = -1;             ///< -1: did not start or was killed by a signal
  /// How the process ended, in words: "exit status 2", "killed by signal Segmentation fault",
  /// "did not start".
  std::string status;
  double wall_s = 0.0;
  std::string failure;                  ///< empty on success, else what went wrong
  std::optional<nlohmann::json> stats;  ///< out_dir/stats.json, parsed, on success
};

using RunResults = std::map<std::string, RunOutcome>;

/// `s` as one word for a POSIX shell: as it is if it needs no quoting, else in single quotes
/// (a quote inside written '\'').
std::string shell_quote(const std::string& s);

}  // namespace rtsim::runs
