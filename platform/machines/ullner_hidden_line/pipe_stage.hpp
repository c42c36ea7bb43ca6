#pragma once
// One processor of the hidden-line pipe (seed 000 Fig. 3-31, L1723-L1733) as a module: a plane
// processor (Figs. 3-32/3-33; one a boundary plane, or idle, passing every message on, where
// the pipe has more processors than the scene has planes) or a cleanup processor (Fig. 3-34).
// A message reaches it through `in` as a TLM transaction; its firmware
// (firmware/hiddenline/) takes it and writes what it sends on, which goes out through `out`
// over its bit-serial link (L1906) to the next processor's input register.
//
// Its timing is its own state's. With A(j) the arrival of input j in its register:
//     accepts      E(j) = max(A(j), D(j-1))                      it holds one input
//     ready        R    = E(j) for what a plane processor forwards on a segment (the segment
//                         and the intersection it held: "forward the segment first", L1813),
//                         E(j) + C(j) for everything else
//     link starts  S    = max(R, its link free, the next register free)
//     arrives      A'   = S + serialisation + latency                at the next processor
//     done         D(j) = max(E(j) + C(j), the last S)
// C(j), its arithmetic for the input, is its multiplications over its multipliers, each a
// multiplication time: a plane processor's six for a segment on three multipliers (L1908-L1910)
// and a cross multiplication's two for a comparison; a cleanup processor's comparisons on its
// two multipliers (L1912). The next register is free once the next processor has accepted the
// input before (the asynchronous links' handshake, L1906: a request and an acknowledge line).
//
// Loosely timed: nothing waits in simulated time; the pipe (hidden_line_pipe.hpp) hands each
// processor's outputs on one at a time, deepest first, so that when one starts, everything it
// depends on — the next processor's acceptance of the message before — is known. The order the
// outputs are computed in is not the order in time, and no time depends on it.
#include <cstdint>
#include <optional>
#include <systemc>
#include <tlm>
#include <vector>

#include "firmware/hiddenline/pipe.hpp"
#include "modules/chain_hop.hpp"
#include "platform/machines/ullner_hidden_line/in_flight.hpp"

namespace rtsim::platform::ullner_hidden_line {

/// What every processor of a class shares: its arithmetic and its output link.
struct StageTiming {
  sc_core::sc_time multiplication_time = sc_core::SC_ZERO_TIME;
  std::uint64_t multipliers = 1;
  sc_core::sc_time bit_time = sc_core::SC_ZERO_TIME;
  std::uint64_t lanes = 1;
  std::uint64_t word_bits = 16;
  sc_core::sc_time link_latency = sc_core::SC_ZERO_TIME;
};

/// Told of every message a processor hands to its link (the pipe's faults, probe and the last
/// link's statistics).
struct LinkWatch {
  virtual ~LinkWatch() = default;
  /// `f` leaves processor `index` (its `at` is its arrival at the next register), started at
  /// `start`, ready since `ready`. It may change `f`.
  virtual void handed(std::size_t index, MessageInFlight& f, const sc_core::sc_time& ready,
                      const sc_core::sc_time& start) = 0;
  /// A message reached processor `index`'s register at `arrived` and was accepted at `accepted`.
  virtual void accepted(std::size_t index, const hiddenline::Message& m,
                        const sc_core::sc_time& arrived, const sc_core::sc_time& accepted) = 0;
};

/// A processor's state: its firmware, its times and its accounts. The pipe keeps every
/// processor's in one array, visited in the order messages travel (a processor module is large,
/// its state small: the state of thousands stays in the cache).
struct StageState {
  struct Pending {
    hiddenline::Message message;
    sc_core::sc_time ready;
  };
  std::optional<hiddenline::Stage> firmware;
  std::vector<Pending> pending;  ///< outputs not yet handed on; [head, size)
  std::size_t head = 0;
  sc_core::sc_time accepted = sc_core::SC_ZERO_TIME, done = sc_core::SC_ZERO_TIME,
                   link_free = sc_core::SC_ZERO_TIME;
  sc_core::sc_time link_busy = sc_core::SC_ZERO_TIME, compute_busy = sc_core::SC_ZERO_TIME,
                   waited = sc_core::SC_ZERO_TIME;
  std::uint64_t inputs = 0, segments_in = 0, intersections_out = 0;
  bool plane = true;
};

class PipeStage : public modules::ChainHop {
 public:
  /// Processor `index` of the pipe with `state` (its firmware: none for an idle plane
  /// processor), which must outlive it.
  PipeStage(const sc_core::sc_module_name& name, std::size_t index, StageState& state,
            const StageTiming& timing, LinkWatch& watch);

  /// The next processor's (or the divider's) input register: free once that one has accepted
  /// the message before (set at elaboration).
  void set_next(const sc_core::sc_time* next_register_free) { next_free_ = next_register_free; }
  /// When it last accepted an input (its register was freed then).
  const sc_core::sc_time& register_free() const { return state_.accepted; }

  /// It has outputs not yet handed to its link.
  bool pending() const { return state_.head < state_.pending.size(); }
  /// Hands its first pending output to its link and on to the next processor.
  void send_next();

  bool is_plane() const { return state_.plane; }
  const StageState& state() const { return state_; }

 private:
  void b_transport(tlm::tlm_generic_payload& gp, sc_core::sc_time& delay) override;

  std::size_t index_;
  StageState& state_;
  StageTiming timing_;
  LinkWatch& watch_;
  const sc_core::sc_time* next_free_ = nullptr;
  std::vector<hiddenline::Message> out_;  ///< the firmware's outputs of one input
  MessageInFlight flight_;
};

/// The transaction's message (a MessageExtension<MessageInFlight>), or nullptr.
MessageInFlight* carried(tlm::tlm_generic_payload& gp);

}  // namespace rtsim::platform::ullner_hidden_line
