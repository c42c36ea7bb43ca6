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

PertProcessor::PertProcessor(const sc_core::sc_module_name& name, MachineRun& run, bool on_queue)
    : modules::Processor(name, run.trace()),
      params_(run.registry(), this->name()),
      probe_(&disabled_probe()) {
  set_timing(modules::read_processor_timing(params_));
  const std::string own = this->name();  // "pertK.shade"
  const std::size_t digit = own.find_first_of("0123456789");
  if (digit != std::string::npos) pert_ = std::strtoull(own.c_str() + digit, nullptr, 10);
  flow_base_ = pert_ << 32;
  // It never waits inside a computation: advanced() does.
  clock_.never_wait();
  if (!on_queue) SC_METHOD(run);
}

void PertProcessor::join(modules::WakeQueue& queue) {
  process_.join(queue, *this, *this);
  if (listen_) listen_();
}

void PertProcessor::run() { process_.resume_in_method(); }

void PertProcessor::woken() {
  wanted_ = 0;
  process_.resume_from_queue();
}

// A change it makes itself (a direct-memory request) finds it running, not waiting: SystemC
// would wake it a delta cycle later had it begun to wait on its port by then, and it would find
// nothing new, since every program looks at its port before it idles (an arrival by now is
// taken, a later one is the idle's `until`). So the queue need not wake it.
void PertProcessor::port_changed() {
  if (wanted_ & kPort) process_.run_at(modules::sim_now());
}

void PertProcessor::item_put(int, const sc_core::sc_time&) {
  if (wanted_ & kInput) process_.run_at(modules::sim_now());
}

void PertProcessor::item_taken(int) {
  if (wanted_ & kRoom) process_.run_at(modules::sim_now());
}

void PertProcessor::wake_on(std::optional<sc_core::sc_time> until, unsigned wakes) {
  if (!process_.on_queue()) {
    if (until)
      sc_core::next_trigger(*until - modules::systemc_now(), events_of(wakes));
    else
      sc_core::next_trigger(events_of(wakes));
    return;
  }
  wanted_ = wakes;
  if (until) process_.run_at(*until);
}

const sc_core::sc_event_or_list& PertProcessor::events_of(unsigned wakes) {
  std::unique_ptr<sc_core::sc_event_or_list>& list = lists_[wakes & 7u];
  if (!list) {
    list = std::make_unique<sc_core::sc_event_or_list>();
    if (wakes & kPort) *list |= *port_changed_;
    if (wakes & kInput) *list |= *input_put_;
    if (wakes & kRoom) *list |= *output_taken_;
  }
  return *list;
}

modules::Resumable PertProcessor::begin_frame() {
  // On the queue it runs first at the frame's start.
  if (frame_start_ && !process_.on_queue()) {
    process_.run_on(*frame_start_);
    co_await process_.suspend();
  }
  clock_.resync();
  // At quantum 0 only: above it, the quantum says how far the program runs ahead.
  if (sync_ == Sync::kInteractions &&
      tlm::tlm_global_quantum::instance().get() == sc_core::SC_ZERO_TIME)
    waits_ = false;
}

}  // namespace rtsim::platform::gaudet
