#include "platform/processor_params.hpp"

#include <cmath>

namespace rtsim::platform {

using modules::ProcessorTiming;

using params::ParamKind;

void declare_processor_params(params::ParamRegistry& r, const std::string& prefix,
                              const ProcessorDefaults& d) {
  r.declare({.name = prefix + ".clock",
             .kind = ParamKind::kFrequency,
             .default_value = d.clock,
             .min = "1 Hz",
             .max = "1000 GHz",
             .description = "Clock of the " + prefix + " processor",
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
    r.declare({.name = prefix + ".cycles." + o.op,
               .kind = ParamKind::kInt,
               .default_value = std::to_string(o.value),
               .min = "0",
               .max = "1000000",
               .unit = "cycles",
               .description = std::string("Cycles per ") + o.what + " on " + prefix,
               .source = d.source});
}

ProcessorTiming read_processor_timing(const params::ParamRegistry& r, const std::string& prefix) {
  ProcessorTiming t;
  const double hz = r.get_frequency_hz(prefix + ".clock");
  // One cycle in whole picoseconds (the time resolution).
  t.cycle = sc_core::sc_time::from_value(
      static_cast<sc_core::sc_time::value_type>(std::max(1.0, std::round(1e12 / hz))));
  auto c = [&](const char* op) {
    return static_cast<std::uint64_t>(r.get_int(prefix + ".cycles." + op));
  };
  t.fp_add = c("fp_add");
  t.fp_mul = c("fp_mul");
  t.fp_div = c("fp_div");
  t.fp_sqrt = c("fp_sqrt");
  t.mem_word = c("mem_word");
  t.instruction = c("instruction");
  return t;
}

}  // namespace rtsim::platform
