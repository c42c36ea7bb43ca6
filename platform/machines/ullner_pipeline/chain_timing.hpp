#pragma once
// When ray descriptions enter and leave the chain of polygon processors, by arithmetic: a few
// formulas per description, not one step per processor (DESIGN.md "Timing rules").
//
// Every processor k (0 .. N-1) is the same (polygon_engine.hpp runs these rules one processor at
// a time). With A_k(j) the arrival of description j in processor k's input register, E_k(j) its
// acceptance and S_k(j) the start of passing it on over the link (serialisation s, latency l):
//     E_k(j)     = max(A_k(j), E_k(j-1) + II, S_k(j-1))       it holds one description
//     S_k(j)     = max(E_k(j) + hl, S_k(j-1) + s, E_{k+1}(j-1) - l)
//     A_{k+1}(j) = S_k(j) + s + l
// (the next register must be free when the first bit reaches it: the handshake, L729-L731). The
// last processor's next register is a slot of the host's result queue (D slots; the host takes
// answer x at T(x)), which must be free when it starts (the host's end signals it; the slot then
// holds the description while its ray fields and, the compute latency cl behind, its result
// fields arrive):
//     S_{N-1}(j) = max(E_{N-1}(j) + hl, S_{N-1}(j-1) + s, T(j-D)).
//
// With h = hl + s + l (one hop) and b = max(II, s, hl) (the spacing the chain allows), every
// path through these constraints that goes back up the chain and down again gains hl + s <= 2b
// for two descriptions, no more than waiting in place, so the longest paths are the straight
// ones and only three processors need their own state:
//     the first:  E_0 and S_0 as above (its input register is the host's);
//     the second: E_1(j) = max(A_1(j), E_1(j-1) + b, E_{N-1}(j - 2(N-2)) - (N-2) l), the last
//                 term the far end's hold-up coming back up the chain, one processor every two
//                 descriptions (E_k(j) >= S_k(j-1) >= E_{k+1}(j-2) - l);
//     the last:   E_{N-1}(j) = max(S_0(j) + s + l + (N-2) h, E_{N-1}(j-1) + b, S_{N-1}(j-1)).
// With room for every answer (D at least the rays in flight) no processor after the first ever
// waits; with fewer slots and a host slow to take answers, the chain fills back from the far end
// to the host. tests/ullner_pipeline_test.cpp shows both models give every ray the same times in
// both cases.
//
// Descriptions are timed lazily: the first processor accepts description j once it knows
// S_0(j-1), which needs E_1(j-2), which needs the far end of description j - 2N + 3; and a
// description leaves when the host has taken the answer D before it. ChainTiming keeps what is
// computed and what waits.
#include <algorithm>
#include <cstdint>
#include <deque>
#include <optional>
#include <systemc>

#include "modules/sim_time.hpp"

namespace rtsim::platform::ullner_pipeline {

/// A polygon processor's timing (the parameters pipeline.engine.*).
struct EngineTiming {
  sc_core::sc_time issue_interval;   ///< II: one description accepted per interval
  sc_core::sc_time hop_latency;      ///< hl: accepted -> starts to pass it on
  sc_core::sc_time compute_latency;  ///< its own t, p_r, u, v after the ray fields arrived
};

/// The far end's handshake: when the answer `slots` before description j was taken (its slot
/// freed); nothing while the host has not taken it. j < slots: always free.
struct FarEnd {
  virtual ~FarEnd() = default;
  virtual std::optional<sc_core::sc_time> slot_free(std::uint64_t j) const = 0;
};

class ChainTiming {
 public:
  ChainTiming(const EngineTiming& engine, const sc_core::sc_time& description_time,
              const sc_core::sc_time& link_latency, std::uint64_t engines)
      : engine_(engine),
        serial_(description_time),
        link_latency_(link_latency),
        engines_(engines) {}

  /// h: from one processor accepting a description to the next accepting it, the chain empty.
  sc_core::sc_time hop() const {
    return modules::plus(modules::plus(engine_.hop_latency, serial_), link_latency_);
  }
  /// b: the shortest time between two descriptions anywhere along the chain.
  sc_core::sc_time spacing() const {
    return std::max({engine_.issue_interval, serial_, engine_.hop_latency});
  }

  // -- pipeline.model = chain: the formulas above, lazily. --

  /// The first processor can accept the next description (it knows when it passed on the last).
  bool can_accept() const {
    return engines_ == 1 ? sl_count_ == accepted_ : s0_count_ == accepted_;
  }
  /// The earliest it accepts the next description (its issue interval and its one register).
  sc_core::sc_time accept_bound() const {
    if (accepted_ == 0) return sc_core::SC_ZERO_TIME;
    return std::max(modules::plus(e0_, engine_.issue_interval), engines_ == 1 ? sl_ : s0_);
  }
  /// It accepts the next description at `accepted` (>= accept_bound()).
  void accept(const sc_core::sc_time& accepted);
  /// When the first processor handed the oldest description that has not left to its link (its
  /// ready time, or later if the next register was not yet free), for the link's statistics;
  /// taken once, as it leaves. Chains of two or more.
  sc_core::sc_time take_first_handed();
  /// Computes what `far_end` now allows; returns when the next description to leave starts
  /// passing on from the last processor, or nothing while it waits for a slot.
  std::optional<sc_core::sc_time> next_leaving(const FarEnd& far_end);
  /// Time the last processor held descriptions ready to leave for want of a result slot.
  sc_core::sc_time far_end_held() const { return held_; }

  const EngineTiming& engine() const { return engine_; }
  sc_core::sc_time description_time() const { return serial_; }
  sc_core::sc_time link_latency() const { return link_latency_; }
  std::uint64_t engines() const { return engines_; }

 private:
  /// Computes whatever the known times now allow: S_0, E_1 and E_{N-1} of the descriptions
  /// waiting for them, in order.
  void update();
  bool first_starts();
  bool second_accepts();
  bool last_accepts();

  EngineTiming engine_;
  sc_core::sc_time serial_;
  sc_core::sc_time link_latency_;
  std::uint64_t engines_;
  // Counts: accepted by the first processor, with S_0, E_1, E_{N-1}, S_{N-1} (left).
  std::uint64_t accepted_ = 0, s0_count_ = 0, e1_count_ = 0, el_count_ = 0, sl_count_ = 0;
  sc_core::sc_time e0_, s0_, e1_, el_, sl_;
  std::deque<sc_core::sc_time> e0_waiting_;  ///< E_0 of the accepted ones without S_0
  std::deque<sc_core::sc_time> s0_waiting_;  ///< S_0 of the ones without E_{N-1}
  std::deque<sc_core::sc_time> handed_;      ///< the first's hand-over of those not left
  std::deque<sc_core::sc_time> el_waiting_;  ///< E_{N-1} of the ones that have not left
  /// E_{N-1} of the last 2(N-2) + 1 descriptions (the hold-up coming back), from el_base_.
  std::deque<sc_core::sc_time> el_history_;
  std::uint64_t el_base_ = 0;
  sc_core::sc_time held_ = sc_core::SC_ZERO_TIME;
};

}  // namespace rtsim::platform::ullner_pipeline
