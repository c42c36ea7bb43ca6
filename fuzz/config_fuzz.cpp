// libFuzzer target: TOML config files (`--config FILE`) layered on the parameter registries the
// command builds: the functional renderer's (`rtsim render`) and each machine's (`rtsim run`), as
// app/configuration.cpp does with platform::declare_params_of. docs/fuzzing.md.
//
// Bad input may only be refused with rtsim::InputError, and a refused file must leave the
// registry as it was (registry.hpp: "a bad file changes nothing"). Any other exception, a crash,
// a sanitizer report, a leak or a timeout is a finding.
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <string_view>
#include <vector>

#include "common/input_error.hpp"
#include "params/registry.hpp"
#include "platform/machine.hpp"
#include "platform/machine_registry.hpp"

namespace {

using rtsim::params::ParamEntry;
using rtsim::params::ParamRegistry;

/// What `rtsim list params` shows of one parameter: enough to see any change.
std::vector<std::string> snapshot(const ParamRegistry& registry) {
  std::vector<std::string> out;
  for (const ParamEntry& e : registry.list())
    out.push_back(e.name + " = " + e.value_text + " @ " + e.where_set);
  return out;
}

struct User {
  ParamRegistry registry;  ///< at its defaults, as before the --config files
  std::vector<std::string> at_defaults;
};

const std::vector<User>& users() {
  static const std::vector<User> all = [] {
    std::vector<User> out;
    std::vector<const rtsim::platform::Machine*> machines{nullptr};  // the functional renderer
    for (const auto* m : rtsim::platform::machines()) machines.push_back(m);
    for (const auto* m : machines) {
      User u;
      rtsim::platform::declare_params_of(m, u.registry);
      u.at_defaults = snapshot(u.registry);
      out.push_back(std::move(u));
    }
    return out;
  }();
  return all;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  for (const User& user : users()) {
    ParamRegistry registry = user.registry;  // a file that loads changes its copy only
    try {
      registry.load_toml_string(text, "fuzz.toml");
    } catch (const rtsim::InputError&) {
      if (snapshot(registry) != user.at_defaults) {
        std::fprintf(stderr, "fuzz: a config file that was refused changed the registry\n");
        std::abort();
      }
      continue;
    }
    try {
      registry.check_instances();  // as build_registry does after every layer
    } catch (const rtsim::InputError&) {
    }
    (void)snapshot(registry);  // every value set is written back as text (list params, stats)
  }
  return 0;
}
