#include "app/analysis_scripts.hpp"

#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <map>
#include <memory>

#include "common/spawn_logged.hpp"

namespace rtsim::app {

namespace fs = std::filesystem;

ReportTools ReportTools::resolved() const {
  ReportTools t = *this;
  if (t.python.empty()) {
    if (const char* env = std::getenv("RTSIM_PYTHON"); env && *env)
      t.python = env;
    else if (fs::exists("/usr/bin/python3"))
      t.python = "/usr/bin/python3";
    else
      t.python = "python3";
  }
  if (t.analysis_dir.empty()) {
    if (const char* env = std::getenv("RTSIM_ANALYSIS_DIR"); env && *env)
      t.analysis_dir = env;
    else
      t.analysis_dir = fs::path(RTSIM_SOURCE_DIR) / "analysis";
  }
  if (t.scratch_dir.empty()) t.scratch_dir = fs::temp_directory_path() / "rtsim-report";
  return t;
}

namespace {

/// A script started and not yet waited for.
struct Launched {
  pid_t pid = -1;
  fs::path log;
  std::string python, script;
  ScriptResult failed_to_start;  ///< when pid is -1
};

Launched launch_script(const ReportTools& tools, const std::string& script,
                       const std::vector<std::string>& args) {
  Launched l;
  l.python = tools.python;
  l.script = script;
  const fs::path script_path = tools.analysis_dir / script;
  if (!fs::exists(script_path)) {
    l.failed_to_start.message = "no analysis script " + script_path.string();
    return l;
  }
  std::error_code ec;
  fs::create_directories(tools.scratch_dir, ec);
  l.log = tools.scratch_dir / (script + ".log");
  std::vector<std::string> argv = {tools.python, script_path.string()};
  argv.insert(argv.end(), args.begin(), args.end());
  std::string error;
  const pid_t pid = spawn_logged(std::move(argv), l.log, true, error);
  if (pid < 0) {
    l.failed_to_start.message = "cannot run " + tools.python + ": " + error;
    return l;
  }
  l.pid = pid;
  return l;
}

ScriptResult wait_for(const Launched& l) {
  if (l.pid < 0) return l.failed_to_start;
  ScriptResult res;
  const int status = wait_for_child(l.pid, res.message);
  if (status < 0) return res;
  if (WIFEXITED(status) && WEXITSTATUS(status) == 0) {
    res.ok = true;
    return res;
  }
  const std::string tail = last_lines_of_file(l.log, 2);  // ": LINES", or "" for no output
  // posix_spawnp reports a missing interpreter as exit status 127 from the child.
  if (WIFEXITED(status) && WEXITSTATUS(status) == 127 && tail.empty())
    res.message = "cannot run " + l.python;
  else
    res.message = l.python + " " + l.script + " failed" +
                  (WIFEXITED(status) ? " (exit status " + std::to_string(WEXITSTATUS(status)) + ")"
                                     : " (killed by a signal)") +
                  tail;
  return res;
}

/// The batch alive now (ScriptBatch): the scripts its first pass started, by script and
/// arguments.
struct BatchState {
  bool starting = true;
  std::map<std::string, Launched> launched;
};
BatchState* batch = nullptr;

}  // namespace

ScriptResult run_analysis_script(const ReportTools& tools_in, const std::string& script,
                                 const std::vector<std::string>& args) {
  const ReportTools tools = tools_in.resolved();
  std::string key = script;
  for (const auto& a : args) key += '\0' + a;
  if (batch && batch->starting) {
    batch->launched.emplace(key, launch_script(tools, script, args));
    return {false, "started"};
  }
  if (batch) {
    if (auto it = batch->launched.find(key); it != batch->launched.end()) {
      const ScriptResult r = wait_for(it->second);
      batch->launched.erase(it);
      return r;
    }
  }
  return wait_for(launch_script(tools, script, args));
}

struct ScriptBatch::State : BatchState {};

ScriptBatch::ScriptBatch() : state_(std::make_unique<State>()) { batch = state_.get(); }

ScriptBatch::~ScriptBatch() {
  batch = nullptr;
  for (const auto& [_, l] : state_->launched) (void)wait_for(l);  // none left, normally
}

void ScriptBatch::collect() { state_->starting = false; }

}  // namespace rtsim::app
