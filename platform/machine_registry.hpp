#pragma once
// Where the machines are found: each registers itself in its own folder's entry file
// (platform/machines/<name>/machine.cpp), so adding a machine edits nothing outside its folder,
// its figures, its test and its docs page (docs/adding-a-machine.md):
//
//   const RegisterMachine<MyMachine> kRegistered({
//       .name = "my-machine",  // the one place its name is written
//       .description = "... (seed NNN, the lines it models)",
//       .sample_scene = "builtin:npp-412",
//       .test_runs = {"--scene builtin:npp-412", "--scene builtin:default -p host.x=2"},
//       .benchmark_runs = {...}});
//
// The platform library is linked whole into the programs (CMakeLists.txt), so no registration
// is dropped for being unreferenced.
#include <memory>
#include <string>
#include <vector>

#include "platform/machine.hpp"

namespace rtsim::platform {

/// Adds `machine` to the registry; a second machine of the same name is a programming error
/// (the program stops, naming it).
void register_machine(std::unique_ptr<Machine> machine);

/// Registers a `M` built from its MachineInfo when the program starts: one static object in the
/// machine's entry file.
template <class M>
struct RegisterMachine {
  explicit RegisterMachine(MachineInfo info) {
    register_machine(std::make_unique<M>(std::move(info)));
  }
};

/// All registered machines, by name.
const std::vector<const Machine*>& machines();
/// The machine called `name`, or null (a stats.json from a build with other machines).
const Machine* machine_named(std::string_view name);
/// The machine called `name`, or InputError naming the closest ones.
const Machine& find_machine(const std::string& name);
/// The machine whose registration says `.default_machine = true` (`rtsim run` without
/// --machine); none or two is a programming error.
const Machine& default_machine();

}  // namespace rtsim::platform
