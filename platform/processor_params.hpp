#pragma once
// Parameters of a processor module (clock, cycles per operation class), declared under the
// processor's hierarchical name, e.g. host.clock, host.cycles.fp_mul.
#include <string>

#include "modules/processor_timing.hpp"
#include "platform/params/registry.hpp"

namespace rtsim::platform {

/// Defaults of a processor's parameters, with where they come from.
struct ProcessorDefaults {
  std::string clock;  ///< e.g. "5 MHz"
  int fp_add, fp_mul, fp_div, fp_sqrt, mem_word, instruction;
  std::string source;  ///< seed line or "assumption: ..."
};

void declare_processor_params(params::ParamRegistry& r, const std::string& prefix,
                              const ProcessorDefaults& d);
modules::ProcessorTiming read_processor_timing(const params::ParamRegistry& r,
                                               const std::string& prefix);

}  // namespace rtsim::platform
