#pragma once
// Attributes for posix_spawn that start a child with no signals blocked and SIGINT, SIGTERM and
// SIGHUP at their default action. rtsim blocks those signals in all its threads (one thread
// waits for them: app/interrupt_cleanup.hpp); a child must not inherit that, or Ctrl-C would not
// reach it.
#include <signal.h>
#include <spawn.h>

namespace rtsim {

class SpawnDefaultSignals {
 public:
  SpawnDefaultSignals() {
    posix_spawnattr_init(&attr_);
    sigset_t none;
    sigemptyset(&none);
    posix_spawnattr_setsigmask(&attr_, &none);
    sigset_t defaults;
    sigemptyset(&defaults);
    sigaddset(&defaults, SIGINT);
    sigaddset(&defaults, SIGTERM);
    sigaddset(&defaults, SIGHUP);
    posix_spawnattr_setsigdefault(&attr_, &defaults);
    posix_spawnattr_setflags(&attr_, POSIX_SPAWN_SETSIGMASK | POSIX_SPAWN_SETSIGDEF);
  }
  ~SpawnDefaultSignals() { posix_spawnattr_destroy(&attr_); }
  SpawnDefaultSignals(const SpawnDefaultSignals&) = delete;
  SpawnDefaultSignals& operator=(const SpawnDefaultSignals&) = delete;

  const posix_spawnattr_t* get() const { return &attr_; }

 private:
  posix_spawnattr_t attr_;
};

}  // namespace rtsim
