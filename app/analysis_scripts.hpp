#pragma once
// The plots of a report: analysis/*.py run by Debian's /usr/bin/python3 with
// python3-matplotlib, each its own process writing a PNG into a scratch folder. If that fails
// (no Python, no matplotlib), the report is written without the plot and says why.
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

namespace rtsim::app {

/// Where the plotting tools are.
struct ReportTools {
  /// Interpreter; empty: $RTSIM_PYTHON, else /usr/bin/python3 (Debian's, where matplotlib
  /// installs) if it exists, else python3 on PATH.
  std::string python;
  /// analysis/ folder; empty: $RTSIM_ANALYSIS_DIR, else the source tree's analysis/.
  std::filesystem::path analysis_dir;
  /// Scratch folder for the PNGs (created if missing; the caller removes it).
  std::filesystem::path scratch_dir;

  /// The same with every empty field filled in as documented above.
  ReportTools resolved() const;
};

/// Result of running one analysis script.
struct ScriptResult {
  bool ok = false;
  std::string message;  ///< on failure: what went wrong (the script's last stderr lines)
};

/// Runs `python analysis_dir/script args...` with its output into scratch_dir/script.log.
ScriptResult run_analysis_script(const ReportTools& tools, const std::string& script,
                                 const std::vector<std::string>& args);

/// While one is alive, run_analysis_script does not wait for the scripts it is first asked
/// for: a report is built twice, the first pass starting every plot at once (its page thrown
/// away), the second, after collect(), waiting for each. Python's start-up and matplotlib's
/// import (about a second) are paid once, not per plot. One at a time.
class ScriptBatch {
 public:
  ScriptBatch();
  /// Waits for any script still running (an exception between the passes, say).
  ~ScriptBatch();
  ScriptBatch(const ScriptBatch&) = delete;
  ScriptBatch& operator=(const ScriptBatch&) = delete;
  /// The second pass: calls from now on wait for the scripts the first pass started.
  void collect();

 private:
  struct State;
  std::unique_ptr<State> state_;
};

}  // namespace rtsim::app
