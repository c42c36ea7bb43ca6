#include "firmware/scanline/scan_converter.hpp"

#include <algorithm>
#include <cmath>

namespace rtsim::scanline {

namespace {

struct Tracked {
  double x, z, r, g, b;
};

/// The chain's values at height y, if an edge of it spans y (top >= y > bottom).
bool track(const std::vector<EdgeEntry>& chain, double y, Tracked& out) {
  for (std::size_t i = 0; i + 1 < chain.size(); ++i) {
    const EdgeEntry& e = chain[i];
    if (!(e.y >= y && y > chain[i + 1].y)) continue;
    const double down = e.y - y;  // the increments are a unit of y down
    out = {e.x + down * e.dx, e.z + down * e.dz, e.r + down * e.dr, e.g + down * e.dg,
           e.b + down * e.db};
    return true;
  }
  return false;
}

/// Screen x in [-1, 1] as the boundary step: the step whose left edge is nearest.
int boundary_step(double x) {
  const double s = (x + 1.0) * (kWordSteps / 2.0);
  if (!std::isfinite(s)) return 0;
  return static_cast<int>(std::lround(std::clamp(s, 0.0, double(kWordSteps))));
}

}  // namespace

std::vector<Segment> scan_convert(const EdgeChains& chains, int lines, std::uint32_t polygon) {
  std::vector<Segment> out;
  if (!chains.empty() && lines > 0) {
    const double top = chains.left.front().y;
    // The first line whose centre is at or below the top vertex.
    int k = std::max(0, static_cast<int>(std::ceil(((1.0 - top) * lines - 1.0) / 2.0)));
    for (; k < lines && k < kDummyLine; ++k) {
      const double y = 1.0 - (2.0 * k + 1.0) / lines;
      Tracked l{}, r{};
      const bool has_l = track(chains.left, y, l), has_r = track(chains.right, y, r);
      if (!has_l && !has_r && y < chains.left.back().y && y < chains.right.back().y) break;
      if (!has_l || !has_r) continue;
      if (r.x < l.x) std::swap(l, r);
      const int first = boundary_step(l.x), end = boundary_step(r.x);
      if (end <= first) continue;  // covers no step
      Segment s;
      s.y = static_cast<std::int16_t>(k);
      s.left = {static_cast<std::int16_t>(first), unit_word(l.z), unit_word(l.r), unit_word(l.g),
                unit_word(l.b)};
      s.right = {static_cast<std::int16_t>(std::min(end - 1, kWordMax)), unit_word(r.z),
                 unit_word(r.r), unit_word(r.g), unit_word(r.b)};
      s.polygon = polygon;
      out.push_back(s);
    }
  }
  Segment d = dummy_segment();
  d.polygon = polygon;
  out.push_back(d);
  return out;
}

}  // namespace rtsim::scanline
