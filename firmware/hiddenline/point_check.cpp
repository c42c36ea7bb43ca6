#include "firmware/hiddenline/point_check.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <utility>

namespace rtsim::hiddenline {

Seen point_seen(const std::vector<std::vector<ScreenPoint>>& polygons, double x, double y, double z,
                const std::vector<std::size_t>& exclude) {
  Seen seen = Seen::kVisible;
  for (std::size_t k = 0; k < polygons.size(); ++k) {
    if (std::binary_search(exclude.begin(), exclude.end(), k)) continue;
    const auto& poly = polygons[k];
    const std::size_t n = poly.size();
    if (n < 3) continue;
    double area = 0;
    for (std::size_t i = 0; i < n; ++i) {
      const auto& p = poly[i];
      const auto& q = poly[(i + 1) % n];
      area += double(p[0]) * q[1] - double(q[0]) * p[1];
    }
    if (area == 0) continue;
    double inside = std::numeric_limits<double>::infinity();  // least distance inside an edge
    for (std::size_t i = 0; i < n; ++i) {
      const auto& p = poly[i];
      const auto& q = poly[(i + 1) % n];
      const double ex = q[0] - p[0], ey = q[1] - p[1];
      const double length = std::hypot(ex, ey);
      if (length == 0) continue;
      const double cross = ex * (y - p[1]) - ey * (x - p[0]);
      inside = std::min(inside, (area > 0 ? cross : -cross) / length);
    }
    if (inside < -kMargin) continue;
    // The plane's depth at (x, y) from the first three vertices.
    const double ux = poly[1][0] - poly[0][0], uy = poly[1][1] - poly[0][1],
                 uz = poly[1][2] - poly[0][2];
    const double wx = poly[2][0] - poly[0][0], wy = poly[2][1] - poly[0][1],
                 wz = poly[2][2] - poly[0][2];
    const double nx = uy * wz - uz * wy, ny = uz * wx - ux * wz, nz = ux * wy - uy * wx;
    if (nz == 0) continue;
    const double behind = z - (poly[0][2] - (nx * (x - poly[0][0]) + ny * (y - poly[0][1])) / nz);
    if (behind < -kMargin) continue;
    if (inside > kMargin && behind > kMargin) return Seen::kHidden;
    seen = Seen::kUnsure;
  }
  return seen;
}

PieceCheck check_pieces(const std::vector<std::vector<ScreenPoint>>& polygons,
                        const std::vector<Segment>& segments,
                        const std::vector<VisiblePiece>& pieces, int per_segment) {
  std::vector<std::vector<std::pair<double, double>>> shown(segments.size());
  for (const VisiblePiece& p : pieces)
    if (p.edge < shown.size()) shown[p.edge].emplace_back(p.t0, p.t1);
  // The polygons each edge (a pair of vertices, either way round) belongs to.
  std::map<std::pair<ScreenPoint, ScreenPoint>, std::vector<std::size_t>> owners;
  for (std::size_t k = 0; k < polygons.size(); ++k) {
    const auto& poly = polygons[k];
    for (std::size_t i = 0; i < poly.size(); ++i) {
      const ScreenPoint& a = poly[i];
      const ScreenPoint& b = poly[(i + 1) % poly.size()];
      owners[std::minmax(a, b)].push_back(k);
    }
  }
  const std::vector<std::size_t> none;
  PieceCheck c;
  for (const Segment& s : segments) {
    if (s.edge >= shown.size()) continue;
    const auto owner = owners.find(std::minmax(s.a, s.b));
    const std::vector<std::size_t>& exclude = owner != owners.end() ? owner->second : none;
    for (int j = 0; j < per_segment; ++j) {
      const double t = (j + 0.5) / per_segment;
      bool near_end = false, on = false;
      for (const auto& [t0, t1] : shown[s.edge]) {
        near_end |= std::abs(t - t0) < 1e-6 || std::abs(t - t1) < 1e-6;
        on |= t > t0 && t < t1;
      }
      if (near_end) continue;
      const Seen seen =
          point_seen(polygons, s.a[0] + t * (s.b[0] - s.a[0]), s.a[1] + t * (s.b[1] - s.a[1]),
                     s.a[2] + t * (s.b[2] - s.a[2]), exclude);
      if (seen == Seen::kUnsure) continue;
      ++c.samples;
      if (seen == Seen::kHidden) {
        ++c.hidden;
        c.drawn_hidden += on ? 1 : 0;
      } else {
        c.missed += on ? 0 : 1;
      }
    }
  }
  return c;
}

}  // namespace rtsim::hiddenline
