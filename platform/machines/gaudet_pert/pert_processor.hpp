#pragma once
// What the three processors of a PERT have in common (seed 001 §5.2, L853-L863): an SJ16
// microprocessor with a Weitek floating-point unit, timed from the firmware's reported costs
// (modules::ProcessorTiming), with its own local clock (temporal decoupling).
//
// Its time splits the way Gaudet's performance model does (L1045):
//   time = (processing/ray + latency/ray + pipelinewait/ray) x rays
// processing: the processor computes; latency: it waits for broadcast data with nothing else
// to do (L825, L833); pipelinewait: it waits for the next stage's queue to take a message or for
// work from the previous stage. A fourth term, starved, is kept apart: the processor waits for
// broadcast data while it could take on another ray but none has come (a ShellProcessor with a
// free ray slot and an empty input queue). That wait is not the thesis's latency, which is
// waiting with nothing else to do (L1060-L1062): had a ray come, the processor would have worked
// on it during the wait. In the processor's accounts (modules::Processor) it is waiting for work.
//
// At quantum 0 its thread waits for simulated time to reach its local time only before it
// interacts with another module: its BIC (a request, a take, a release, a withdrawal), its
// queues (a look, a take) or the frame's progress (settle()). The computations in between cost
// no wait (pert.sync = interactions, the default: about a third fewer thread switches). Two
// rules make the answers those of a thread that waits after every computation as well
// (pert.sync = computations, the reference; tests/gaudet_sync_test.cpp): a message goes into
// the next queue as its sender begins writing it, stamped with its arrival (WritingAhead), so a
// processor that looks at the queue at the arrival finds it whichever thread SystemC runs
// first; and a strobe still matches a request withdrawn at its very time (bus_interface.hpp).
#include <optional>
#include <string>
#include <systemc>
#include <utility>

#include "firmware/cost.hpp"
#include "modules/link.hpp"
#include "modules/module_params.hpp"
#include "modules/processor.hpp"
#include "platform/machines/gaudet_pert/bus_interface.hpp"
#include "platform/machines/gaudet_pert/ray_probe.hpp"
#include "platform/machines/machine_run.hpp"
#include "platform/machines/machine_trace.hpp"

namespace rtsim::platform::gaudet {

struct TimeSplit {
  sc_core::sc_time processing = sc_core::SC_ZERO_TIME;
  sc_core::sc_time latency = sc_core::SC_ZERO_TIME;
  sc_core::sc_time pipeline_wait = sc_core::SC_ZERO_TIME;
  sc_core::sc_time starved = sc_core::SC_ZERO_TIME;
  std::uint64_t rays = 0;  ///< rays this processor finished its part of
  TimeSplit& operator+=(const TimeSplit& o) {
    processing += o.processing;
    latency += o.latency;
    pipeline_wait += o.pipeline_wait;
    starved += o.starved;
    rays += o.rays;
    return *this;
  }
};

class PertProcessor : public modules::Processor {
 public:
  /// The parameters every kind has, under `processor` ("pert.shade"): the SJ16's clock and
  /// cycles per operation (the same hardware in all three, L853-L863) and its BIC's.
  /// Its bus interface chip, under its name (and its parameters' path).
  static constexpr const char* kBic = "bic";
  static void declare_params(const modules::ParamDecls& processor,
                             const BusInterface::IdRegisters& id_registers);

  /// Its time in Gaudet's terms (L1045): processing = busy; latency = waiting for broadcast
  /// data with nothing else to do; pipeline wait = waiting for work or for room in the next
  /// stage's queue; starved = waiting for broadcast data with room for a ray that has not come
  /// (part of the accounts' waiting for work). The four add up to the accounts' total.
  TimeSplit split() const {
    const auto a = accounts();
    return {.processing = a.busy,
            .latency = a.waiting_for_data,
            .pipeline_wait = a.waiting_for_work - starved_.value() + a.blocked,
            .starved = starved_.value(),
            .rays = rays_.value()};
  }
  /// Elaboration: the event that starts the frame (the control processor's).
  void set_frame_start(const sc_core::sc_event& e) { frame_start_ = &e; }
  /// When its thread waits for simulated time to reach its local time (pert.sync).
  enum class Sync {
    kInteractions,  ///< only before it interacts with another module: its queues, its port
    kComputations,  ///< after every computation (the reference the other is tested against)
  };
  /// Elaboration: how its thread waits (default kInteractions).
  void set_sync(Sync s) { sync_ = s; }
  /// Elaboration: the --latency-probe the rays' journeys are recorded in (default: disabled).
  void set_probe(RayProbe& p) { probe_ = &p; }
  /// Elaboration: the link its messages cross to the next processor's queue (none: they arrive
  /// as soon as they are written).
  void set_output_link(modules::Link& link) {
    out_link_ = &link;
    link.trace_to(trace_);
  }

 protected:
  /// Reads its parameters under its hierarchical name ("pert0.shade").
  /// Reads its parameters under its name from the run's registry; traces to the run's trace.
  PertProcessor(const sc_core::sc_module_name& name, MachineRun& run);

