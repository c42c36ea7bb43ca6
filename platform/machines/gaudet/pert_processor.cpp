#include "platform/machines/gaudet/pert_processor.hpp"

namespace rtsim::platform::gaudet {

namespace {
/// Where processors not given a probe record: nowhere (its rays get no journey).
RayProbe& disabled_probe() {
  static modules::LatencyProbe disabled(false);
  static RayProbe p(disabled);
  return p;
}
}  // namespace

void PertProcessor::declare_params(const modules::ParamDecls& processor,
                                   const BusInterface::IdRegisters& id_registers) {
  // An SJ16 at 5 MHz with a Weitek FPU; the per-operation costs are calibrated on Fig. 6-10
  // (docs/machines.md, docs/validation.md).
  modules::declare_processor_params(
      processor,
      {.clock = "5 MHz",
       .fp_add = 9,
       .fp_mul = 9,
       .fp_div = 15,
       .fp_sqrt = 30,
       .mem_word = 1,
       .instruction = 1,
       .source = "seed 001 L951 (5 MHz SJ16), L859 (Weitek FPU > 2.78 Mflops), L863 and L924 "
                 "(one cycle a streamed or FIFO word); cycles per FP operation calibrated on "
                 "Fig. 6-10 (L1025-L1030), same for the three processors (same hardware)"});
  BusInterface::declare_params(processor.sub("bic"), id_registers);
}

PertProcessor::PertProcessor(sc_core::sc_module_name name, const params::ParamRegistry& registry,
                             MachineTrace& trace)
    : sc_core::sc_module(name),
      params_(registry, this->name()),
      timing_(modules::read_processor_timing(params_)),
      trace_(trace),
      probe_(&disabled_probe()),
      track_(this->name()) {}

void PertProcessor::compute(const Cost& c, std::string_view what) {
  const sc_core::sc_time t = timing_.time_for(c);
  if (t == sc_core::SC_ZERO_TIME) return;
  trace_.slice(track_, what, clock_.now(), t);
  timeline_.add(clock_.now(), t);
  clock_.advance(t);
  split_.processing += t;
}

void PertProcessor::idle(std::optional<sc_core::sc_time> until,
                         const sc_core::sc_event_or_list& events, bool for_bus) {
  const sc_core::sc_time before = clock_.now();
  clock_.sync();
  const sc_core::sc_time g = sc_core::sc_time_stamp();
  // A time already reached is something the caller cannot act on yet: wait for a change.
  if (until && *until > g)
    sc_core::wait(*until - g, events);
  else
    sc_core::wait(events);
  clock_.resync();
  const sc_core::sc_time spent = clock_.now() - before;
  (for_bus ? split_.latency : split_.pipeline_wait) += spent;
}

void PertProcessor::begin_frame() {
  if (frame_start_) sc_core::wait(*frame_start_);
  clock_.resync();
}

void PertProcessor::blocked_until(const sc_core::sc_time& t) {
  if (t <= clock_.now()) return;
  split_.pipeline_wait += t - clock_.now();
  clock_.catch_up(t);
}

}  // namespace rtsim::platform::gaudet
