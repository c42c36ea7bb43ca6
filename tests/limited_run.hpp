#pragma once
// Running the rtsim binary as a hostile user's command would: its arguments passed as they are
// (no shell, so no quoting), in a folder of the test's, with a time limit and a cap on its
// address space (an allocation without bound fails inside the child instead of swamping the
// machine), and what it cost: exit status or signal, peak resident memory, wall time, output.
#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace rtsim::test {

struct LimitedRun {
  int exit_code = -1;  ///< -1: ended by a signal (`signal`) or not started
  int signal = 0;
  bool timed_out = false;  ///< killed at the time limit
  long max_rss_kib = 0;    ///< peak resident set of the child
  double wall_s = 0.0;
  std::string output;  ///< stdout and stderr together

  /// The status as a test prints it.
  std::string status() const {
    if (timed_out) return "timed out";
    if (exit_code >= 0) return "exit " + std::to_string(exit_code);
    return "signal " + std::to_string(signal);
  }
};

/// Runs rtsim-kit (rtsim with the kit's minimal machine, test_support.hpp) with `args` in `cwd`,
/// killed after `timeout_s`, its address space capped at
/// `address_space_bytes` (0: no cap). No input (/dev/null).
inline LimitedRun run_limited(const std::vector<std::string>& args,
                              const std::filesystem::path& cwd, double timeout_s,
                              std::uint64_t address_space_bytes = 0) {
  LimitedRun r;
  int fds[2];
  if (::pipe2(fds, O_CLOEXEC) != 0) return r;
  std::vector<std::string> argv_text = {RTSIM_KIT_BINARY};
  argv_text.insert(argv_text.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (auto& a : argv_text) argv.push_back(a.data());
  argv.push_back(nullptr);
  const auto start = std::chrono::steady_clock::now();
  const pid_t pid = ::fork();
  if (pid < 0) {
    ::close(fds[0]);
    ::close(fds[1]);
    return r;
  }
  if (pid == 0) {
    ::setpgid(0, 0);  // its own group: the kill at the time limit takes its children too
    if (::chdir(cwd.c_str()) != 0) ::_exit(127);
    const int in = ::open("/dev/null", O_RDONLY);
    ::dup2(in, STDIN_FILENO);
    ::dup2(fds[1], STDOUT_FILENO);
    ::dup2(fds[1], STDERR_FILENO);
    if (address_space_bytes > 0) {
      const rlimit limit{address_space_bytes, address_space_bytes};
      ::setrlimit(RLIMIT_AS, &limit);
    }
    ::execv(argv[0], argv.data());
    ::_exit(127);
  }
  ::close(fds[1]);
  const auto elapsed = [&] {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  };
  char buffer[4096];
  for (;;) {
    const double left = timeout_s - elapsed();
    if (left <= 0) {
      r.timed_out = true;
      ::kill(-pid, SIGKILL);
      ::kill(pid, SIGKILL);
      break;
    }
    pollfd p{fds[0], POLLIN, 0};
    const int ready = ::poll(&p, 1, static_cast<int>(left * 1000) + 1);
    if (ready < 0 && errno == EINTR) continue;
    if (ready <= 0) continue;
    const ssize_t n = ::read(fds[0], buffer, sizeof buffer);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) break;
    // Bounded: a run that prints without end must not fill the test's memory.
    if (r.output.size() < (1u << 20)) r.output.append(buffer, static_cast<std::size_t>(n));
  }
  ::close(fds[0]);
  int status = 0;
  rusage usage{};
  while (::wait4(pid, &status, 0, &usage) < 0 && errno == EINTR) {
  }
  r.wall_s = elapsed();
  r.max_rss_kib = usage.ru_maxrss;
  if (WIFEXITED(status)) {
    r.exit_code = WEXITSTATUS(status);
  } else if (WIFSIGNALED(status)) {
    r.signal = WTERMSIG(status);
  }
  return r;
}

}  // namespace rtsim::test
