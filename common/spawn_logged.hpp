#pragma once
// Starting a child program whose output goes to a log file, and waiting for it: the runs of
// `rtsim sweep` and `rtsim validate` (platform/runs/run_queue.cpp) and the report's
// analysis scripts (app/analysis_scripts.cpp).
#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "common/spawn_signals.hpp"

extern char** environ;

namespace rtsim {

/// Starts `args` (args[0] the program, looked up on PATH when `search_path`) with no input
/// (/dev/null), its stdout and stderr written to `log` (truncated) and the interrupt signals at
/// their default. Returns its pid, or -1 with why in `error`.
inline pid_t spawn_logged(std::vector<std::string> args, const std::filesystem::path& log,
                          bool search_path, std::string& error) {
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, log.c_str(),
                                   O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_adddup2(&actions, STDOUT_FILENO, STDERR_FILENO);
  pid_t pid = 0;
  const SpawnDefaultSignals attributes;
  const int rc = search_path
                     ? posix_spawnp(&pid, argv[0], &actions, attributes.get(), argv.data(), environ)
                     : posix_spawn(&pid, argv[0], &actions, attributes.get(), argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  if (rc != 0) {
    error = std::strerror(rc);
    return -1;
  }
  return pid;
}

/// Waits for child `pid` (through interruptions); returns its wait status, or -1 with why in
/// `error`.
inline int wait_for_child(pid_t pid, std::string& error) {
  int status = 0;
  while (waitpid(pid, &status, 0) < 0) {
    if (errno != EINTR) {
      error = std::string("waitpid: ") + std::strerror(errno);
      return -1;
    }
  }
  return status;
}

/// Last `n` non-empty lines of `text`, joined with "; ": what a failed child said.
inline std::string last_lines(const std::string& text, int n) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);)
    if (!line.empty()) lines.push_back(line);
  std::string out;
  for (std::size_t i = lines.size() > static_cast<std::size_t>(n) ? lines.size() - n : 0;
       i < lines.size(); ++i)
    out += (out.empty() ? "" : "; ") + lines[i];
  return out;
}

/// The same of a child's log file: "" when it is empty or cannot be read, else ": LINES".
inline std::string last_lines_of_file(const std::filesystem::path& log, int n) {
  std::ifstream in(log, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  const std::string lines = last_lines(text.str(), n);
  return lines.empty() ? "" : ": " + lines;
}

}  // namespace rtsim
