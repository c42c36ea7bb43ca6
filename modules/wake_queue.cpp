#include "modules/wake_queue.hpp"

#include <stdexcept>
#include <string>

#include "modules/sim_time.hpp"

namespace rtsim::modules {

WakeQueue::WakeQueue(const sc_core::sc_module_name& name, const sc_core::sc_event& start)
    : sc_core::sc_module(name) {
  SC_METHOD(dispatch);
  sensitive << start;  // its first run; from then it triggers itself (next_trigger)
  dont_initialize();
}

std::size_t WakeQueue::add(Client& client) {
  if (clients_.size() >= WakeHeap::kMaxClients)
    throw std::length_error(std::string(name()) + ": more than " +
                            std::to_string(WakeHeap::kMaxClients) + " clients");
  clients_.push_back(&client);
  pending_.emplace_back();
  return clients_.size() - 1;
}

void WakeQueue::wake_at(std::size_t k, const sc_core::sc_time& t) {
  const std::uint64_t now = modules::sim_now().value();
  if (t.value() < now)
    throw std::logic_error(std::string(name()) + ": a wake asked for in the past");
  if (pending_[k].seq != kNone && pending_[k].t <= t.value()) return;  // the sooner one stands
  if (seq_ >= WakeHeap::kMaxSeq)
    throw std::length_error(std::string(name()) + ": more than " +
                            std::to_string(WakeHeap::kMaxSeq) + " wakes");
  pending_[k] = {seq_, t.value()};
  heap_.push(t.value(), seq_++, static_cast<std::uint32_t>(k));
  // From outside a dispatch (a SystemC process, at SystemC's time): SystemC must run the queue
  // by then.
  if (!dispatching_ && t.value() < scheduled_) {
    scheduled_ = t.value();
    kick_.notify(from_ticks(t.value() - systemc_now().value()));
  }
}

void WakeQueue::dispatch() {
  dispatching_ = true;
  const std::uint64_t now = systemc_now().value();
  if (!started_) {
    started_ = true;
    for (std::size_t k = 0; k < clients_.size(); ++k) wake_at(k, systemc_now());
  }
  // While its clients run ahead, they see the time of their wake (sim_now); back to SystemC's
  // at the end, or if one throws.
  struct Ahead {
    sc_core::sc_time at;
    ~Ahead() { sim_time_detail::ahead = nullptr; }
  } ahead;
  std::uint64_t at = now;
  for (;;) {
    // Every client due at `at`, those woken for then by the ones that run included.
    while (!heap_.empty()) {
      const Entry e = heap_.top();
      if (stale(e)) {
        heap_.pop();
        continue;
      }
      if (e.t > at) break;
      heap_.pop();
      pending_[e.client()] = {};
      ++wakes_;
      prepare_next();
      clients_[e.client()]->woken();
    }
    // On to the next wake without SystemC when nothing else would happen before it: no other
    // process to run now and no event due until after it (events a client notified included:
    // they count from SystemC's time). The clients then run in the order SystemC would have
    // run them, one wake time after another, and SystemC's scheduling of each wake (a timed
    // notification, a delta cycle, a method's dispatch) is saved.
    while (!heap_.empty() && stale(heap_.top())) heap_.pop();
    if (heap_.empty()) break;
    const std::uint64_t next = heap_.top().t;
    // (Activity pending at the current time makes the time to it zero: one call asks both.)
    if (next - now >= sc_core::sc_time_to_pending_activity().value()) break;
    at = next;
    ahead.at = from_ticks(at);
    sim_time_detail::ahead = &ahead.at;
  }
  dispatching_ = false;
  prepare_next();
  // SystemC runs the queue again at its earliest wake (or when a process asks for one).
  kick_.cancel();
  if (heap_.empty()) {
    scheduled_ = kNone;
  } else {
    scheduled_ = heap_.top().t;
    kick_.notify(from_ticks(scheduled_ - now));
  }
  next_trigger(kick_);
}

void WakeQueue::prepare_next() {
  if (heap_.empty()) return;
  const Entry& next = heap_.top();
  if (!stale(next)) clients_[next.client()]->prepare();
}

}  // namespace rtsim::modules
