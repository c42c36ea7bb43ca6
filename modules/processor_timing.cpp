#include "modules/processor_timing.hpp"

#include <algorithm>
#include <cmath>

namespace rtsim::modules {

void declare_processor_params(const ParamDecls& processor, const ProcessorDefaults& d) {
  const std::string& who = processor.path();
  processor.declare({.name = "clock",
                     .kind = params::ParamKind::kFrequency,
                     .default_value = d.clock,
                     .min = "1 Hz",
                     .max = "1000 GHz",
                     .description = "Clock of the " + who + " processor",
                     .source = d.source});
  const struct {
    const char* op;
    int value;
    const char* what;
  } ops[] = {{"fp_add", d.fp_add, "floating-point addition, subtraction or comparison"},
             {"fp_mul", d.fp_mul, "floating-point multiplication"},
             {"fp_div", d.fp_div, "floating-point division"},
             {"fp_sqrt", d.fp_sqrt, "floating-point square root"},
             {"mem_word", d.mem_word, "32-bit memory word read or written"},
             {"instruction", d.instruction, "integer or control instruction"}};
  for (const auto& o : ops)
    processor.count(std::string("cycles.") + o.op, std::to_string(o.value), "0", "1000000",
                    "cycles", std::string("Cycles per ") + o.what + " on " + who, d.source);
}

ProcessorTiming read_processor_timing(const ModuleParams& processor) {
  ProcessorTiming t;
  const double hz = processor.get_frequency_hz("clock");
  // One cycle in whole picoseconds (the time resolution).
  t.cycle = sc_core::sc_time::from_value(
      static_cast<sc_core::sc_time::value_type>(std::max(1.0, std::round(1e12 / hz))));
  auto c = [&](const char* op) {
    return static_cast<std::uint64_t>(processor.get_int(std::string("cycles.") + op));
  };
  t.fp_add = c("fp_add");
  t.fp_mul = c("fp_mul");
  t.fp_div = c("fp_div");
  t.fp_sqrt = c("fp_sqrt");
  t.mem_word = c("mem_word");
  t.instruction = c("instruction");
  return t;
}

}  // namespace rtsim::modules
