#include "modules/processor.hpp"

#include "modules/activations.hpp"
#include "modules/sim_time.hpp"

namespace rtsim::modules {

Processor::Processor(const sc_core::sc_module_name& name, SliceSink& trace)
    : sc_core::sc_module(name),
      StatGroup(sc_core::sc_module::name()),
      trace_(trace),
      traced_(trace.records()),
      track_(this->name()) {}

void Processor::compute_for(const sc_core::sc_time& t, std::string_view what,
                            std::initializer_list<PerfettoTrace::Arg> args) {
  if (t == sc_core::SC_ZERO_TIME) return;
  if (traced_) trace_.slice(track_, what, clock_.now(), t, args);
  busy_.record(clock_.now(), t);
  clock_.advance(t);
}

template <class Events>
void Processor::idle_on(std::optional<sc_core::sc_time> until, const Events& events, Wait why) {
  const sc_core::sc_time before = clock_.now();
  // Ahead of simulated time (a quantum > 0): catch up first and let the caller look again.
  // While this thread waited, the others ran up to its local time, and an event it would wait
  // for may have fired then (a slot freed, an item put): waiting on it now could miss it and
  // sleep until `until`, or forever.
  if (before > modules::systemc_now()) {
    clock_.sync();
    return;
  }
  const sc_core::sc_time g = modules::systemc_now();
  // A time already reached is something the caller cannot act on yet: wait for a change.
  if (until && *until > g)
    modules::sim_wait(*until - g, events);
  else
    modules::sim_wait(events);
  clock_.resync();
  account(why) += clock_.now() - before;
}

void Processor::idle(std::optional<sc_core::sc_time> until, const sc_core::sc_event_or_list& events,
                     Wait why) {
  idle_on(until, events, why);
}

void Processor::idle(std::optional<sc_core::sc_time> until, const sc_core::sc_event& event,
                     Wait why) {
  idle_on(until, event, why);
}

void Processor::idle_until(const sc_core::sc_time& t, Wait why) {
  if (t <= clock_.now()) return;
  account(why) += t - clock_.now();
  clock_.catch_up(t);
}

void Processor::blocked_until(const sc_core::sc_time& t) {
  if (t <= clock_.now()) return;
  blocked_ += t - clock_.now();
  clock_.catch_up(t);
}

void Processor::resume() {
  if (queue_activations_)
    ++*queue_activations_;
  else
    count_activation();
  clock_.resync();
  if (!idle_since_) return;
  account(idle_since_->second) += clock_.now() - idle_since_->first;
  idle_since_.reset();
}

void Processor::resume_at_local_time() {
  const sc_core::sc_time g = modules::systemc_now();
  next_trigger(clock_.now() > g ? clock_.now() - g : sc_core::SC_ZERO_TIME);
}

void Processor::idle_trigger(std::optional<sc_core::sc_time> until, const sc_core::sc_event& event,
                             Wait why) {
  const sc_core::sc_time g = modules::systemc_now();
  // Ahead of simulated time: catch up first and look again (as idle() does).
  if (clock_.now() > g) {
    resume_at_local_time();
    return;
  }
  idle_since_.emplace(clock_.now(), why);
  if (until && *until > g)
    next_trigger(*until - g, event);
  else
    next_trigger(event);
}

}  // namespace rtsim::modules
