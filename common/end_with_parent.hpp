#pragma once
// A child forked to do part of a command's work (a sweep's point, the --sample-error pilot) must
// not outlive the command: when the parent ends, however it ends, the child gets SIGTERM (so an
// rtsim child removes its partial outputs), and ends at once if the parent is already gone.
#include <sys/prctl.h>
#include <unistd.h>

#include <csignal>

namespace rtsim {

/// Call in the child just forked from `parent` (the parent's pid, taken before the fork).
/// Async-signal-safe.
inline void end_with_parent(pid_t parent) {
  ::prctl(PR_SET_PDEATHSIG, SIGTERM);
  if (::getppid() != parent) ::_exit(128 + SIGTERM);  // the parent died before the prctl
}

}  // namespace rtsim
