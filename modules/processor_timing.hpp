#pragma once
// How a processor turns the cost a firmware task reports (DESIGN.md: floating-point ops, memory
// words, instructions) into time: cycles per operation class at a clock. A processor declares
// them under its own name (`clock`, `cycles.fp_mul`: pert.shade.clock, host.cycles.fp_mul).
// Used by gaudet-pert's Shade, Shell and Prim processors and ullner-peripheral's host.
#include <string>
#include <systemc>

#include "firmware/cost.hpp"
#include "modules/module_params.hpp"
#include "modules/sim_time.hpp"

namespace rtsim::modules {

/// The values of a processor's parameters (read_processor_timing); zero until they are read:
/// the defaults are the machine preset's, where the processor declares them.
struct ProcessorTiming {
  sc_core::sc_time cycle = sc_core::SC_ZERO_TIME;
  std::uint64_t fp_add = 0, fp_mul = 0, fp_div = 0, fp_sqrt = 0, mem_word = 0, instruction = 0;

  std::uint64_t cycles_for(const Cost& c) const {
    return c.fp_add * fp_add + c.fp_mul * fp_mul + c.fp_div * fp_div + c.fp_sqrt * fp_sqrt +
           c.mem_words * mem_word + c.instructions * instruction;
  }
  sc_core::sc_time time_for(const Cost& c) const { return times(cycle, cycles_for(c)); }
};

/// A machine preset's defaults for one processor's parameters, with where they come from.
struct ProcessorDefaults {
  std::string clock;  ///< e.g. "5 MHz"
  int fp_add, fp_mul, fp_div, fp_sqrt, mem_word, instruction;
  std::string source;  ///< seed line or "assumption: ..."
};

/// Declares `clock` and `cycles.*` under the processor's path.
void declare_processor_params(const ParamDecls& processor, const ProcessorDefaults& d);
/// Reads them back for one processor instance.
ProcessorTiming read_processor_timing(const ModuleParams& processor);

}  // namespace rtsim::modules
