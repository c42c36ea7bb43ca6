#pragma once
// A processor of the kit with an inbox: the queue a network delivers its messages into (a token
// ring's channel, a mesh), unbounded, and the one way of taking the next message out, which
// waits for one when none has arrived and remembers when it was delivered and when it was taken
// (the latency probe's queueing at the inbox). Used by pxpl5-raytrace's ring nodes and
// sort-first's nodes.
#include <systemc>

#include "modules/message_channel.hpp"
#include "modules/processor.hpp"

namespace rtsim::modules {

template <class M>
class InboxProcessor : public Processor {
 public:
  MessageQueue<M> inbox;

 protected:
  InboxProcessor(const sc_core::sc_module_name& name, SliceSink& trace)
      : Processor(name, trace), inbox("inbox", TimedFifo<M>::kUnbounded) {}

  /// The next message that has arrived, waiting for one (idle, `why`) if none has.
  M receive(Wait why) {
    const sc_core::sc_time since = clock_.now();
    wait_for_item(inbox.fifo, clock_);
    waited_since(since, why);
    // A message stamped ahead (it is still on its way until then).
    if (auto t = inbox.fifo.next_item_time(); t && *t > clock_.now()) idle_until(*t, why);
    last_delivered_ = inbox.fifo.next_item_time().value_or(clock_.now());
    sc_core::sc_time taken;
    M m = inbox.fifo.get(clock_.now(), taken);
    clock_.catch_up(taken);
    last_taken_ = taken;
    return m;
  }
  /// The message receive() returned last: when it was delivered into the inbox, and when this
  /// processor took it out (--latency-probe).
  sc_core::sc_time last_delivered_, last_taken_;
};

}  // namespace rtsim::modules
