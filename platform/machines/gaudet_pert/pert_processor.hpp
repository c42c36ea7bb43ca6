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
// Its firmware is a program (a C++20 coroutine, modules/resumable.hpp) that the machine's event
// queue runs (process = queue), or an SC_METHOD of its own (method): written as a thread's loop,
// it waits where a thread would (co_await), without a stack of its own. Every wait is one a
// thread would make, at the same simulated time and on the same changes, so its answers are a
// thread's (the 27 gaudet-pert comparison setups, docs/benchmarks.md "stop 72").
//
// At quantum 0 it waits for simulated time to reach its local time only before it interacts
// with another module: its BIC (a request, a take, a release, a withdrawal), its queues (a look,
// a take) or the frame's progress (settle()). The computations in between cost no wait
// (pert.sync = interactions, the default: about a third fewer activations). Two rules make the
// answers those of a processor that waits after every computation as well (pert.sync =
// computations, the reference; tests/gaudet_sync_test.cpp): a message goes into the next queue
// as its sender begins writing it, stamped with its arrival (WritingAhead), so a processor that
// looks at the queue at the arrival finds it whichever process SystemC runs first; and a strobe
// still matches a request withdrawn at its very time (bus_interface.hpp).
#include <array>
#include <coroutine>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <systemc>
#include <utility>

#include "firmware/cost.hpp"
#include "modules/link.hpp"
#include "modules/module_params.hpp"
#include "modules/processor.hpp"
#include "modules/resumable.hpp"
#include "modules/resumable_process.hpp"
#include "modules/timed_fifo.hpp"
#include "modules/wake_queue.hpp"
#include "platform/machines/gaudet_pert/bus_interface.hpp"
#include "platform/machines/gaudet_pert/packet_port.hpp"
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

