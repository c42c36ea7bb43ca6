#pragma once
// A processor of the kit (DESIGN.md "The three layers"): a SystemC module whose thread runs a
// firmware task's handlers. The task reports what a handler cost in machine-neutral units
// (firmware/cost.hpp) and never reads a clock; the processor turns the cost into time (its clock
// and cycles per operation class, ProcessorTiming) or takes a time the machine computed, and
// accounts where its time went:
//   busy      computing (its utilisation; the busy signal of its traces),
//   waiting   for data it asked for (a packet on a bus, an answer) or for work to arrive,
//   blocked   on output: the next stage's queue had no room.
// It keeps its own local time (temporal decoupling, LocalClock) and records each computation as
// a Perfetto slice on its track and in its Busy statistic (the source of stats.json's busy time
// and the traces' busy signal alike). It is the statistics group of its name: a subclass
// declares its own counters as members (modules/statistics.hpp).
//
// Used by gaudet-pert's Shade, Shell and Prim processors, ullner-peripheral's host and vax-750's
// host; the next machines' engines and nodes are processors too.
#include <optional>
#include <string>
#include <string_view>
#include <systemc>

#include "firmware/cost.hpp"
#include "modules/activations.hpp"
#include "modules/busy_timeline.hpp"
#include "modules/local_clock.hpp"
#include "modules/prefetch.hpp"
#include "modules/processor_timing.hpp"
#include "modules/slice_sink.hpp"
#include "modules/statistics.hpp"
#include "modules/timed_fifo.hpp"

namespace rtsim::modules {

class Processor : public sc_core::sc_module, public StatGroup {
 public:
  /// Why a processor is idle.
  enum class Wait {
    kData,  ///< for data it asked for (a packet, an answer)
    kWork,  ///< for work to arrive
  };
  struct Accounts {
    sc_core::sc_time busy = sc_core::SC_ZERO_TIME;
    sc_core::sc_time waiting_for_data = sc_core::SC_ZERO_TIME;
    sc_core::sc_time waiting_for_work = sc_core::SC_ZERO_TIME;
    sc_core::sc_time blocked = sc_core::SC_ZERO_TIME;
  };

  Accounts accounts() const {
    return {busy_.total(), waiting_for_data_.value(), waiting_for_work_.value(), blocked_.value()};
  }
  /// When it computed, for utilisation windows and the traces' busy signal.
  const BusyTimeline& timeline() const { return busy_.timeline(); }
  /// Its local time (absolute).
  sc_core::sc_time now() const { return clock_.now(); }

 protected:
  /// Its reported costs become time by `timing` (set_timing; a processor that is given times
  /// needs none).
  Processor(const sc_core::sc_module_name& name, SliceSink& trace);
  /// Elaboration: how its costs become time (read from its parameters once it has its name).
  void set_timing(const ProcessorTiming& timing) { timing_ = timing; }

  /// Spends the time `c` costs computing: a slice `what` on its track.
  void compute(const Cost& c, std::string_view what,
               std::initializer_list<PerfettoTrace::Arg> args = {}) {
    compute_for(timing_.time_for(c), what, args);
  }
  /// Spends `t` computing (a time the machine worked out itself).
  void compute_for(const sc_core::sc_time& t, std::string_view what,
                   std::initializer_list<PerfettoTrace::Arg> args = {});
  /// The work it starts now is a step of item `id`'s journey (`flow`: "ray"): the traces link
  /// it to the item's slices on the links and the other processors (SliceSink::hop).
  void hop(std::string_view flow, std::uint64_t id) {
    if (traced_) trace_.hop(track_, flow, id, clock_.now());
  }
  /// Idle until `until` (if known) or until one of `events` fires, whichever comes first.
  /// A thread ahead of simulated time only catches up and returns (an event may have fired
  /// meanwhile): call it in a loop that looks at the state again.
  void idle(std::optional<sc_core::sc_time> until, const sc_core::sc_event_or_list& events,
            Wait why);
  /// idle() on one event. A list built for a single wait allocates on every call; a loop that
  /// idles once a ray keeps its lists (sc_event_or_list members or locals of its thread).
  void idle(std::optional<sc_core::sc_time> until, const sc_core::sc_event& event, Wait why);
  /// Idle until `t`, a time already known (a message stamped ahead of it).
  void idle_until(const sc_core::sc_time& t, Wait why);
  /// After waiting on events itself: the time since `since` (its local time then) was idle.
  void waited_since(const sc_core::sc_time& since, Wait why) {
    if (clock_.now() > since) account(why) += clock_.now() - since;
  }
  /// Blocked on output until `t` (a put into a full queue was accepted at t).
  void blocked_until(const sc_core::sc_time& t);

