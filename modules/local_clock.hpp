#pragma once
// Temporal decoupling for one SystemC thread (loosely-timed coding style, TLM-2.0 §"quantum").
// The thread keeps its own absolute local time, which may run ahead of sc_time_stamp() by at
// most the global quantum (tlm::tlm_global_quantum). Quantum 0 is the reference setting: the
// thread synchronises at every advance and every interaction happens in global time order.
// Unlike tlm_utils::tlm_quantumkeeper this clock is absolute, so timestamps carried by messages
// (see TimedFifo) compare directly with it.
// An event-driven process (an SC_METHOD, which cannot wait) runs ahead within an activation
// instead: never_wait() makes advance() only move local time, and the method asks to be
// triggered again at its local time (Processor::make_event_driven).
// Used by every processor (modules::Processor) and ullner-peripheral's peripheral.
#include <algorithm>
#include <systemc>
#include <tlm>

#include "modules/activations.hpp"
#include "modules/sim_time.hpp"

namespace rtsim::modules {

class LocalClock {
 public:
  /// Current local time (absolute).
  sc_core::sc_time now() const { return local_; }

  /// Spend `d` of local time; synchronise if the thread is a quantum ahead.
  void advance(const sc_core::sc_time& d) {
    local_ = plus(local_, d);
    if (waits_ && local_ - modules::systemc_now() >= tlm::tlm_global_quantum::instance().get())
      sync();
  }

  /// For an SC_METHOD: advance() never waits (elaboration, before the simulation starts).
  void never_wait() { waits_ = false; }
  /// For a thread: whether advance() synchronises (a quantum ahead) or only moves local time on;
  /// a thread that does not wait there calls sync() itself before it interacts.
  void set_waits(bool waits) { waits_ = waits; }
  bool waits() const { return waits_; }

  /// Move local time forward to `t` if it is later (a message that arrives at t).
  void catch_up(const sc_core::sc_time& t) {
    if (t > local_) advance(t - local_);
  }

  /// Wait in global time until local time (no-op if already there).
  void sync() {
    const sc_core::sc_time g = modules::systemc_now();
    if (local_ > g) modules::sim_wait(local_ - g);
  }

  /// After a wait() on an event: local time is at least the global time.
  void resync() { local_ = std::max(local_, modules::sim_now()); }

 private:
  sc_core::sc_time local_ = sc_core::SC_ZERO_TIME;
  bool waits_ = true;
};

}  // namespace rtsim::modules
