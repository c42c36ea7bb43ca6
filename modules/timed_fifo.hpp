#pragma once
// A bounded FIFO between two temporally decoupled threads, exact at any quantum for the FIFO's
// own timing: every item carries the absolute time it was put, every slot the absolute time it
// was freed. Item n can be put no earlier than the time item n - capacity was taken out (its
// slot), and taken no earlier than the time it was put. Only decisions that look at the FIFO's
// state "now" (has_item_by, has_room_by) depend on how far threads run ahead: that is the error
// a larger quantum buys speed with.
//
// Blocking calls wait() on an event, so they must be called from an SC_THREAD.
// It is the statistics group of its name: its depth over time (queue.{capacity, mean_occupancy,
// max_occupancy} and the traces' depth signal), the messages put, and the puts that waited for
// a slot and how long (back-pressure on its producers).
// Used by every machine's queues (MessageQueue).
#include <cstdint>
#include <optional>
#include <string>
#include <systemc>
#include <vector>

#include "modules/activations.hpp"
#include "modules/ring_buffer.hpp"
#include "modules/statistics.hpp"

namespace rtsim::modules {

/// Told of every put into a TimedFifo with the item's stamp: a consumer that keeps its own
/// account of what waits for it (an event-driven processor that wakes at the first item's stamp
/// instead of at every put).
class PutListener {
 public:
  /// An item stamped `stamp` was put into the FIFO the listener registered as `port`.
  virtual void item_put(int port, const sc_core::sc_time& stamp) = 0;

 protected:
  ~PutListener() = default;
};

/// Told of every take from a FIFO it listens to (listen_takes): a producer that waits for room
/// without SystemC events (gaudet-pert's processors on their event queue).
class TakeListener {
 public:
  /// An item was taken from the FIFO the listener registered as `port`.
  virtual void item_taken(int port) = 0;

 protected:
  ~TakeListener() = default;
};

template <class T>
class TimedFifo : public StatGroup {
 public:
  /// A FIFO that is never full: a node's stockpile of messages in its memory (ullner-array).
  static constexpr std::size_t kUnbounded = Level::kUnbounded;

  TimedFifo(std::string name, std::size_t capacity)
      : StatGroup(std::move(name)),
        capacity_(capacity ? capacity : 1),
        slot_free_(capacity_ == kUnbounded ? 0 : capacity_),
        depth_(*this, capacity_) {}

  const std::string& name() const { return stat_path(); }
  std::size_t capacity() const { return capacity_; }
  std::size_t size() const { return items_.size(); }

  /// True if an item put at or before `t` is waiting.
  bool has_item_by(const sc_core::sc_time& t) const {
    return !items_.empty() && items_.front().stamp <= t;
  }
  /// True if a slot is free at or before `t`.
  bool has_room_by(const sc_core::sc_time& t) const {
    if (capacity_ == kUnbounded) return true;
    return items_.size() < capacity_ && slot_free_[messages_.value() % capacity_] <= t;
  }
  bool full() const { return items_.size() >= capacity_; }
  /// `listener` is told of every put from now on (one at most; null: none), with `port`, which
  /// of its FIFOs this is. One that never waits on put_event() (an event-driven processor woken
  /// by the listener) says `notify_puts` = false: a put then costs SystemC no notification (a
  /// delta cycle each).
  void listen(PutListener* listener, bool notify_puts = true, int port = 0) {
    listener_ = listener;
    notify_puts_ = notify_puts;
    port_ = port;
  }
  /// `listener` is told of every take from now on (one at most), with `port`; a take then
  /// notifies no get event (nobody waits on it through SystemC).
  void listen_takes(TakeListener* listener, int port = 0) {
    take_listener_ = listener;
    take_port_ = port;
  }
  /// Prefetches what a get() reads: the oldest item and the FIFO's own state.
  void prepare_get() const {
    prefetch_object(items_);
    prefetch_object(depth_);
    items_.prefetch_front();
  }
  /// Prefetches what a put() writes: the slot it fills and the FIFO's own state.
  void prepare_put() const {
    prefetch_object(items_);
    prefetch_object(depth_);
    prefetch_object(messages_);
    items_.prefetch_back();
  }
  /// When the oldest waiting item was (or will be) put; nothing if the FIFO is empty.
  std::optional<sc_core::sc_time> next_item_time() const {
    if (items_.empty()) return std::nullopt;
    return items_.front().stamp;
  }
  /// When the next put can enter; nothing while the FIFO is full (it depends on a get).
  std::optional<sc_core::sc_time> next_room_time() const {
    if (capacity_ == kUnbounded) return sc_core::SC_ZERO_TIME;
    if (items_.size() >= capacity_) return std::nullopt;
    return slot_free_[messages_.value() % capacity_];
  }
  bool empty() const { return items_.empty(); }
  /// When message `n` (0: the first put) was taken out, if it has been and its slot has not been
  /// reused since (n + capacity > messages taken); nothing otherwise. A producer that must know
  /// when a slot frees before it can time its next put (a pipeline's far end) asks this.
  std::optional<sc_core::sc_time> taken_at(std::uint64_t n) const {
    if (capacity_ == kUnbounded || n >= get_count_ || n + capacity_ < get_count_)
      return std::nullopt;
    return slot_free_[n % capacity_];
  }

