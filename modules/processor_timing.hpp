#pragma once
// How a processor turns the cost a firmware task reports (DESIGN.md: floating-point ops, memory
// words, instructions) into time: cycles per operation class at a clock. The machines declare
// the parameters under the processor's hierarchical name (platform/processor_params.hpp).
#include <string>
#include <systemc>

#include "firmware/cost.hpp"

namespace rtsim::modules {

struct ProcessorTiming {
  sc_core::sc_time cycle = sc_core::sc_time(1, sc_core::SC_NS);
  std::uint64_t fp_add = 1, fp_mul = 1, fp_div = 1, fp_sqrt = 1, mem_word = 1, instruction = 1;

  std::uint64_t cycles_for(const Cost& c) const {
    return c.fp_add * fp_add + c.fp_mul * fp_mul + c.fp_div * fp_div + c.fp_sqrt * fp_sqrt +
           c.mem_words * mem_word + c.instructions * instruction;
  }
  sc_core::sc_time time_for(const Cost& c) const {
    return sc_core::sc_time::from_value(cycle.value() * cycles_for(c));
  }
};

}  // namespace rtsim::modules
