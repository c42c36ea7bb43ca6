#include "firmware/scanline/segment.hpp"

#include <algorithm>
#include <cmath>

namespace rtsim::scanline {

namespace {
std::int16_t word(int v) { return static_cast<std::int16_t>(std::clamp(v, 0, kWordMax)); }
}  // namespace

Segment Segment::from_words(const std::array<std::int16_t, kSegmentWords>& w,
                            std::uint32_t polygon) {
  Segment s;
  s.y = std::clamp<std::int16_t>(w[0], 0, kDummyLine);
  s.left = {word(w[1]), word(w[2]), word(w[3]), word(w[4]), word(w[5])};
  s.right = {word(w[6]), word(w[7]), word(w[8]), word(w[9]), word(w[10])};
  if (s.right.x < s.left.x) std::swap(s.left, s.right);
  s.polygon = polygon;
  return s;
}

SegmentEnd point_at(const Segment& s, int x) {
  const int span = s.right.x - s.left.x;
  if (span <= 0) return s.left;
  const auto at = [&](int l, int r) {
    // Rounded to the nearest step, halves away from zero: integers only, as the bit-serial
    // multipliers and dividers of the merging processor compute it (L1509-L1513).
    const long num = static_cast<long>(r - l) * static_cast<long>(x - s.left.x);
    const long q = num >= 0 ? (2 * num + span) / (2L * span) : -((-2 * num + span) / (2L * span));
    return word(static_cast<int>(l + q));
  };
  return {word(x), at(s.left.z, s.right.z), at(s.left.r, s.right.r), at(s.left.g, s.right.g),
          at(s.left.b, s.right.b)};
}

std::int16_t unit_word(double v) {
  if (!(v > 0.0)) return 0;
  return word(static_cast<int>(std::lround(std::min(v, 1.0) * kWordMax)));
}

}  // namespace rtsim::scanline
