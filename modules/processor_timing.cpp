#include "modules/processor_timing.hpp"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <string>

namespace rtsim::modules {

namespace {
// The names, each written once: declared with the preset's defaults, read below.
constexpr const char* kClock = "clock";
constexpr const char* kOps[] = {"fp_add", "fp_mul", "fp_div", "fp_sqrt", "mem_word", "instruction"};
std::string cycles_of(const char* op) { return std::string("cycles.") + op; }
}  // namespace

void declare_processor_params(const ParamDecls& processor, const ProcessorDefaults& d) {
  const std::string& who = processor.path();
  processor.declare({.name = kClock,
                     .kind = params::ParamKind::kFrequency,
                     .default_value = d.clock,
                     .min = "1 Hz",
                     .max = "1000 GHz",
                     .description = "Clock of the " + who + " processor",
                     .source = d.source});
  // In kOps' order.
  const struct {
    int value;
    const char* what;
  } ops[] = {{d.fp_add, "floating-point addition, subtraction or comparison"},
             {d.fp_mul, "floating-point multiplication"},
             {d.fp_div, "floating-point division"},
             {d.fp_sqrt, "floating-point square root"},
             {d.mem_word, "32-bit memory word read or written"},
             {d.instruction, "integer or control instruction"}};
  for (std::size_t k = 0; k < std::size(kOps); ++k)
    processor.count(cycles_of(kOps[k]), std::to_string(ops[k].value), "0", "1000000", "cycles",
                    std::string("Cycles per ") + ops[k].what + " on " + who, d.source);
}

ProcessorTiming read_processor_timing(const ModuleParams& processor) {
  ProcessorTiming t;
  const double hz = processor.get_frequency_hz(kClock);
  // One cycle in whole picoseconds (the time resolution).
  t.cycle = sc_core::sc_time::from_value(
      static_cast<sc_core::sc_time::value_type>(std::max(1.0, std::round(1e12 / hz))));
  std::uint64_t* cycles[] = {&t.fp_add,  &t.fp_mul,   &t.fp_div,
                             &t.fp_sqrt, &t.mem_word, &t.instruction};  // kOps' order
  for (std::size_t k = 0; k < std::size(kOps); ++k)
    *cycles[k] = static_cast<std::uint64_t>(processor.get_int(cycles_of(kOps[k])));
  return t;
}

}  // namespace rtsim::modules
