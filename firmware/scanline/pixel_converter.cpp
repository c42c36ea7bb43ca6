#include "firmware/scanline/pixel_converter.hpp"

#include <algorithm>
#include <limits>

namespace rtsim::scanline {

std::pair<int, int> covered_pixels(const Segment& s, int width, const Strip& strip) {
  // In strip k of 2^n the centre (2p + 1) S / (2w) of the screen is at (2p + 1) S 2^n / (2w) -
  // k S: in [x_l, x_r + 1) when 2 w (x_l + k S) <= (2p + 1) S 2^n < 2 w (x_r + 1 + k S).
  const std::int64_t w = width, steps = kWordSteps;
  const std::int64_t scaled = steps << strip.levels;
  const std::int64_t offset = static_cast<std::int64_t>(strip.index) * steps;
  // The smallest p whose centre is at or past `bound` (in units of 1 / (2w) steps).
  const auto first_at = [&](std::int64_t bound) {
    const std::int64_t num = bound - scaled;
    return num <= 0 ? std::int64_t{0} : (num + 2 * scaled - 1) / (2 * scaled);
  };
  const std::int64_t first = std::min(first_at(2 * w * (s.left.x + offset)), w);
  const std::int64_t end = std::min(first_at(2 * w * (s.right.x + 1 + offset)), w);
  return {static_cast<int>(first), static_cast<int>(std::max(first, end))};
}

std::pair<int, int> strip_pixels(int width, const Strip& strip) {
  // A segment over the strip's every step covers them.
  Segment all;
  all.y = 0;
  all.left.x = 0;
  all.right.x = kWordMax;
  return covered_pixels(all, width, strip);
}

void blank_pixels(PixelRow& row, int first, int end, const Color& background) {
  for (int p = first; p < end; ++p) {
    const auto i = static_cast<std::size_t>(p);
    row.colour[i] = background;
    if (!row.polygon.empty()) row.polygon[i] = -1;
    if (!row.depth.empty()) row.depth[i] = std::numeric_limits<float>::infinity();
  }
}

void paint(const Segment& s, int width, PixelRow& row, const Strip& strip) {
  const auto [first, end] = covered_pixels(s, width, strip);
  const int span = s.right.x - s.left.x;
  const double scale = static_cast<double>(1 << strip.levels);
  const double offset = static_cast<double>(strip.index) * kWordSteps;
  for (int p = first; p < end; ++p) {
    const double c = (2.0 * p + 1.0) * kWordSteps * scale / (2.0 * width) - offset;
    const double t = span > 0 ? std::clamp((c - s.left.x) / span, 0.0, 1.0) : 0.0;
    const auto lerp = [&](int a, int b) { return (a + (b - a) * t) / kWordMax; };
    const auto i = static_cast<std::size_t>(p);
    row.colour[i] =
        Color(lerp(s.left.r, s.right.r), lerp(s.left.g, s.right.g), lerp(s.left.b, s.right.b));
    if (!row.polygon.empty()) row.polygon[i] = s.polygon;
    if (!row.depth.empty()) row.depth[i] = static_cast<float>(lerp(s.left.z, s.right.z));
  }
}

}  // namespace rtsim::scanline
