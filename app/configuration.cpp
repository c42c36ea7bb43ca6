#include "app/configuration.hpp"

#include "common/input_error.hpp"

namespace rtsim::app {

params::ParamRegistry build_registry(const ConfigArgs& args, const platform::Machine* machine) {
  params::ParamRegistry registry;
  platform::declare_params_of(machine, registry);
  for (const auto& file : args.config_files) registry.load_toml_file(file);
  for (const auto& assignment : args.overrides) {
    try {
      registry.apply_override(assignment);
    } catch (const InputError& e) {
      // Name the command-line argument, the -p "file" of this error.
      throw InputError("-p " + assignment, 0, e.message());
    }
  }
  registry.check_instances();
  return registry;
}

}  // namespace rtsim::app
