#pragma once
// A segment of Ullner's scan-line tree (seed 000 L1068, L1340, L1348): the part of a polygon on
// one scan line, eleven 12-bit fixed-point numbers — the line y, and x, z, r, g, b at the left
// and at the right end — 132 bits on the wire. x counts 4096 steps across the screen (12 bits,
// L1659: "the twelve bit resolution already used"); a segment at x covers the screen from x to
// x + 1 steps, so [x_l, x_r] covers x_l up to x_r + 1 and a segment broken at x ends at x - 1
// (the merge's epsilon, L1421-L1427, is one step). z runs from 0 (near) to 4095 (far), colours
// from 0 to 4095 (full).
//
// Every stream ends with a dummy segment that is off the screen (L1365): line kDummyLine.
#include <array>
#include <cstdint>

namespace rtsim::scanline {

inline constexpr int kWordBits = 12;
inline constexpr int kWordSteps = 1 << kWordBits;  ///< 4096
inline constexpr int kWordMax = kWordSteps - 1;
inline constexpr int kSegmentWords = 11;
inline constexpr int kSegmentBits = kSegmentWords * kWordBits;  ///< 132
/// The dummy's line: past any screen's last (a 12-bit line number's largest).
inline constexpr std::int16_t kDummyLine = kWordMax;
inline constexpr std::uint32_t kNoJourney = ~std::uint32_t{0};

/// An end of a segment: x, z, r, g, b.
struct SegmentEnd {
  std::int16_t x = 0, z = 0, r = 0, g = 0, b = 0;
};

struct Segment {
  std::int16_t y = kDummyLine;  ///< the scan line, 0 at the top
  SegmentEnd left, right;
  /// Not on the wire: the polygon it comes from (for the id image and traces), and the journey
  /// the latency probe follows it by (kNoJourney: none).
  std::uint32_t polygon = 0;
  std::uint32_t journey = kNoJourney;
  /// A line mark (splitting.hpp): no segment, only "this stream sends nothing before line y";
  /// a flag beside the eleven words. Merging processors drop it.
  bool mark = false;

  bool dummy() const { return y >= kDummyLine; }
  /// Its eleven words, as the link sends them (Fig. 3-25's order, L1610).
  std::array<std::int16_t, kSegmentWords> words() const {
    return {y, left.x, left.z, left.r, left.g, left.b, right.x, right.z, right.r, right.g, right.b};
  }
  static Segment from_words(const std::array<std::int16_t, kSegmentWords>& w,
                            std::uint32_t polygon);
};

/// The dummy that ends every stream.
inline Segment dummy_segment() { return Segment{}; }
/// A line mark for line y.
inline Segment line_mark(std::int16_t y) {
  Segment s;
  s.y = y;
  s.mark = true;
  return s;
}

/// The point of `s` at step x (rounded): z, r, g, b interpolated between its ends.
SegmentEnd point_at(const Segment& s, int x);

/// A 12-bit word from a value in [0, 1] (clamped; NaN is 0).
std::int16_t unit_word(double v);

}  // namespace rtsim::scanline
