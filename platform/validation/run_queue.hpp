#pragma once
// Runs the rtsim binary once per RunRequest, as separate processes (SystemC allows one
// simulation per process), up to `jobs` at a time. Each run gets its own folder
// WORK/KEY/ as --out and writes its stdout and stderr to WORK/KEY.log; its stats.json is read
// back when it exits with status 0.
#include <filesystem>
#include <functional>
#include <vector>

#include "platform/validation/validation.hpp"

namespace rtsim::validation {

struct RunQueueOptions {
  std::filesystem::path executable;  ///< the rtsim binary
  std::filesystem::path work_dir;    ///< parent of the run folders; created if missing
  int jobs = 1;                      ///< processes at once (at least 1)
  /// Called after each run ends, from the thread that waited for it, one call at a time.
  std::function<void(const RunOutcome&, int done, int total)> on_finished{};
};

/// Execute every request; never throws for a failed run (the outcome says what failed).
RunResults run_all(const std::vector<RunRequest>& requests, const RunQueueOptions& options);

/// Last `max_lines` lines of a text file ("" if it cannot be read).
std::string tail_of_file(const std::filesystem::path& file, int max_lines);

}  // namespace rtsim::validation
