#pragma once
// Helpers for tests that call a machine directly (platform::find_machine) rather than through
// the rtsim binary: SystemC allows one simulation per process, so each simulation runs in a
// forked child (run_in_child, tests/systemc_test_support.hpp); and the machine is set up as
// `rtsim run` sets it up.
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <exception>
#include <filesystem>
#include <fstream>
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

/// Runs `machine_name` on `scene_name` at `size` x `size` with `overrides` and `faults` in a
/// child, which writes the image's floats (rgb, row by row) to `out`. Returns the child's exit
/// code: 0, 2 when the run refused its input, 4 when the file could not be written.
inline int image_in_child(const std::string& machine_name, const std::string& scene_name, int size,
                          const std::vector<std::string>& overrides,
                          const std::vector<platform::MemoryFault>& faults,
                          const std::filesystem::path& out) {
  return run_in_child([&] {
    auto m = prepare_machine(machine_name, scene_name, overrides);
    platform::RunOptions opts;
    opts.width = size;
    opts.height = size;
    opts.faults = faults;
    const auto result = m->machine->run(m->scene, m->twin, m->registry, opts);
    std::ofstream f(out, std::ios::binary);
    f.write(reinterpret_cast<const char*>(result.image.rgb.data()),
            static_cast<std::streamsize>(result.image.rgb.size() * sizeof(float)));
    return f ? 0 : 4;
  });
}

}  // namespace rtsim::test
