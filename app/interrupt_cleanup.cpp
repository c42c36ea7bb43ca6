#include "app/interrupt_cleanup.hpp"

#include <pthread.h>
#include <signal.h>
#include <unistd.h>

#include <cstdlib>
#include <cstring>
#include <map>
#include <mutex>
#include <string>
#include <system_error>
#include <thread>

namespace rtsim::app {

namespace {

namespace fs = std::filesystem;

std::mutex& registry_mutex() {
  static std::mutex m;
  return m;
}

/// Registered paths by id: ids grow, so the map's reverse order is newest first.
std::map<std::uint64_t, fs::path>& registry() {
  static std::map<std::uint64_t, fs::path> paths;
  return paths;
}

std::uint64_t next_id = 1;

sigset_t interrupt_signals() {
  sigset_t set;
  sigemptyset(&set);
  sigaddset(&set, SIGINT);
  sigaddset(&set, SIGTERM);
  sigaddset(&set, SIGHUP);
  return set;
}

std::function<void(int)>& handler() {
  static std::function<void(int)> h;
  return h;
}

}  // namespace

[[noreturn]] void end_by_signal(int sig) {
  // The default action of these signals ends the process; unblocked here, raise() delivers it.
  ::signal(sig, SIG_DFL);
  sigset_t set;
  sigemptyset(&set);
  sigaddset(&set, sig);
  pthread_sigmask(SIG_UNBLOCK, &set, nullptr);
  ::raise(sig);
  std::_Exit(128 + sig);
}

namespace {

void wait_for_interrupt() {
  const sigset_t set = interrupt_signals();
  int sig = 0;
  while (sigwait(&set, &sig) != 0) {
  }
  std::function<void(int)> h;
  {
    std::lock_guard lock(registry_mutex());
    h = handler();
  }
  if (h) {
    h(sig);
    // The command ends itself; a second signal ends it now.
    while (sigwait(&set, &sig) != 0) {
    }
  }
  std::size_t removed = 0;
  {
    // Held to the end: a commit or a new registration cannot slip in between.
    std::lock_guard lock(registry_mutex());
    auto& paths = registry();
    for (auto it = paths.rbegin(); it != paths.rend(); ++it) {
      std::error_code ec;
      if (fs::remove_all(it->second, ec) > 0) ++removed;
    }
    const std::string message = std::string("\nrtsim: interrupted (") + sigabbrev_np(sig) + ")" +
                                (removed > 0 ? "; removed the run's partial outputs\n" : "\n");
    (void)!::write(STDERR_FILENO, message.data(), message.size());
    end_by_signal(sig);
  }
}

}  // namespace

void set_interrupt_handler(std::function<void(int)> h) {
  std::lock_guard lock(registry_mutex());
  handler() = std::move(h);
}

void restart_interrupt_cleanup_after_fork() {
  // The parent's threads do not exist here: this is the only thread.
  registry().clear();
  handler() = nullptr;
  std::thread(wait_for_interrupt).detach();
}

void install_interrupt_cleanup() {
  const sigset_t set = interrupt_signals();
  pthread_sigmask(SIG_BLOCK, &set, nullptr);
  // A fork while another thread holds the registry's lock would leave it locked for ever in the
  // child (a sweep's in-process point): the fork waits for the lock and both sides release it.
  pthread_atfork([] { registry_mutex().lock(); }, [] { registry_mutex().unlock(); },
                 [] { registry_mutex().unlock(); });
  std::thread(wait_for_interrupt).detach();
}

std::uint64_t remove_on_interrupt(const fs::path& path) {
  std::lock_guard lock(registry_mutex());
  const std::uint64_t id = next_id++;
  registry().emplace(id, path);
  return id;
}

std::uint64_t make_and_remove_on_interrupt(const fs::path& path,
                                           const std::function<void()>& make) {
  std::lock_guard lock(registry_mutex());
  make();
  const std::uint64_t id = next_id++;
  registry().emplace(id, path);
  return id;
}

void forget_on_interrupt(std::uint64_t id) {
  std::lock_guard lock(registry_mutex());
  registry().erase(id);
}

}  // namespace rtsim::app