class PertProcessor : public modules::Processor,
                      private modules::WakeQueue::Client,
                      private PacketPort::Listener,
                      private modules::PutListener,
                      private modules::TakeListener {
 public:
  SC_HAS_PROCESS(PertProcessor);
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
  /// Elaboration: what its program waits on besides time: its bus interface (`port`), its
  /// input queue and the queue it sends into.
  template <class In, class Out>
  void wire(PacketPort& port, modules::TimedFifo<In>& input, modules::TimedFifo<Out>& output) {
    port_changed_ = &port.changed_event();
    input_put_ = &input.put_event();
    output_taken_ = &output.get_event();
    listen_ = [this, &port, &input, &output] {
      port.listen(this);
      input.listen(this, false);
      output.listen_takes(this);
    };
  }
  /// Elaboration (process = queue; made with `on_queue`): its program runs on `queue`,
  /// which starts it at the frame's start.
  void join(modules::WakeQueue& queue);
  /// When its program waits for simulated time to reach its local time (pert.sync).
  enum class Sync {
    kInteractions,  ///< only before it interacts with another module: its queues, its port
    kComputations,  ///< after every computation (the reference the other is tested against)
  };
  /// Elaboration: how its program waits (default kInteractions).
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
  /// `on_queue`: its program runs on the machine's event queue (join), not in a method.
  PertProcessor(const sc_core::sc_module_name& name, MachineRun& run, bool on_queue);

  // Its program (what a thread's loop was): a coroutine (modules/resumable.hpp) that goes on
  // where it waits, run by an SC_METHOD of its own (process = method) or by the machine's
  // event queue (queue, modules/wake_queue.hpp). Every wait below is co_awaited: it asks to be
  // run again when a thread's wait() would have woken the thread -- of SystemC (next_trigger),
  // or of the queue (wake_at, and its listeners for what SystemC events would signal) -- and the
  // program goes on there. A call that moves local time on (compute, catch_up, ...) returns a
  // Synced to co_await: the wait a thread's LocalClock::advance() would make (at quantum 0 with
  // pert.sync = computations, or a quantum ahead), or none. Synced and the waits are
  // [[nodiscard]], so a call that forgets its co_await does not compile.

  /// Elaboration (the kind's constructor): the program it runs.
  void start_program(modules::Resumable program) { process_.start(std::move(program)); }

  /// What a program waits for besides time (a mask).
  enum Wake : unsigned {
    kPort = 1,   ///< its bus interface captured a packet (PacketPort::changed_event)
    kInput = 2,  ///< a message was put into its input queue
    kRoom = 4,   ///< a message was taken from the queue it sends into
  };

  /// co_await: simulated time has reached its local time (due: else no wait at all).
  class [[nodiscard]] Synced {
   public:
    Synced(PertProcessor& p, bool due) : p_(p), due_(due) {}
    bool await_ready() const noexcept { return !due_; }
    void await_suspend(std::coroutine_handle<> h) {
      p_.process_.suspended(h);
      p_.process_.run_at(p_.clock_.now());
    }
    void await_resume() const noexcept {}

   private:
    PertProcessor& p_;
    bool due_;
  };
  /// co_await: until one of `wakes` happens (nothing accounted: the caller looks again).
  class [[nodiscard]] Until {
   public:
    Until(PertProcessor& p, unsigned wakes) : p_(p), wakes_(wakes) {}
    bool await_ready() const noexcept { return false; }
    void await_suspend(std::coroutine_handle<> h) {
      p_.process_.suspended(h);
      p_.wake_on(std::nullopt, wakes_);
    }
    void await_resume() const noexcept {}

   private:
    PertProcessor& p_;
    unsigned wakes_;
  };
  /// co_await: idle until `until` (if known) or until one of `wakes` happens, whichever comes
  /// first, accounted as `why` (and as starved if `starved`). Ahead of simulated time it only
  /// catches up (something may have happened meanwhile): the caller looks again
  /// (Processor::idle).
  class [[nodiscard]] Idle {
   public:
    Idle(PertProcessor& p, std::optional<sc_core::sc_time> until, unsigned wakes, Wait why,
         bool starved)
        : p_(p), until_(until), wakes_(wakes), why_(why), starved_(starved) {}
    bool await_ready() noexcept {
      before_ = p_.clock_.now();
      return false;
    }
    void await_suspend(std::coroutine_handle<> h) {
      p_.process_.suspended(h);
      const sc_core::sc_time g = modules::sim_now();
      if (before_ > g) {
        caught_up_only_ = true;
        p_.process_.run_at(p_.clock_.now());
        return;
      }
      // A time already reached is something the caller cannot act on yet: wait for a change.
      p_.wake_on(until_ && *until_ > g ? until_ : std::nullopt, wakes_);
    }
    void await_resume() {
      if (!caught_up_only_) {
        p_.clock_.resync();
        p_.waited_since(before_, why_);
      }
      if (starved_) p_.starved_ += p_.clock_.now() - before_;
    }

   private:
    PertProcessor& p_;
    std::optional<sc_core::sc_time> until_;
    unsigned wakes_;
    Wait why_;
    bool starved_;
    bool caught_up_only_ = false;
    sc_core::sc_time before_;
  };

  /// Waits until `until` (if known) or until one of `wakes` happens, whichever comes first.
  /// The time counts as latency if `for_bus`, else as pipeline wait.
  Idle idle(std::optional<sc_core::sc_time> until, unsigned wakes, bool for_bus) {
    return {*this, until, wakes, for_bus ? Wait::kData : Wait::kWork, false};
  }
  /// Waits as idle() does, starved: broadcast data is awaited, but the processor has room for
  /// another ray and none has come. Accounted as waiting for work, reported as `starved`.
  Idle idle_starved(std::optional<sc_core::sc_time> until, unsigned wakes) {
    return {*this, until, wakes, Wait::kWork, true};
  }
  /// Until the queue it sends into takes a message (a put into a full queue waits so).
  Until room() { return {*this, kRoom}; }
  /// Waits for the frame to start.
  modules::Resumable begin_frame();
  /// Before it touches what another process reads or writes (its port, its queues, the frame's
  /// progress): catches up with its local time, if its computations have run ahead of it.
  Synced settle() { return {*this, clock_.now() > modules::sim_now()}; }
  /// Spends the time `c` costs computing (Processor::compute).
  Synced compute(const Cost& c, std::string_view what) {
    Processor::compute(c, what);
    return advanced();
  }
  /// Idle until `t`, a time already known (Processor::idle_until).
  Synced idle_until(const sc_core::sc_time& t, Wait why) {
    Processor::idle_until(t, why);
    return advanced();
  }
  /// Blocked on output until `t` (Processor::blocked_until).
  Synced blocked_until(const sc_core::sc_time& t) {
    Processor::blocked_until(t);
    return advanced();
  }
  /// Local time moves on to `t` if later (a message taken at t).
  Synced catch_up(const sc_core::sc_time& t) {
    clock_.catch_up(t);
    return advanced();
  }
  /// While it lives, the processor's computations only move its local time on, whatever its
  /// Sync: it writes a message into the next queue (the message goes in as its sender begins
  /// writing it, stamped with its arrival, so the receiver looking at the queue then finds it
  /// whichever of the two processes SystemC runs first). The caller settles afterwards, or the
  /// loop does before its next look.
  class WritingAhead {
   public:
    explicit WritingAhead(PertProcessor& p) : p_(p), waits_(p.waits_) { p_.waits_ = false; }
    ~WritingAhead() { p_.waits_ = waits_; }
    WritingAhead(const WritingAhead&) = delete;
    WritingAhead& operator=(const WritingAhead&) = delete;

   private:
    PertProcessor& p_;
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
  Synced compute_for(RayTicket& t, Stage stage, const Cost& c, std::string_view what) {
    hop("ray", flow_base_ | t.id);
    if (t.journey == modules::LatencyProbe::kNoJourney) {
      compute_of(t, c, what);
      return advanced();
    }
    probe_->to(t, stage, RayProbe::Part::kQueueing, clock_.now());
    compute_of(t, c, what);
    probe_->to(t, stage, RayProbe::Part::kService, clock_.now());
    return advanced();
  }

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
  /// Processor::compute for ray `t`, its trace slice naming the ray and the PERT (the names are
  /// made only when a trace is written: a ray's every step comes here).
  void compute_of(const RayTicket& t, const Cost& c, std::string_view what) {
    if (traced_)
      Processor::compute(c, what, {{"ray", t.id}, {"pert", pert_}});
    else
      Processor::compute(c, what);
  }
  /// Its SC_METHOD (process = method): resumes the program where it waits.
  void run();
  /// The queue's activation (process = queue).
  void woken() override;
  void port_changed() override;
  void item_put(int port, const sc_core::sc_time& stamp) override;
  void item_taken(int port) override;
  /// A wait's end: run again at `until` (if given) or when one of `wakes` happens.
  void wake_on(std::optional<sc_core::sc_time> until, unsigned wakes);
  /// The SystemC events of `wakes`, as a list made once (process = method).
  const sc_core::sc_event_or_list& events_of(unsigned wakes);
  /// After local time moved on: the wait LocalClock::advance() makes for a thread that waits
  /// (waits_: a quantum ahead, or at every computation at quantum 0 with pert.sync =
  /// computations).
  Synced advanced() {
    const sc_core::sc_time g = modules::sim_now();
    const sc_core::sc_time local = clock_.now();
    return {*this, waits_ && local > g && local - g >= tlm::tlm_global_quantum::instance().get()};
  }
  modules::ResumableProcess process_;  ///< its program, and what runs it
  // What its waits end on: the SystemC events (method), or the queue and what tells it
  // (queue: each listener wakes it if the wait it is in wants that wake).
  const sc_core::sc_event* port_changed_ = nullptr;
  const sc_core::sc_event* input_put_ = nullptr;
  const sc_core::sc_event* output_taken_ = nullptr;
  std::array<std::unique_ptr<sc_core::sc_event_or_list>, 8> lists_;
  std::function<void()> listen_;  ///< registers it with its port and queues (join)
  unsigned wanted_ = 0;           ///< the wakes the wait it is in ends on (queue)
  /// Whether it waits as it computes (a thread's LocalClock::waits()); false at quantum 0 with
  /// pert.sync = interactions once the frame starts, and while WritingAhead.
  bool waits_ = true;
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
