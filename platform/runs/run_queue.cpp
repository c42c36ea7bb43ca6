#include "platform/runs/run_queue.hpp"

#include <fcntl.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <deque>
#include <fstream>
#include <iostream>
#include <map>
#include <mutex>
#include <set>
#include <sstream>
#include <thread>

#include "common/end_with_parent.hpp"
#include "common/spawn_logged.hpp"
#include "platform/sweep/stats_document.hpp"

namespace rtsim::runs {

namespace fs = std::filesystem;

std::string tail_of_file(const fs::path& file, int max_lines) {
  std::ifstream in(file);
  if (!in) return "";
  std::deque<std::string> lines;
  std::string line;
  while (std::getline(in, line)) {
    lines.push_back(line);
    if (static_cast<int>(lines.size()) > max_lines) lines.pop_front();
  }
  std::string out;
  for (const auto& l : lines) out += (out.empty() ? "" : "\n") + l;
  return out;
}

namespace {

// Lines of a failed run's log quoted in its failure message.
constexpr int kLogLinesInFailure = 5;

std::string describe_status(int status) {
  if (WIFEXITED(status)) return "exit status " + std::to_string(WEXITSTATUS(status));
  if (WIFSIGNALED(status)) return std::string("killed by signal ") + strsignal(WTERMSIG(status));
  return "unknown wait status " + std::to_string(status);
}

}  // namespace

namespace {

/// A run about to start: its outcome so far and its command line.
struct Prepared {
  RunOutcome out;
  std::vector<std::string> args;
  bool ready = false;  ///< false: it cannot start (out says why)
};

Prepared prepare(const RunRequest& request, const RunQueueOptions& options) {
  Prepared p;
  RunOutcome& out = p.out;
  out.request = request;
  out.out_dir = options.work_dir / request.key;
  out.log =
      options.log_in_run_dir ? out.out_dir / "run.log" : options.work_dir / (request.key + ".log");
  std::error_code ec;
  fs::remove_all(out.out_dir, ec);
  fs::create_directories(options.work_dir, ec);
  if (options.log_in_run_dir) {
    fs::create_directories(out.out_dir, ec);
    if (ec) {
      out.status = "did not start";
      out.failure = "cannot create " + out.out_dir.string() + ": " + ec.message();
      return p;
    }
  }
  p.args.push_back(options.executable.string());
  p.args.insert(p.args.end(), request.args.begin(), request.args.end());
  p.args.push_back("--out");
  p.args.push_back(out.out_dir.string());
  p.ready = true;
  return p;
}

/// The children running now, for stop_runs.
std::mutex running_mutex;
std::set<pid_t> running_children;
std::atomic<bool> stopped{false};
int stop_signal = SIGTERM;

void track_child(pid_t pid) {
  std::lock_guard lock(running_mutex);
  running_children.insert(pid);
  // Stopped between the caller's check and now: this one goes too.
  if (stopped.load()) ::kill(pid, stop_signal);
}

void untrack_child(pid_t pid) {
  std::lock_guard lock(running_mutex);
  running_children.erase(pid);
}

/// The outcome of a run that stop_runs kept from starting.
RunOutcome not_run(const RunRequest& request) {
  RunOutcome out;
  out.request = request;
  out.status = "not run";
  out.failure = "not run: the queue was stopped";
  return out;
}

/// Starts the program `args` as spawn_logged does (no input, its output to `log`, the interrupt
/// signals at their default), and with the parent-death signal, which posix_spawn cannot set:
/// the program ends (SIGTERM: removing its partial outputs) when this process does, however
/// it ends. Returns its pid, or -1 with why in `error` (an exec that failed included).
pid_t start_program(std::vector<std::string> args, const fs::path& log, std::string& error) {
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  const int out = ::open(log.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (out < 0) {
    error = "cannot write " + log.string() + ": " + std::strerror(errno);
    return -1;
  }
  int exec_failed[2];  // the child writes errno here if exec fails; closed by a good exec
  if (::pipe2(exec_failed, O_CLOEXEC) != 0) {
    error = std::string("pipe: ") + std::strerror(errno);
    ::close(out);
    return -1;
  }
  const pid_t parent = ::getpid();
  const pid_t pid = ::fork();
  if (pid == 0) {
    // Only async-signal-safe calls between fork and exec.
    end_with_parent(parent);
    sigset_t none;
    sigemptyset(&none);
    ::pthread_sigmask(SIG_SETMASK, &none, nullptr);
    for (const int sig : {SIGINT, SIGTERM, SIGHUP}) ::signal(sig, SIG_DFL);
    const int null = ::open("/dev/null", O_RDONLY);
    if (null >= 0) ::dup2(null, STDIN_FILENO);
    ::dup2(out, STDOUT_FILENO);
    ::dup2(out, STDERR_FILENO);
    ::execv(argv[0], argv.data());
    const int e = errno;
    (void)!::write(exec_failed[1], &e, sizeof e);
    ::_exit(127);
  }
  ::close(out);
  ::close(exec_failed[1]);
  if (pid < 0) {
    error = std::string("fork: ") + std::strerror(errno);
    ::close(exec_failed[0]);
    return -1;
  }
  int e = 0;
  const ssize_t n = ::read(exec_failed[0], &e, sizeof e);
  ::close(exec_failed[0]);
  if (n == static_cast<ssize_t>(sizeof e)) {
    std::string ignored;
    (void)wait_for_child(pid, ignored);
    error = std::strerror(e);
    return -1;
  }
  return pid;
}

}  // namespace

pid_t fork_logged(int log, const std::vector<std::string>& args,
                  const std::function<int(const std::vector<std::string>&)>& run,
                  const std::function<void()>& in_child) {
  std::cout.flush();
  std::cerr.flush();
  std::fflush(nullptr);
  const pid_t parent = ::getpid();
  const pid_t pid = ::fork();
  if (pid != 0) return pid;
  // The child: its own output, no input, the run's signals at their default; it ends when the
  // run does, and with its parent.
  end_with_parent(parent);
  if (in_child) in_child();
  ::dup2(log, STDOUT_FILENO);
  ::dup2(log, STDERR_FILENO);
  const int null = ::open("/dev/null", O_RDONLY);
  if (null >= 0) ::dup2(null, STDIN_FILENO);
  int code = 70;  // EX_SOFTWARE
  try {
    code = run(args);
  } catch (...) {
  }
  std::cout.flush();
  std::cerr.flush();
  std::fflush(nullptr);
  std::_Exit(code);
}

namespace {

/// Starts the run: a new program, or a fork of this process calling options.in_process.
/// Returns the child's pid, or -1 with the outcome saying why it did not start.
pid_t start(Prepared& p, const RunQueueOptions& options) {
  if (options.in_process) {
    const int log = ::open(p.out.log.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
    if (log < 0) {
      p.out.status = "did not start";
      p.out.failure = "cannot write " + p.out.log.string() + ": " + std::strerror(errno);
      return -1;
    }
    const pid_t pid = fork_logged(log, p.args, options.in_process);
    ::close(log);
    if (pid < 0) {
      p.out.status = "did not start";
      p.out.failure = std::string("fork: ") + std::strerror(errno);
    }
    return pid;
  }
  std::string error;
  const pid_t pid = start_program(p.args, p.out.log, error);
  if (pid < 0) {
    p.out.status = "did not start";
    p.out.failure = "cannot start " + p.args[0] + ": " + error;
  }
  return pid;
}

/// The outcome of a run that ended with wait status `status` after `wall_s`.
RunOutcome finish(RunOutcome out, int status, double wall_s) {
  out.wall_s = wall_s;
  out.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  out.status = describe_status(status);
  if (!(WIFEXITED(status) && WEXITSTATUS(status) == 0)) {
    out.failure = describe_status(status) + " (log " + out.log.string() + ")";
    const std::string tail = tail_of_file(out.log, kLogLinesInFailure);
    if (!tail.empty()) out.failure += ":\n" + tail;
    return out;
  }
  const fs::path stats = out.out_dir / "stats.json";
  std::ifstream in(stats, std::ios::binary);
  if (!in) {
    out.failure = "exit status 0 but no " + stats.string();
    return out;
  }
  std::ostringstream text;
  text << in.rdbuf();
  if (const std::string problem = sweep::stats_json_problem(text.str()); !problem.empty()) {
    out.failure = stats.string() + " is not a stats.json: " + problem;
    return out;
  }
  out.stats = nlohmann::json::parse(text.str());
  return out;
}

double seconds_since(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

}  // namespace

void stop_runs(int sig) {
  std::lock_guard lock(running_mutex);
  stop_signal = sig;
  stopped.store(true);
  for (const pid_t pid : running_children) ::kill(pid, sig);
}

bool runs_stopped() { return stopped.load(); }

RunOutcome run_request(const RunRequest& request, const RunQueueOptions& options) {
  if (stopped.load()) return not_run(request);
  Prepared p = prepare(request, options);
  if (!p.ready) return p.out;
  const auto began = std::chrono::steady_clock::now();
  if (options.run_and_wait) {
    pid_t child = -1;
    std::string error;
    const int status = options.run_and_wait(
        p.args, p.out.log,
        [&child](pid_t pid) {
          child = pid;
          track_child(pid);
        },
        error);
    if (child > 0) untrack_child(child);
    if (status < 0) {
      p.out.status = child > 0 ? "lost" : "did not start";
      p.out.failure = error;
      return p.out;
    }
    return finish(std::move(p.out), status, seconds_since(began));
  }
  const pid_t pid = start(p, options);
  if (pid < 0) return p.out;
  track_child(pid);
  std::string error;
  const int status = wait_for_child(pid, error);
  untrack_child(pid);
  if (status < 0) {
    p.out.status = "lost";
    p.out.failure = error;
    return p.out;
  }
  return finish(std::move(p.out), status, seconds_since(began));
}

namespace {

/// run_all with in_process: this thread forks every child (fork copies only the calling thread,
/// so no worker threads may exist) and waits for whichever ends first.
void run_forked(const std::vector<RunRequest>& requests, const std::vector<std::size_t>& order,
                int workers, const RunQueueOptions& options, std::vector<RunOutcome>& outcomes) {
  struct Running {
    std::size_t index;
    RunOutcome out;
    std::chrono::steady_clock::time_point began;
  };
  std::map<pid_t, Running> running;
  std::size_t next = 0;
  int done = 0;
  const int total = static_cast<int>(requests.size());
  const auto report = [&](std::size_t i) {
    ++done;
    if (options.on_finished) options.on_finished(outcomes[i], done, total);
  };
  while (next < order.size() || !running.empty()) {
    while (next < order.size() && static_cast<int>(running.size()) < workers) {
      const std::size_t i = order[next++];
      if (stopped.load()) {
        outcomes[i] = not_run(requests[i]);
        continue;  // not reported: it did not run
      }
      Prepared p = prepare(requests[i], options);
      const auto began = std::chrono::steady_clock::now();
      const pid_t pid = p.ready ? start(p, options) : -1;
      if (pid < 0) {
        outcomes[i] = std::move(p.out);
        report(i);
        continue;
      }
      track_child(pid);
      running.emplace(pid, Running{i, std::move(p.out), began});
    }
    if (running.empty()) continue;
    int status = 0;
    const pid_t pid = waitpid(-1, &status, 0);
    if (pid < 0) {
      if (errno == EINTR) continue;
      // No children left to wait for: every running one is lost.
      for (auto& [_, r] : running) {
        r.out.status = "lost";
        r.out.failure = std::string("waitpid: ") + std::strerror(errno);
        outcomes[r.index] = std::move(r.out);
        report(r.index);
      }
      running.clear();
      continue;
    }
    const auto it = running.find(pid);
    if (it == running.end()) continue;  // not one of ours
    untrack_child(pid);
    outcomes[it->second.index] =
        finish(std::move(it->second.out), status, seconds_since(it->second.began));
    const std::size_t i = it->second.index;
    running.erase(it);
    report(i);
  }
}

}  // namespace

RunResults run_all(const std::vector<RunRequest>& requests, const RunQueueOptions& options) {
  fs::create_directories(options.work_dir);
  const int total = static_cast<int>(requests.size());
  const int workers = std::clamp(options.jobs, 1, std::max(1, total));
  std::vector<RunOutcome> outcomes(requests.size());
  // Biggest first (longest-processing-time order); ties keep the plan's order.
  std::vector<std::size_t> order(requests.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return requests[a].cost_hint > requests[b].cost_hint;
  });
  if (options.in_process) {
    run_forked(requests, order, workers, options, outcomes);
    RunResults results;
    for (auto& o : outcomes) results.emplace(o.request.key, std::move(o));
    return results;
  }
  std::atomic<std::size_t> next{0};
  std::mutex report;
  int done = 0;

  auto worker = [&] {
    for (;;) {
      const std::size_t n = next.fetch_add(1);
      if (n >= order.size()) return;
      const std::size_t i = order[n];
      outcomes[i] = run_request(requests[i], options);
      std::lock_guard lock(report);
      ++done;
      if (options.on_finished) options.on_finished(outcomes[i], done, total);
    }
  };
  {
    std::vector<std::jthread> pool;
    for (int w = 0; w < workers; ++w) pool.emplace_back(worker);
  }
  RunResults results;
  for (auto& o : outcomes) results.emplace(o.request.key, std::move(o));
  return results;
}

}  // namespace rtsim::runs
