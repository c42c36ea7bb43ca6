#pragma once
// What travels on the hidden-line pipe's links (seed 000 L1733-L1737, L1906), and how long a
// message takes on a link of `lanes` wires: its values — numbers of `word_bits` bits, then its
// one-bit flags — are dealt to the wires one a wire in turn ("dedicate one [wire] for every
// value", L1906), and it lasts as long as the busiest wire's bits. On the seed's six wires a
// segment (six numbers) and an intersection (two numbers, three flags) take a number's 16 bit
// times each, "about 8 usec" at 500 ns a bit; on the plane path's five wires a plane (four
// numbers and a flag) takes the same. On one wire a message takes all its bits.
#include <cstdint>
#include <systemc>

#include "firmware/hiddenline/messages.hpp"

namespace rtsim::platform::ullner_hidden_line {

/// A message on its way, and when its last bit reaches the register it was sent to (the pipe is
/// loosely timed: the time travels in the message, not in the kernel's clock).
struct MessageInFlight {
  hiddenline::Message message;
  sc_core::sc_time at = sc_core::SC_ZERO_TIME;
};

/// Bit times of a message of `numbers` numbers and `flags` one-bit flags on `lanes` wires.
inline std::uint64_t bit_times(std::uint64_t numbers, std::uint64_t flags, std::uint64_t lanes,
                               std::uint64_t word_bits) {
  // Wire w carries values w, w + lanes, ...: the first wires take one more number than the
  // rest, and the flags fill in after the numbers.
  std::uint64_t busiest = 0;
  for (std::uint64_t w = 0; w < lanes && w < numbers + flags; ++w) {
    std::uint64_t bits = 0;
    for (std::uint64_t v = w; v < numbers + flags; v += lanes) bits += v < numbers ? word_bits : 1;
    busiest = bits > busiest ? bits : busiest;
  }
  return busiest;
}

/// A message's values: a segment six numbers (L1906: 96 bits at 16), an intersection two numbers
/// and three flags (35), the end of the stream one flag.
inline std::uint64_t message_bit_times(const hiddenline::Message& m, std::uint64_t lanes,
                                       std::uint64_t word_bits) {
  switch (m.kind) {
    case hiddenline::Message::Kind::kSegment:
      return bit_times(6, 0, lanes, word_bits);
    case hiddenline::Message::Kind::kIntersection:
      return bit_times(2, 3, lanes, word_bits);
    case hiddenline::Message::Kind::kEnd:
      break;
  }
  return bit_times(0, 1, lanes, word_bits);
}

/// A plane on its own path: four numbers and the last-plane flag (65 bits at 16).
inline std::uint64_t plane_bit_times(std::uint64_t lanes, std::uint64_t word_bits) {
  return bit_times(4, 1, lanes, word_bits);
}

}  // namespace rtsim::platform::ullner_hidden_line
