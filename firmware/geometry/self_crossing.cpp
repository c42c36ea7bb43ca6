#include "firmware/geometry/self_crossing.hpp"

#include <algorithm>
#include <cmath>
#include <set>

namespace rtsim::geometry {
namespace {

/// Grid steps from the polygon's centre to its farthest coordinate: coordinate differences fit
/// 31 bits with the sign, their products 61, an orientation (a difference of two) 62: exact in
/// int64.
constexpr double kSnapSteps = 536870912.0;  // 2^29

struct IPoint {
  std::int64_t x = 0, y = 0;
  friend bool operator==(const IPoint&, const IPoint&) = default;
  /// Lexicographic: the sweep line's order (x, then y: a vertical edge starts at its bottom).
  friend bool operator<(const IPoint& a, const IPoint& b) {
    return a.x != b.x ? a.x < b.x : a.y < b.y;
  }
};

/// Sign of the turn a -> b -> c: +1 counter-clockwise (c left of ab), -1 clockwise, 0 collinear.
int orientation(const IPoint& a, const IPoint& b, const IPoint& c) {
  const std::int64_t d = (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
  return (d > 0) - (d < 0);
}

struct Edge {
  IPoint left, right;  ///< left < right
  std::size_t index = 0;
};

class Sweep {
 public:
  Sweep(std::vector<Edge> edges, std::size_t vertices)
      : edges_(std::move(edges)), vertices_(vertices) {}

  std::optional<std::pair<std::size_t, std::size_t>> run() {
    struct Event {
      IPoint at;
      bool insert = false;  ///< removals first at one point: an edge ending there leaves first
      std::size_t edge = 0;
    };
    std::vector<Event> events;
    events.reserve(2 * edges_.size());
    for (std::size_t e = 0; e < edges_.size(); ++e) {
      events.push_back({edges_[e].left, true, e});
      events.push_back({edges_[e].right, false, e});
    }
    std::sort(events.begin(), events.end(), [](const Event& a, const Event& b) {
      if (a.at != b.at) return a.at < b.at;
      if (a.insert != b.insert) return !a.insert;
      return a.edge < b.edge;
    });
    const auto below = [this](std::size_t a, std::size_t b) { return edge_below(a, b); };
    std::set<std::size_t, decltype(below)> status(below);
    std::vector<std::set<std::size_t, decltype(below)>::iterator> where(edges_.size());
    for (const Event& ev : events) {
      if (ev.insert) {
        const auto it = status.insert(ev.edge).first;
        where[ev.edge] = it;
        if (it != status.begin())
          if (auto c = crossing(*std::prev(it), ev.edge)) return c;
        if (const auto next = std::next(it); next != status.end())
          if (auto c = crossing(ev.edge, *next)) return c;
      } else {
        const auto it = where[ev.edge];
        const auto next = std::next(it);
        if (it != status.begin() && next != status.end())
          if (auto c = crossing(*std::prev(it), *next)) return c;
        status.erase(it);
      }
    }
    return std::nullopt;
  }

 private:
  std::vector<Edge> edges_;
  std::size_t vertices_;

  /// Edge a lies below edge b where both meet the sweep line (exact while no two edges cross
  /// left of it, which is all the sweep needs: it stops at the first crossing).
  bool edge_below(std::size_t a, std::size_t b) const {
    if (a == b) return false;
    const Edge& s = edges_[a];
    const Edge& t = edges_[b];
    // Compare the later-starting edge's start with the other's line; a start on that line
    // (a shared vertex, a T-junction) is decided by where the edge goes.
    if (!(t.left < s.left)) {
      int o = orientation(s.left, s.right, t.left);
      if (o == 0) o = orientation(s.left, s.right, t.right);
      if (o != 0) return o > 0;
    } else {
      int o = orientation(t.left, t.right, s.left);
      if (o == 0) o = orientation(t.left, t.right, s.right);
      if (o != 0) return o < 0;
    }
    return s.index < t.index;  // on one line: crossing() says whether they overlap
  }

  bool adjacent(std::size_t i, std::size_t j) const {
    return (i + 1) % vertices_ == j || (j + 1) % vertices_ == i;
  }

  std::optional<std::pair<std::size_t, std::size_t>> crossing(std::size_t a, std::size_t b) const {
    const Edge& s = edges_[a];
    const Edge& t = edges_[b];
    if (adjacent(s.index, t.index)) return std::nullopt;
    const int o1 = orientation(s.left, s.right, t.left);
    const int o2 = orientation(s.left, s.right, t.right);
    const int o3 = orientation(t.left, t.right, s.left);
    const int o4 = orientation(t.left, t.right, s.right);
    if (!(o1 * o2 < 0 && o3 * o4 < 0)) return std::nullopt;
    return std::pair{std::min(s.index, t.index), std::max(s.index, t.index)};
  }
};

}  // namespace

std::optional<std::pair<std::size_t, std::size_t>> first_self_crossing(
    const std::vector<Point2>& outline) {
  const std::size_t n = outline.size();
  if (n < 4) return std::nullopt;  // a triangle's edges all share vertices
  double cx = 0.0, cy = 0.0;
  for (const Point2& p : outline) {
    cx += p.x;
    cy += p.y;
  }
  cx /= static_cast<double>(n);
  cy /= static_cast<double>(n);
  double extent = 0.0;
  for (const Point2& p : outline)
    extent = std::max({extent, std::fabs(p.x - cx), std::fabs(p.y - cy)});
  if (!(extent > 0.0)) return std::nullopt;
  const double scale = kSnapSteps / extent;
  std::vector<IPoint> v(n);
  for (std::size_t i = 0; i < n; ++i)
    v[i] = {std::llround((outline[i].x - cx) * scale), std::llround((outline[i].y - cy) * scale)};
  std::vector<Edge> edges;
  edges.reserve(n);
  for (std::size_t i = 0; i < n; ++i) {
    const IPoint& a = v[i];
    const IPoint& b = v[(i + 1) % n];
    if (a == b) continue;  // snapped to one point: nothing to cross
    edges.push_back(a < b ? Edge{a, b, i} : Edge{b, a, i});
  }
  return Sweep(std::move(edges), n).run();
}

}  // namespace rtsim::geometry
