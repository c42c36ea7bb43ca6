#include "platform/validation/run_queue.hpp"

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <chrono>
#include <cstring>
#include <deque>
#include <fstream>
#include <mutex>
#include <sstream>
#include <thread>

#include "common/spawn_signals.hpp"

extern char** environ;

namespace rtsim::validation {

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

RunOutcome run_request(const RunRequest& request, const RunQueueOptions& options) {
  RunOutcome out;
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
      return out;
    }
  }

  std::vector<std::string> args;
  args.push_back(options.executable.string());
  args.insert(args.end(), request.args.begin(), request.args.end());
  args.push_back("--out");
  args.push_back(out.out_dir.string());
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);

  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, out.log.c_str(),
                                   O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_adddup2(&actions, STDOUT_FILENO, STDERR_FILENO);
  posix_spawn_file_actions_addclose(&actions, STDIN_FILENO);

  const auto start = std::chrono::steady_clock::now();
  pid_t pid = 0;
  const SpawnDefaultSignals attributes;
  const int rc = posix_spawn(&pid, argv[0], &actions, attributes.get(), argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  if (rc != 0) {
    out.status = "did not start";
    out.failure = "cannot start " + args[0] + ": " + std::strerror(rc);
    return out;
  }
  int status = 0;
  while (waitpid(pid, &status, 0) < 0) {
    if (errno != EINTR) {
      out.status = "lost";
      out.failure = std::string("waitpid: ") + std::strerror(errno);
      return out;
    }
  }
  out.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  out.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  out.status = describe_status(status);

  if (!(WIFEXITED(status) && WEXITSTATUS(status) == 0)) {
    out.failure = describe_status(status) + " (log " + out.log.string() + ")";
    const std::string tail = tail_of_file(out.log, kLogLinesInFailure);
    if (!tail.empty()) out.failure += ":\n" + tail;
    return out;
  }
  const fs::path stats = out.out_dir / "stats.json";
  std::ifstream in(stats);
  if (!in) {
    out.failure = "exit status 0 but no " + stats.string();
    return out;
  }
  try {
    out.stats = nlohmann::json::parse(in);
  } catch (const nlohmann::json::exception& e) {
    out.failure = stats.string() + " is not valid JSON: " + e.what();
  }
  return out;
}

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

}  // namespace rtsim::validation
