#pragma once
// When a ray description reaches the last polygon processor of the chain, by arithmetic: one
// formula per description, not one event per processor (DESIGN.md "Timing rules").
//
// Every processor k (0 .. N-1) is the same: it accepts a description at most once per issue
// interval II, starts passing it on hop_latency (hl) after accepting it, and its output link
// carries it in s = the link's serialisation of 13 words (32 bit times on 13 wires, seed 000
// L729-L733), delivering it the link's latency l after its last bit. With A_k(j) the arrival of
// description j at processor k and E_k(j) its acceptance:
//     E_k(j)     = max(A_k(j), E_k(j-1) + II)
//     A_{k+1}(j) = max(E_k(j) + hl, L_k(j-1)) + s + l  (L_k: when link k was last free)
// If II >= s the links never wait and E_{k+1}(j) = max(E_k(j) + h, E_{k+1}(j-1) + II); if s > II
// the processors never wait (arrivals are s apart) and the same holds with s for II. So, with
//     h = hl + s + l   (one hop)      b = max(II, s)   (the spacing the chain allows)
//     E_{k+1}(j) = max(E_k(j) + h, E_{k+1}(j-1) + b),
// and by induction over k (E_k(j-1) >= E_{k-1}(j-1) + h makes the cross term redundant)
//     E_{N-1}(j) = max(E_0(j) + (N-1) h, E_{N-1}(j-1) + b).
// The input register of processor k+1 is free by the time the next description's first bit
// reaches it (E_{k+1}(j-1) <= E_k(j) + hl + l follows from the same induction), so no processor
// waits for room: only the host end, where the chain's first input register is a queue of one,
// can be held up. pipeline.model = engines runs the same rules one processor at a time
// (polygon_engine.hpp, with the handshake on the next register made explicit); a test shows
// both give every ray the same times (tests/ullner_pipeline_test.cpp).
#include <algorithm>
#include <cstdint>
#include <systemc>

#include "modules/sim_time.hpp"

namespace rtsim::platform::ullner_pipeline {

/// A polygon processor's timing (the parameters pipeline.engine.*).
struct EngineTiming {
  sc_core::sc_time issue_interval;   ///< II: one description accepted per interval
  sc_core::sc_time hop_latency;      ///< hl: accepted -> starts to pass it on
  sc_core::sc_time compute_latency;  ///< its own t, p_r, u, v after the ray fields arrived
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
  sc_core::sc_time spacing() const { return std::max(engine_.issue_interval, serial_); }

  /// Description j accepted by the first processor at `first`: when the last one accepts it.
  sc_core::sc_time last_accepts(const sc_core::sc_time& first) {
    sc_core::sc_time t = modules::plus(first, modules::times(hop(), engines_ - 1));
    if (any_) t = std::max(t, modules::plus(last_, spacing()));
    last_ = t;
    any_ = true;
    return t;
  }

  const EngineTiming& engine() const { return engine_; }
  sc_core::sc_time description_time() const { return serial_; }
  sc_core::sc_time link_latency() const { return link_latency_; }
  std::uint64_t engines() const { return engines_; }

 private:
  EngineTiming engine_;
  sc_core::sc_time serial_;
  sc_core::sc_time link_latency_;
  std::uint64_t engines_;
  sc_core::sc_time last_ = sc_core::SC_ZERO_TIME;
  bool any_ = false;
};

}  // namespace rtsim::platform::ullner_pipeline
