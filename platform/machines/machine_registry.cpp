#include <algorithm>

#include "common/input_error.hpp"
#include "common/suggest.hpp"
#include "platform/machine.hpp"
#include "platform/machines/gaudet_pert.hpp"
#include "platform/machines/ullner_peripheral.hpp"
#include "platform/machines/vax750.hpp"

namespace rtsim::platform {

const std::vector<const Machine*>& machines() {
  static const Vax750 vax;
  static const UllnerPeripheral peripheral;
  static const GaudetPert pert;
  static const std::vector<const Machine*> all{&vax, &peripheral, &pert};
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
  const auto close = closest_names(name, names);
  if (!close.empty()) {
    msg += "; did you mean ";
    for (std::size_t i = 0; i < close.size(); ++i)
      msg += (i ? (i + 1 == close.size() ? " or '" : ", '") : "'") + close[i] + "'";
    msg += "?";
  }
  msg += " (`rtsim list machines` lists them)";
  throw InputError("--machine", 0, msg);
}

void declare_common_params(params::ParamRegistry& r) {
  functional::declare_render_params(r);
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