  /// Waits until `until` (if known) or until one of `events` fires, whichever comes first.
  /// The time counts as latency if `for_bus`, else as pipeline wait.
  template <class Events>  // sc_core::sc_event or sc_core::sc_event_or_list
  void idle(std::optional<sc_core::sc_time> until, const Events& events, bool for_bus) {
    Processor::idle(until, events, for_bus ? Wait::kData : Wait::kWork);
  }
  /// Waits as idle() does, starved: broadcast data is awaited, but the processor has room for
  /// another ray and none has come. Accounted as waiting for work, reported as `starved`.
  template <class Events>
  void idle_starved(std::optional<sc_core::sc_time> until, const Events& events) {
    const sc_core::sc_time before = clock_.now();
    Processor::idle(until, events, Wait::kWork);
    starved_ += clock_.now() - before;
  }
  /// Waits for the frame to start.
  void begin_frame();
  /// Before it touches what another process reads or writes (its port, its queues, the frame's
  /// progress): catches up with its local time, if its computations have run ahead of it.
  void settle() { clock_.sync(); }
  /// While it lives, the processor's computations only move its local time on, whatever its
  /// Sync: it writes a message into the next queue (the message goes in as its sender begins
  /// writing it, stamped with its arrival, so the receiver looking at the queue then finds it
  /// whichever of the two threads SystemC runs first). The caller settles afterwards, or the
  /// loop does before its next look.
  class WritingAhead {
   public:
    explicit WritingAhead(PertProcessor& p) : clock_(p.clock_), waits_(p.clock_.waits()) {
      clock_.set_waits(false);
    }
    ~WritingAhead() { clock_.set_waits(waits_); }
    WritingAhead(const WritingAhead&) = delete;
    WritingAhead& operator=(const WritingAhead&) = delete;

   private:
    modules::LocalClock& clock_;
    bool waits_;
  };
  /// The statistics name of its PERT's ring queue `which` ("shade_to_shell" ->
  /// "pert0.queue.shade_to_shell"): the queue the thesis names, which the processor's input is.
  std::string ring_queue(std::string_view which) const {
    const std::string own = name();
    std::string pert = own.substr(0, own.rfind('.'));
    pert += ".queue.";
    pert += which;
    return pert;
  }
  /// compute() for ray `t` at `stage` (--latency-probe): the gap since the ray's cursor is
  /// queueing at `stage` (unless the caller attributed it otherwise first), the compute service.
  /// Traced as a step of the ray's flow (its id within the machine: its PERT's number in the
  /// high bits, its own below).
  void compute_for(RayTicket& t, Stage stage, const Cost& c, std::string_view what) {
    hop("ray", flow_base_ | t.id);
    if (t.journey == modules::LatencyProbe::kNoJourney) {
      compute(c, what, {{"ray", t.id}, {"pert", pert_}});
      return;
    }
    probe_->to(t, stage, RayProbe::Part::kQueueing, clock_.now());
    compute(c, what, {{"ray", t.id}, {"pert", pert_}});
    probe_->to(t, stage, RayProbe::Part::kService, clock_.now());
  }
  using Processor::compute_for;

  /// A message of `words` 32-bit words that the processor wrote into its output FIFO since
  /// `since` (until now) crosses the ring link: when it arrives at the next queue.
  sc_core::sc_time over_link(unsigned words, const sc_core::sc_time& since, const RayTicket& ray) {
    if (!out_link_) return clock_.now();
    return out_link_->transfer(std::uint64_t{32} * words, since, clock_.now(),
                               {"ray", "ray", ray.id, flow_base_ | ray.id});
  }
  /// How long after leaving the sender a message arrives (0 without a link).
  sc_core::sc_time link_latency() const {
    return out_link_ ? out_link_->latency() : sc_core::SC_ZERO_TIME;
  }

  modules::ModuleParams params_;  ///< its own parameters, under its name
  RayProbe* probe_;
  modules::Counter rays_{*this, "rays", "rays this processor finished its part of"};

 private:
  const sc_core::sc_event* frame_start_ = nullptr;
  Sync sync_ = Sync::kInteractions;
  modules::Link* out_link_ = nullptr;
  /// Its PERT's number ("pert3.shade": 3), and that number in the high bits of its rays' flows
  /// (a ray's id is its PERT's own count).
  std::uint64_t pert_ = 0;
  std::uint64_t flow_base_ = 0;
  modules::Duration starved_{*this, "starved_s",
                             "waiting for broadcast data with room for a ray that has not come"};
  // Gaudet's split of its time (L1045): latency is waiting for data, pipeline wait the rest of
  // its waiting but starved.
  modules::Computed latency_{*this, "latency_s", modules::StatUnit::seconds,
                             "waiting for broadcast data with nothing else to do",
                             [this] { return split().latency.to_seconds(); }};
  modules::Computed pipeline_wait_{*this, "pipeline_wait_s", modules::StatUnit::seconds,
                                   "waiting for work or for room in the next stage's queue",
                                   [this] { return split().pipeline_wait.to_seconds(); }};
};

}  // namespace rtsim::platform::gaudet
