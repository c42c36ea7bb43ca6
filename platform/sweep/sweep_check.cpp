#include "platform/sweep/sweep_check.hpp"

#include <map>
#include <set>
#include <tuple>

#include "common/input_error.hpp"
#include "params/registry.hpp"
#include "platform/machine.hpp"
#include "platform/machine_registry.hpp"
#include "scenes/scene_loader.hpp"

namespace rtsim::sweep {

namespace {

std::string in_quotes(const std::string& s) { return "'" + s + "'"; }

}  // namespace

void check_sweep(const SweepFile& file, const std::vector<Point>& points,
                 const CheckOptions& options) {
  // One registry per machine, as `rtsim run` builds it before the -p overrides.
  std::map<std::string, params::ParamRegistry> registries;
  const auto registry_of = [&](const Setting& machine) -> params::ParamRegistry& {
    auto it = registries.find(machine.value.text);
    if (it != registries.end()) return it->second;
    const platform::Machine* m = nullptr;
    try {
      m = &platform::find_machine(machine.value.text);
    } catch (const InputError& e) {
      throw InputError(file.origin, machine.value.line, e.message());
    }
    params::ParamRegistry r;
    platform::declare_params_of(m, r);
    for (const auto& [config, line] : file.configs) r.load_toml_file(config.string());
    return registries.emplace(machine.value.text, std::move(r)).first->second;
  };

  // Each (machine, parameter, value) is checked once, in point order, so the first error
  // reported is the first a run would meet.
  std::set<std::tuple<std::string, std::string, std::string>> checked;
  // Distinct scenes in order of first use.
  std::vector<const Setting*> scene_list;
  std::set<std::string> scene_seen;
  for (const auto& p : points) {
    const Setting* machine = p.find(kMachine);
    params::ParamRegistry& registry = registry_of(*machine);
    for (const auto& s : p.settings) {
      if (is_run_option(s.name)) continue;
      if (!checked.emplace(machine->value.text, s.name, s.value.text).second) continue;
      try {
        registry.apply_override(s.name + "=" + s.value.text);
      } catch (const InputError& e) {
        // An unknown name is reported where the name is; a bad value where the value is.
        const std::size_t line = registry.contains(s.name) ? s.value.line : s.name_line;
        throw InputError(file.origin, line,
                         "on machine " + in_quotes(machine->value.text) + ": " + e.message());
      }
    }
    const Setting* scene = p.find(kScene);
    if (scene_seen.insert(scene->value.text).second) scene_list.push_back(scene);
  }

  // A plain axis names each value once, compared as values: ["1 us", "1000 ns"] would run one
  // point twice. (Its texts were compared when the file was read.)
  for (const Axis& axis : file.axes) {
    if (axis.members.size() != 1 || is_run_option(axis.members.front().name)) continue;
    const AxisMember& m = axis.members.front();
    for (auto& [machine, registry] : registries) {
      if (!registry.contains(m.name)) continue;
      std::map<std::string, const Value*> seen;
      for (const Value& v : m.values) {
        registry.apply_override(m.name + "=" + v.text);
        const auto [it, inserted] = seen.emplace(registry.value_text(m.name), &v);
        if (!inserted)
          throw InputError(file.origin, v.line,
                           "the axis of " + in_quotes(m.name) + " lists " + in_quotes(v.text) +
                               " and " + in_quotes(it->second->text) + ", one value (" + it->first +
                               ") twice");
      }
    }
  }

  if (!options.load_scenes) return;
  for (const Setting* scene : scene_list) {
    const std::string& text = scene->value.text;
    try {
      (void)scenes::load_scene(scene_argument(file, text));
    } catch (const InputError& e) {
      throw InputError(file.origin, scene->value.line,
                       "scene " + in_quotes(text) + ": " + std::string(e.what()));
    }
  }
}

}  // namespace rtsim::sweep
