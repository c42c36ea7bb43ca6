#pragma once
// Runs the rtsim binary once per RunRequest, as separate processes (SystemC allows one
// simulation per process), up to `jobs` at a time. With `in_process` set, a run is a fork of this
// process that calls it instead of a new program: no program start-up, no libraries loaded again
// (a 64 x 64 point costs a fraction of what `rtsim --version` does), and a crash still stays in
// its child. Each run gets its own folder
// WORK/KEY/ as --out and writes its stdout and stderr to WORK/KEY.log (or WORK/KEY/run.log with
// log_in_run_dir); its stats.json is read back when it exits with status 0. `rtsim validate` and
// `rtsim sweep` (locally, and one run at a time on each MPI rank) run through it.
#include <sys/types.h>

#include <filesystem>
#include <functional>
#include <vector>

#include "platform/runs/run_request.hpp"

namespace rtsim::runs {

struct RunQueueOptions {
  std::filesystem::path executable;  ///< the rtsim binary
  std::filesystem::path work_dir;    ///< parent of the run folders; created if missing
  int jobs = 1;                      ///< processes at once (at least 1)
  /// The log goes inside the run's folder (WORK/KEY/run.log) instead of beside it, so a folder
  /// holds everything about its run (rtsim sweep's point folders).
  bool log_in_run_dir = false;
  /// Called after each run ends, from the thread that waited for it, one call at a time.
  std::function<void(const RunOutcome&, int done, int total)> on_finished{};
  /// Runs a request's command line (argv[0] is `executable`) in the forked child and returns
  /// its exit status; the child's stdout and stderr go to the run's log. Empty: exec
  /// `executable`. run_all forks from its calling thread only, one child per slot.
  std::function<int(const std::vector<std::string>&)> in_process{};
  /// Runs a request's command line (argv[0] is `executable`) somewhere else with its stdout and
  /// stderr to `log`, calls `started` with the child's pid (so stop_runs can signal it) and
  /// returns its wait status, or -1 with `error`: an MPI rank's fork servers
  /// (app/fork_server.hpp). Used by run_request only; takes precedence over in_process there.
  std::function<int(const std::vector<std::string>& args, const std::filesystem::path& log,
                    const std::function<void(pid_t)>& started, std::string& error)>
      run_and_wait{};
};

/// Execute every request; never throws for a failed run (the outcome says what failed).
RunResults run_all(const std::vector<RunRequest>& requests, const RunQueueOptions& options);

/// Execute one request in this thread (jobs and on_finished are not used). The run's folder is
/// emptied first. Never throws for a failed run.
RunOutcome run_request(const RunRequest& request, const RunQueueOptions& options);

/// Forks a child that calls `run(args)` with stdout and stderr to the open file `log`, no input,
/// and the parent-death signal (it ends with this process), and exits with its status; `in_child`
/// runs first in the child. Returns the child's pid, or -1 (errno). Forks from the calling
/// thread: the run queue's in-process runs and an MPI rank's fork servers (app/fork_server.hpp).
pid_t fork_logged(int log, const std::vector<std::string>& args,
                  const std::function<int(const std::vector<std::string>&)>& run,
                  const std::function<void()>& in_child = {});

/// Stops every run queue of this process: no run starts from now on, and every running child
/// is sent `sig` (SIGTERM lets an rtsim child remove its partial outputs). run_all then returns
/// once the running ones have ended; a run never started has an outcome with status "not run".
/// Safe to call from any thread (the interrupt thread of app/interrupt_cleanup.hpp).
void stop_runs(int sig);
/// Whether stop_runs was called.
bool runs_stopped();

/// Last `max_lines` lines of a text file ("" if it cannot be read).
std::string tail_of_file(const std::filesystem::path& file, int max_lines);

}  // namespace rtsim::runs
