#pragma once
// Helpers for tests that call a machine directly (platform::find_machine) rather than through
// the rtsim binary: SystemC allows one simulation per process, so each simulation runs in a
// forked child (run_in_child, tests/systemc_test_support.hpp); and the machine is set up as
// `rtsim run` sets it up.
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
#include "tests/systemc_test_support.hpp"

namespace rtsim::test {

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
