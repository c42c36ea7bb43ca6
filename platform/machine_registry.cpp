#include "platform/machine_registry.hpp"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <set>

#include "common/input_error.hpp"
#include "common/suggest.hpp"
#include "platform/functional/render_params.hpp"
#include "platform/machines/machine_support.hpp"

namespace rtsim::platform {
namespace {

/// The machines as registered (in no particular order: static initialisation across files).
std::vector<std::unique_ptr<Machine>>& registered() {
  static std::vector<std::unique_ptr<Machine>> all;
  return all;
}

}  // namespace

void register_machine(std::unique_ptr<Machine> machine) {
  for (const auto& m : registered())
    if (m->name() == machine->name()) {
      std::fprintf(stderr, "rtsim: two machines registered as '%s'\n", machine->name().c_str());
      std::abort();
    }
  registered().push_back(std::move(machine));
}

const std::vector<const Machine*>& machines() {
  // Sorted by name: the same order whatever order the registrations ran in.
  static const std::vector<const Machine*> all = [] {
    std::vector<const Machine*> v;
    for (const auto& m : registered()) v.push_back(m.get());
    std::sort(v.begin(), v.end(),
              [](const Machine* a, const Machine* b) { return a->name() < b->name(); });
    return v;
  }();
  return all;
}

const Machine& default_machine() {
  const Machine* found = nullptr;
  for (const Machine* m : machines()) {
    if (!m->info().default_machine) continue;
    if (found)
      throw std::logic_error("two machines say they are the default: " + found->name() + " and " +
                             m->name());
    found = m;
  }
  if (!found) throw std::logic_error("no registered machine says it is the default");
  return *found;
}

const Machine* machine_named(std::string_view name) {
  for (const Machine* m : machines())
    if (m->name() == name) return m;
  return nullptr;
}

const Machine& find_machine(const std::string& name) {
  if (const Machine* m = machine_named(name)) return *m;
  std::vector<std::string> owned;
  for (const Machine* m : machines()) owned.push_back(m->name());
  const std::vector<std::string_view> names(owned.begin(), owned.end());
  std::string msg = "unknown machine '" + name + "'";
  auto close = closest_names(name, names);
  // A part of a name ("gaudet", "pipeline") is a near miss too.
  if (close.empty() && !name.empty())
    for (const auto& n : owned)
      if (n.find(name) != std::string::npos) close.push_back(n);
  if (!close.empty()) {
    msg += "; did you mean ";
    for (std::size_t i = 0; i < close.size(); ++i)
      msg += (i ? (i + 1 == close.size() ? " or '" : ", '") : "'") + close[i] + "'";
    msg += "?";
  }
  msg += " (`rtsim list machines` lists them)";
  throw InputError("--machine", 0, msg);
}

void declare_common_params(params::ParamRegistry& r, const functional::RenderParamUse& use) {
  functional::declare_render_params(r, use);
  declare_quantum_param(r);
}

}  // namespace rtsim::platform

namespace rtsim::platform {
namespace {

/// Every parameter name some user declares: the functional renderer and each machine.
const std::vector<std::string>& all_param_names() {
  static const std::vector<std::string> names = [] {
    std::set<std::string> all;
    const auto add = [&all](const params::ParamRegistry& r) {
      for (const auto& e : r.list()) all.insert(e.name);
    };
    params::ParamRegistry functional_only;
    functional::declare_render_params(functional_only);
    add(functional_only);
    for (const Machine* m : machines()) {
      params::ParamRegistry r;
      m->declare_params(r);
      add(r);
    }
    return std::vector<std::string>(all.begin(), all.end());
  }();
  return names;
}

}  // namespace

void declare_params_of(const Machine* machine, params::ParamRegistry& registry) {
  if (machine)
    machine->declare_params(registry);
  else
    functional::declare_render_params(registry);
  std::vector<std::string> elsewhere;
  for (const auto& name : all_param_names())
    if (!registry.contains(name)) elsewhere.push_back(name);
  registry.set_user(
      machine ? machine->name() : "the functional renderer",
      machine ? "rtsim list params --machine " + machine->name() : "rtsim list params",
      std::move(elsewhere));
}

}  // namespace rtsim::platform
