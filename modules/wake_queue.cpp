#include "modules/wake_queue.hpp"

#include <stdexcept>

#include "modules/sim_time.hpp"

namespace rtsim::modules {

WakeQueue::WakeQueue(const sc_core::sc_module_name& name, const sc_core::sc_event& start)
    : sc_core::sc_module(name) {
  SC_METHOD(dispatch);
  sensitive << start;  // its first run; from then it triggers itself (next_trigger)
  dont_initialize();
}

std::size_t WakeQueue::add(Client& client) {
  clients_.push_back(&client);
  pending_.emplace_back();
  return clients_.size() - 1;
}

void WakeQueue::wake_at(std::size_t k, const sc_core::sc_time& t) {
  const std::uint64_t now = modules::sim_now().value();
  if (t.value() < now)
    throw std::logic_error(std::string(name()) + ": a wake asked for in the past");
  if (pending_[k].seq != kNone && pending_[k].t <= t.value()) return;  // the sooner one stands
  pending_[k] = {seq_, t.value()};
  heap_.push({t.value(), seq_++, static_cast<std::uint32_t>(k)});
  // From outside a dispatch (a SystemC process): SystemC must run the queue by then.
  if (!dispatching_ && t.value() < scheduled_) {
    scheduled_ = t.value();
    kick_.notify(from_ticks(t.value() - now));
  }
}

void WakeQueue::dispatch() {
  dispatching_ = true;
  const std::uint64_t now = modules::sim_now().value();
  if (!started_) {
    started_ = true;
    for (std::size_t k = 0; k < clients_.size(); ++k) wake_at(k, modules::sim_now());
  }
  // Every client due now, those woken for now by the ones that run included.
  while (!heap_.empty()) {
    const Entry e = heap_.top();
    if (stale(e)) {
      heap_.pop();
      continue;
    }
    if (e.t > now) break;
    heap_.pop();
    pending_[e.client] = {};
    ++wakes_;
    prepare_next();
    clients_[e.client]->woken();
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
  if (!stale(next)) clients_[next.client]->prepare();
}

}  // namespace rtsim::modules