  // An event-driven processor: an SC_METHOD, a state machine that never waits (no stack of its
  // own, so a thousand of them switch as cheaply as function calls). Within an activation its
  // compute_for and idle_until only move its local time on; the activation ends asking to be
  // triggered again at its local time (resume_at_local_time) or by what it idles for
  // (idle_trigger), and the next begins with resume().
  /// Elaboration: it is an SC_METHOD.
  void make_event_driven() { clock_.never_wait(); }
  /// First thing in an activation: local time catches up with simulated time, and an idle
  /// begun by idle_trigger is accounted.
  void resume();
  /// Ends an activation that computed ahead of simulated time: triggered again at its local time.
  void resume_at_local_time();
  /// Ends an activation in an idle: triggered again at `until` (if known and later than now) or
  /// by `event`, whichever comes first; the time is accounted as `why` at resume().
  void idle_trigger(std::optional<sc_core::sc_time> until, const sc_core::sc_event& event,
                    Wait why);
  /// A processor run by a WakeQueue (modules/wake_queue.hpp) rather than by SystemC: it asks
  /// the queue for its next activation itself, and its activations are counted as those of
  /// `activation` ("activate": its name as an SC_METHOD, so both ways count under one name).
  void make_queue_driven(std::string_view activation) {
    clock_.never_wait();
    queue_activations_ = &activation_count(*this, activation);
  }
  /// Ends a queue-driven activation in an idle (its queue wakes it): the time is accounted as
  /// `why` at resume().
  void begin_idle(Wait why) { idle_since_.emplace(clock_.now(), why); }
  /// A host's wait when it can neither take an answer nor send (call it in its loop): until
  /// the next answer in `answers`, or, if it `wants_to_send`, until `out` has room, whichever
  /// comes first. Waiting for room is being blocked on output, waiting for an answer waiting
  /// for data. A full `out` frees a slot only when its consumer takes an item, a time not known
  /// yet: then the wait ends at that take too.
  template <class Answer, class Request>
  void await_answer_or_room(const TimedFifo<Answer>& answers, const TimedFifo<Request>& out,
                            bool wants_to_send) {
    std::optional<sc_core::sc_time> next = answers.next_item_time();
    const std::optional<sc_core::sc_time> room = out.next_room_time();
    if (wants_to_send && room && (!next || *room < *next) && *room > clock_.now()) {
      blocked_until(*room);
      return;
    }
    if (wants_to_send && !room) {
      idle(next, answers.put_event() | out.get_event(), Wait::kData);
      return;
    }
    if (next && *next > clock_.now()) {
      idle_until(*next, Wait::kData);
      return;
    }
    idle(std::nullopt, answers.put_event(), Wait::kData);
  }

  /// Blocked on output until `out` has room at its local time, so a put is accepted at once
  /// (back-pressure from a full queue): until a known slot frees, or until its consumer takes
  /// an item.
  template <class T>
  void wait_for_room(const TimedFifo<T>& out) {
    while (!out.has_room_by(clock_.now())) {
      // Not full: its next slot frees at a known time (later than now, or it would have room).
      if (const std::optional<sc_core::sc_time> room = out.next_room_time()) {
        blocked_until(*room);
        continue;
      }
      // Full: catch up with simulated time first, and look again before waiting, or a take made
      // meanwhile would be a notification missed.
      const sc_core::sc_time since = clock_.now();
      clock_.sync();
      if (out.full()) modules::sim_wait(out.get_event());
      clock_.resync();
      blocked_ += clock_.now() - since;
    }
  }
  const ProcessorTiming& timing() const { return timing_; }
  /// Prefetches what an activation's resume() and its first computation read (a queue-driven
  /// processor's Client::prepare, modules/wake_queue.hpp).
  void prepare_activation() const {
    prefetch_object(clock_);
    prefetch_object(idle_since_);
    prefetch_object(busy_);
  }

  LocalClock clock_;
  SliceSink& trace_;
  /// trace_.records(), asked once (it holds for the whole run): a processor's every step asks.
  const bool traced_;

 private:
  template <class Events>
  void idle_on(std::optional<sc_core::sc_time> until, const Events& events, Wait why);
  Duration& account(Wait why) { return why == Wait::kData ? waiting_for_data_ : waiting_for_work_; }
  // What every activation and computation touches first, together.
  /// An event-driven processor's idle: since when, and why (idle_trigger, resume).
  std::optional<std::pair<sc_core::sc_time, Wait>> idle_since_;
  /// A queue-driven processor's count of its activations (else resume() counts the running
  /// process's).
  std::uint64_t* queue_activations_ = nullptr;
  Busy busy_{*this, "time computing (its utilisation)"};
  Duration waiting_for_data_{*this, "waiting_for_data_s", "time idle for data it asked for"};
  Duration waiting_for_work_{*this, "waiting_for_work_s", "time idle for work to arrive"};
  Duration blocked_{*this, "blocked_s", "time blocked on output: the next queue was full"};
  ProcessorTiming timing_;
  std::string track_;  ///< its trace track: its hierarchical name
};

}  // namespace rtsim::modules
