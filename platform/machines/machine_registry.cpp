#include <algorithm>
#include <set>

#include "common/input_error.hpp"
#include "common/suggest.hpp"
#include "platform/machine.hpp"
#include "platform/machines/gaudet_pert.hpp"
#include "platform/machines/pxpl5_raytrace.hpp"
#include "platform/machines/ullner_array.hpp"
#include "platform/machines/ullner_peripheral.hpp"
#include "platform/machines/ullner_pipeline.hpp"
#include "platform/machines/vax750.hpp"
#include "platform/machines/wang_bezier.hpp"

namespace rtsim::platform {

const std::vector<const Machine*>& machines() {
  static const Vax750 vax;
  static const UllnerPeripheral peripheral;
  static const GaudetPert pert;
  static const UllnerPipeline pipeline;
  static const UllnerArray array;
  static const WangBezier wang;
  static const Pxpl5Raytrace pxpl5;
  static const std::vector<const Machine*> all{&vax,   &peripheral, &pert, &pipeline,
                                               &array, &wang,       &pxpl5};
  return all;
}

const Machine& find_machine(const std::string& name) {
  std::vector<std::string> owned;
  for (const Machine* m : machines()) {
    if (m->name() == name) return *m;
    owned.push_back(m->name());
  }
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
  r.declare({.name = "quantum",
             .kind = params::ParamKind::kTime,
             .default_value = "0 s",
             .min = "0 s",
             .max = "1 s",
             .description = "Global TLM quantum: how far a thread may run ahead of simulated "
                            "time. 0 is the reference setting (every interaction in time "
                            "order); larger values run faster at a measured frame-time error "
                            "(docs/quantum.md)",
             .source = "assumption: TLM-2.0 loosely-timed coding style"});
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
