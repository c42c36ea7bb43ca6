#pragma once
// How a processor gets the packets of a data set it does not hold (seed 001 §5.1-5.4): it asks
// for a packet by its ID and later finds the packet in a buffer. Two implementations:
//  * BusInterface (bus_interface.hpp): Gaudet's Bus Interface Controller on a broadcast bus —
//    ID registers, comparator, hit line, double FIFO buffer (§5.4, L897-L924);
//  * LocalDataSet (local_data_set.hpp): the "direct memory" baseline, every processor holding
//    the whole data set in its own memory (L806, L1103) — a packet is there when asked for.
// The processor reads a packet's words at one cycle a word in both cases (FIFO read, L924;
// streamed memory, L863) and charges that itself. The words travel with the packet: a word
// corrupted in a Broadcast Processor's memory reaches every processor that captures it.
//
// Times are absolute. A processor may run ahead of simulated time (temporal decoupling); every
// request and release is stamped with the processor's local time, and the broadcast side
// honours a stamp only from that time on, so the outcome does not depend on who ran ahead.
#include <algorithm>
#include <cstdint>
#include <optional>
#include <span>
#include <systemc>

#include "modules/sim_time.hpp"

namespace rtsim::platform::gaudet {

/// A packet that has arrived in one of the port's buffers.
struct ReceivedPacket {
  std::uint32_t id = 0;
  sc_core::sc_time arrival = sc_core::SC_ZERO_TIME;  ///< its last word is in the buffer
  /// When its transfer began: the bus started sending it (overhead, then words), or the memory
  /// access began (LocalDataSet). arrival - transfer_start is its transfer time.
  sc_core::sc_time transfer_start = sc_core::SC_ZERO_TIME;
  int buffer = -1;
  /// The packet's words as they arrived (the BIC's FIFO buffer, or the processor's own memory):
  /// what the processor computes on. Valid until release().
  std::span<const std::uint32_t> words{};
  /// Streamed (BusInterface with `stream`): its words are readable as they come in, word n
  /// (from 0) at first_word + (n + 1) x word_time. Otherwise only at arrival.
  bool streamed = false;
  sc_core::sc_time first_word = sc_core::SC_ZERO_TIME;  ///< its first word starts on the bus
  sc_core::sc_time word_time = sc_core::SC_ZERO_TIME;

  /// When its first `n` words are readable.
  sc_core::sc_time words_in(std::size_t n) const {
    if (!streamed) return arrival;
    return std::min(arrival, first_word + modules::times(word_time, n));
  }
};

class PacketPort {
 public:
  virtual ~PacketPort() = default;

  /// Ask for packet `id` from local time `t`. False if no ID register is free at `t` (the
  /// processor keeps the ID in its own memory and tries again later, L910).
  virtual bool request(std::uint32_t id, const sc_core::sc_time& t) = 0;
  /// Withdraw a request not yet served (the PrimProcessor's prefetch it no longer needs).
  /// A packet of that ID already in a buffer is dropped and its buffer freed at `t`.
  virtual void cancel(std::uint32_t id, const sc_core::sc_time& t) = 0;
  /// Whether a register holds `id` (asked for, not yet received).
  virtual bool pending(std::uint32_t id) const = 0;
  /// Whether a register is free at `t`.
  virtual bool register_free(const sc_core::sc_time& t) const = 0;

  /// The earliest arrival among packets waiting in buffers (of `id` only, if given).
  virtual std::optional<sc_core::sc_time> next_arrival(
      std::optional<std::uint32_t> id = std::nullopt) const = 0;
  /// Takes the earliest packet that has arrived by `t` (of `id` only, if given): the processor
  /// now works on it in its buffer.
  virtual std::optional<ReceivedPacket> take(const sc_core::sc_time& t,
                                             std::optional<std::uint32_t> id = std::nullopt) = 0;
  /// The processor is done with the packet: its buffer is free from `t`.
  virtual void release(const ReceivedPacket& p, const sc_core::sc_time& t) = 0;

  /// Notified when a packet is captured or a register freed (the processor then looks at
  /// next_arrival(); arrival times may lie ahead of the notification).
  virtual const sc_core::sc_event& changed_event() const = 0;

  /// Told instead of the event from now on (a processor on gaudet-pert's event queue, which waits
  /// for nothing through SystemC).
  class Listener {
   public:
    virtual void port_changed() = 0;

   protected:
    ~Listener() = default;
  };
  void listen(Listener* listener) { listener_ = listener; }

 protected:
  /// A packet was captured or a register freed: the listener is told, or `changed` notified
  /// (next delta).
  void tell_changed(sc_core::sc_event& changed) {
    if (listener_ != nullptr)
      listener_->port_changed();
    else
      changed.notify(sc_core::SC_ZERO_TIME);
  }

 private:
  Listener* listener_ = nullptr;
};

}  // namespace rtsim::platform::gaudet
