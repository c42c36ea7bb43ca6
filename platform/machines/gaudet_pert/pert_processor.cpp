#include "platform/machines/gaudet_pert/pert_processor.hpp"

#include "modules/activations.hpp"

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
  BusInterface::declare_params(processor.sub(kBic), id_registers);
}

PertProcessor::PertProcessor(const sc_core::sc_module_name& name, MachineRun& run)
    : modules::Processor(name, run.trace()),
      params_(run.registry(), this->name()),
      probe_(&disabled_probe()) {
  set_timing(modules::read_processor_timing(params_));
  const std::string own = this->name();  // "pertK.shade"
  const std::size_t digit = own.find_first_of("0123456789");
  if (digit != std::string::npos) pert_ = std::strtoull(own.c_str() + digit, nullptr, 10);
  flow_base_ = pert_ << 32;
}

void PertProcessor::begin_frame() {
  if (frame_start_) modules::sim_wait(*frame_start_);
  clock_.resync();
  // At quantum 0 only: above it, the quantum says how far the thread runs ahead.
  if (sync_ == Sync::kInteractions &&
      tlm::tlm_global_quantum::instance().get() == sc_core::SC_ZERO_TIME)
    clock_.set_waits(false);
}

}  // namespace rtsim::platform::gaudet
