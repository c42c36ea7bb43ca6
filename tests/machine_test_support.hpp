#pragma once
// Helpers for tests that call a machine directly (platform::find_machine) rather than through
// the rtsim binary: SystemC allows one simulation per process, so each simulation runs in a
// forked child; and the machine is set up as `rtsim run` sets it up.
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <exception>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "app/scene_input.hpp"
#include "platform/machine.hpp"
#include "platform/machine_registry.hpp"

namespace rtsim::test {

/// Runs `body` in a forked child and returns its exit code (the body's return value; 3 if it
/// threw, the message on stderr; -1 if the child died). A child that hangs is killed after
/// `alarm_s` seconds, so the test fails instead of stalling.
inline int run_in_child(const std::function<int()>& body, unsigned alarm_s = 120) {
  std::fflush(nullptr);
  const pid_t pid = ::fork();
  if (pid == 0) {
    ::alarm(alarm_s);
    int code = 3;
    try {
      code = body();
    } catch (const std::exception& e) {
      std::fprintf(stderr, "in child: %s\n", e.what());
    }
    std::fflush(nullptr);
    ::_exit(code);
  }
  int status = 0;
  ::waitpid(pid, &status, 0);
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

/// A machine as `rtsim run` prepares it: its parameters declared and `overrides` applied, the
/// scene loaded, the functional twin made. Held by pointer: the twin refers to the scene.
struct PreparedMachine {
  const platform::Machine* machine = nullptr;
  params::ParamRegistry registry;
  scenes::Scene scene;
  platform::FunctionalTwin twin;
};

inline std::unique_ptr<PreparedMachine> prepare_machine(
    const std::string& machine_name, const std::string& scene_name,
    const std::vector<std::string>& overrides = {}) {
  auto p = std::make_unique<PreparedMachine>();
  p->machine = &platform::find_machine(machine_name);
  platform::declare_params_of(p->machine, p->registry);
  for (const auto& o : overrides) p->registry.apply_override(o);
  p->scene = app::load_scene_with_seed(scene_name, p->registry);
  p->twin = p->machine->make_twin(p->scene, p->registry);
  return p;
}

}  // namespace rtsim::test
