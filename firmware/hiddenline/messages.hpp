#pragma once
// The hidden-line pipeline's messages (seed 000 L1733-L1737, L1906), in screen coordinates (x
// right, y down, z the depth away from the eye; integers, the machine's 16-bit numbers):
//   segment       two endpoints, 6 numbers: 96 bits;
//   intersection  where the segment's line meets a boundary plane, t = t_n / t_d (2 numbers),
//                 v (the line's negative end is the visible one), h (the end of a hidden part,
//                 set by a polygon's last plane or a cleanup processor), p (the first or the
//                 second intersection to leave a plane processor): 35 bits;
//   end           the end of the scene's stream: every processor sends on what it holds.
// An intersection carries no segment: it belongs to the last segment before it (L1735).
// Planes travel on a path of their own (plane.hpp).
#include <array>
#include <cstdint>

#include "firmware/hiddenline/line_param.hpp"

namespace rtsim::hiddenline {

using ScreenPoint = std::array<std::int32_t, 3>;

struct Segment {
  ScreenPoint a{}, b{};
  /// Which scene edge it is (for the drawing and the tests; not a field of the hardware's
  /// message, whose segments are anonymous).
  std::uint32_t edge = 0;
};

struct Intersection {
  LineParam t{};
  bool v = false;
  bool h = false;
  bool p = false;
};

struct Message {
  enum class Kind : std::uint8_t { kSegment, kIntersection, kEnd };
  Kind kind = Kind::kSegment;
  Segment segment{};
  Intersection intersection{};

  static Message of(const Segment& s) { return {Kind::kSegment, s, {}}; }
  static Message of(const Intersection& i) { return {Kind::kIntersection, {}, i}; }
  static Message end() { return {Kind::kEnd, {}, {}}; }
};

/// Sizes on the pipe's links with `word_bits`-bit numbers (L1906: 16): a segment 6 words, an
/// intersection 2 words and 3 flags, a plane 4 words and its flag.
inline constexpr int segment_bits(int word_bits) { return 6 * word_bits; }
inline constexpr int intersection_bits(int word_bits) { return 2 * word_bits + 3; }
inline constexpr int plane_bits(int word_bits) { return 4 * word_bits + 1; }

}  // namespace rtsim::hiddenline