  /// Put `item` at local time `t`; blocks while the FIFO is full. Returns the time the item
  /// actually entered (>= t: later if it had to wait for a slot).
  sc_core::sc_time put(T item, sc_core::sc_time t) {
    while (items_.size() >= capacity_) modules::sim_wait(event_of_get());
    const sc_core::sc_time stamp =
        capacity_ == kUnbounded ? t : std::max(t, slot_free_[messages_.value() % capacity_]);
    Entry& e = items_.append();
    e.item = std::move(item);
    e.stamp = stamp;
    ++messages_;
    if (stamp > t) {
      ++waits_;
      waited_ += stamp - t;
    }
    depth_.put(stamp);
    if (notify_puts_) event_of_put().notify(sc_core::SC_ZERO_TIME);
    if (listener_) listener_->item_put(port_, stamp);
    return stamp;
  }

  /// Take the oldest item at local time `t`; blocks while the FIFO is empty. `stamp` receives
  /// the time it was taken (>= t and >= the time it was put).
  T get(sc_core::sc_time t, sc_core::sc_time& stamp) {
    while (items_.empty()) modules::sim_wait(event_of_put());
    T item = std::move(items_.front().item);  // returned as it is (no second copy)
    stamp = std::max(t, items_.front().stamp);
    items_.pop_front();
    if (capacity_ != kUnbounded) slot_free_[get_count_ % capacity_] = stamp;
    ++get_count_;
    depth_.got(stamp);
    // Only a producer blocked on a full FIFO waits for a take (an unbounded one is never full).
    if (take_listener_ != nullptr)
      take_listener_->item_taken(take_port_);
    else if (capacity_ != kUnbounded)
      event_of_get().notify(sc_core::SC_ZERO_TIME);
    return item;
  }

  /// Notified (next delta) when an item is put / taken.
  const sc_core::sc_event& put_event() const { return event_of_put(); }
  const sc_core::sc_event& get_event() const { return event_of_get(); }

  std::uint64_t puts() const { return messages_.value(); }
  const Occupancy& occupancy() const { return depth_.occupancy(); }

 private:
  struct Entry {
    T item;
    sc_core::sc_time stamp;
  };
  std::size_t capacity_;
  RingBuffer<Entry> items_;
  std::vector<sc_core::sc_time> slot_free_;  ///< per slot: when its last item was taken
  std::uint64_t get_count_ = 0;
  PutListener* listener_ = nullptr;
  int port_ = 0;
  bool notify_puts_ = true;
  TakeListener* take_listener_ = nullptr;
  int take_port_ = 0;
  Level depth_;
  Counter messages_{*this, "messages", "messages put"};
  Counter waits_{*this, "waits", "puts that waited for a free slot"};
  Duration waited_{*this, "waited_s", "time puts waited for a free slot (back-pressure)"};
  /// The put and get events, made when first asked for or notified: a put's notification
  /// reaches only processes waiting on the event, and there are none before it exists, so a
  /// FIFO nobody waits on (an event-driven processor's port) never makes them. Events are a
  /// large part of building a machine of thousands of queues (SystemC names each one). Last:
  /// two events are some 300 bytes, which between the items and the depth put every put and
  /// get of a FIFO nobody waits on several cache lines apart.
  sc_core::sc_event& event_of_put() const { return put_ ? *put_ : put_.emplace(); }
  sc_core::sc_event& event_of_get() const { return got_ ? *got_ : got_.emplace(); }
  mutable std::optional<sc_core::sc_event> put_;
  mutable std::optional<sc_core::sc_event> got_;
};

/// Returns once `fifo` holds an item; a thread whose local time is `clock` (a LocalClock) first
/// synchronises with simulated time, then waits for a put (the loop of a consumer thread).
template <class T, class Clock>
void wait_for_item(const TimedFifo<T>& fifo, Clock& clock) {
  if (!fifo.empty()) return;
  clock.sync();
  while (fifo.empty()) modules::sim_wait(fifo.put_event());
  clock.resync();
}

}  // namespace rtsim::modules
