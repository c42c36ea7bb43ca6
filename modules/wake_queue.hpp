#pragma once
// An event queue of its own for many event-driven processors, with SystemC at its edge
// (DESIGN.md "The three layers": a kit part). A thousand SC_METHODs each cost SystemC a timed
// notification, a place in its priority queue and a process dispatch for every activation; here
// one SC_METHOD (`dispatch`) runs them instead: it keeps when each of its clients must run next
// in a 4-ary heap (modules/wake_heap.hpp) and, at each simulated time, runs every client due
// then, in the order their wakes were asked for (first asked, first run). SystemC sees one
// process and one timed notification: the earliest wake.
//
// It runs ahead of SystemC: when SystemC has nothing else to do before the queue's next wake (no
// other process to run now, no event due until after it), the queue goes on to that wake itself,
// and so on, instead of handing back to SystemC for each (a timed notification, a delta cycle and
// a method's dispatch a wake: 0.56 G of a 32 x 32 array's 3.83 G instructions of simulation).
// While it does, its clients see the time of their wake through modules::sim_now(), which the
// model reads time by everywhere; SystemC's own time (modules::systemc_now) lags, so a delay a
// client hands to SystemC (an event it notifies) must count from systemc_now(). Such an event is
// then due, and the queue stops running ahead before it; a wake due at the same time as another
// process's activity is left to SystemC, as without running ahead.
//
// A client asks to run at an absolute time (wake_at); a client has at most one wake pending,
// the earliest asked for, as an sc_event keeps its earliest notification. A wake may be asked
// for from a client's own run, from another client's (a message put into its port) or from any
// SystemC process (a ring delivering), at the current simulated time or later.
//
// Exact where the clients are: a processor that handles what is due by its time and computes
// ahead (modules::Processor's event-driven mode) does not depend on which of two processors due
// at the same time runs first, because every message it takes was put before its stamp.
// Used by ullner-array's 1024 processors (node.process = queue) and gaudet-pert's PERT
// processors (process = queue); tests/ullner_array_test.cpp and tests/gaudet_sync_test.cpp
// show their statistics those of SystemC methods, tests/wake_queue_test.cpp where it runs ahead
// and where it stops.
#include <cstdint>
#include <limits>
#include <systemc>
#include <vector>

#include "modules/wake_heap.hpp"

namespace rtsim::modules {

class WakeQueue : public sc_core::sc_module {
 public:
  /// What the queue runs.
  class Client {
   public:
    /// Runs at the simulated time its wake was asked for (sc_time_stamp()).
    virtual void woken() = 0;
    /// Called just before the client that runs before it: it may prefetch what its woken()
    /// reads first (modules/prefetch.hpp), so that its state is on its way into the cache while
    /// the other runs. A hint only: it must change nothing.
    virtual void prepare() const {}

   protected:
    ~Client() = default;
  };

  SC_HAS_PROCESS(WakeQueue);
  /// Runs every client added, in the order added, when `start` fires; from then, as they ask.
  WakeQueue(const sc_core::sc_module_name& name, const sc_core::sc_event& start);

  /// Elaboration: a client; returns its number (for wake_at).
  std::size_t add(Client& client);
  /// Client `k` runs at `t` (absolute; now or later), unless it has a wake pending by then.
  void wake_at(std::size_t k, const sc_core::sc_time& t);
  /// Client `k`'s pending wake, if any, is dropped: it runs when a wake is asked for again (an
  /// alarm moved later: cancel, then wake_at).
  void cancel(std::size_t k) { pending_[k] = {}; }
  /// Wakes run so far (the clients' activations).
  std::uint64_t wakes() const { return wakes_; }

 private:
  using Entry = WakeHeap::Entry;
  static constexpr std::uint64_t kNone = std::numeric_limits<std::uint64_t>::max();
  void dispatch();
  /// The client of the earliest live wake prepares (Client::prepare).
  void prepare_next();
  /// A client's pending wake: its entry's sequence number and time (kNone: none).
  struct Pending {
    std::uint64_t seq = kNone;
    std::uint64_t t = kNone;
  };
  /// An entry is stale when its client has since been given a sooner wake (or has run).
  bool stale(const Entry& e) const { return pending_[e.client()].seq != e.seq(); }

  std::vector<Client*> clients_;
  std::vector<Pending> pending_;  ///< by client
  WakeHeap heap_;
  std::uint64_t seq_ = 0;
  std::uint64_t wakes_ = 0;
  bool started_ = false;
  bool dispatching_ = false;
  /// When SystemC will next run dispatch (kNone: only when asked).
  std::uint64_t scheduled_ = kNone;
  sc_core::sc_event kick_{"kick"};
};

}  // namespace rtsim::modules
