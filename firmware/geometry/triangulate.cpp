#include "firmware/geometry/triangulate.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "firmware/geometry/self_crossing.hpp"

namespace rtsim::geometry {
namespace {

struct P2 {
  double x = 0.0, y = 0.0;
};

P2 operator-(P2 a, P2 b) { return {a.x - b.x, a.y - b.y}; }
double cross(P2 a, P2 b) { return a.x * b.y - a.y * b.x; }
double length(P2 a) { return std::hypot(a.x, a.y); }
bool same(P2 a, P2 b) { return a.x == b.x && a.y == b.y; }

/// Newell's normal: twice the vector area of the polygon, for any (even non-planar) vertex
/// loop, pointing so that the loop is counter-clockwise about it. Computed about the centroid to
/// keep the products small for polygons far from the origin.
Vec3 newell_normal(const std::vector<Vec3>& v, const Vec3& centre) {
  Vec3 n(0.0);
  const std::size_t count = v.size();
  for (std::size_t i = 0; i < count; ++i) {
    const Vec3 a = v[i] - centre;
    const Vec3 b = v[(i + 1) % count] - centre;
    n.x += (a.y - b.y) * (a.z + b.z);
    n.y += (a.z - b.z) * (a.x + b.x);
    n.z += (a.x - b.x) * (a.y + b.y);
  }
  return n;
}

/// Ear clipping over a cyclic doubly linked list of projected vertices.
class EarClipper {
 public:
  EarClipper(std::vector<P2> pts, std::vector<std::uint32_t> ids, double diameter, EarChoice choice)
      : p_(std::move(pts)), id_(std::move(ids)), diameter_(diameter), choice_(choice) {
    const std::size_t n = p_.size();
    prev_.resize(n);
    next_.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
      prev_[i] = (i + n - 1) % n;
      next_[i] = (i + 1) % n;
    }
    remaining_ = n;
    alive_.assign(n, true);
    sine_.resize(n);
    for (std::size_t i = 0; i < n; ++i) sine_[i] = corner_sine(i);
    build_grid();
  }

  void run(TriangulationResult& out) {
    std::size_t i = 0;
    std::size_t misses = 0;  // ear tests failed since the last clip
    while (remaining_ > 3) {
      if (choice_ == EarChoice::BestShaped && remaining_ <= kBestEarVertexLimit) {
        const std::size_t best = best_shaped_ear();
        if (best != kNone) {
          i = next_[best];
          clip(best, out);
        } else {
          i = force(i, out);
        }
        continue;
      }
      if (is_ear(i)) {
        const std::size_t after = next_[i];
        clip(i, out);
        i = next_[after];  // skip one: balanced, non-fan triangles on convex runs
        misses = 0;
        continue;
      }
      i = next_[i];
      if (++misses <= remaining_) continue;
      i = force(i, out);
      misses = 0;
    }
    if (remaining_ == 3 && sine_[i] > kCollinearRelativeSine) clip(i, out);
    out.ear_vertex_tests = vertex_tests_;
  }

 private:
  /// Sine of the turn at corner j (positive: convex for the CCW polygon).
  double corner_sine(std::size_t j) const {
    const P2 e1 = p_[j] - p_[prev_[j]];
    const P2 e2 = p_[next_[j]] - p_[j];
    const double l = length(e1) * length(e2);
    if (!(l > 0.0)) return 0.0;
    return cross(e1, e2) / l;
  }

  /// No ear could be found (a full cycle without one, or none at all): the polygon self-
  /// intersects or is numerically degenerate. Clips the most convex corner anyway, or drops a flat
  /// one; returns the vertex to go on from.
  std::size_t force(std::size_t i, TriangulationResult& out) {
    if (!out.not_simple) {
      out.not_simple = true;
      out.warnings.emplace_back(
          "no valid ear found (self-intersecting or numerically degenerate polygon); "
          "clipped the most convex corners");
    }
    std::size_t best = i;
    double best_sine = -2.0;
    std::size_t j = i;
    for (std::size_t k = 0; k < remaining_; ++k, j = next_[j]) {
      const double s = sine_[j];
      if (s > best_sine) {
        best_sine = s;
        best = j;
      }
    }
    if (best_sine > kCollinearRelativeSine) {
      clip(best, out);
    } else {
      unlink(best);  // flat or reflex everywhere: no area left to cover here
    }
    return next_[best];
  }

  /// The ear whose triangle has the largest smallest angle sine (the first such in input order),
  /// or kNone when there is no ear.
  std::size_t best_shaped_ear() const {
    std::size_t best = kNone;
    double best_quality = -kInfinity;
    std::size_t j = head_;
    for (std::size_t k = 0; k < remaining_; ++k, j = next_[j]) {
      if (!is_ear(j)) continue;
      const P2 a = p_[prev_[j]], b = p_[j], c = p_[next_[j]];
      // For a triangle the turn sines at its corners are the sines of its interior angles.
      const double quality = std::min({sine_[j], turn_sine(b, c, a), turn_sine(c, a, b)});
      if (quality > best_quality) {
        best_quality = quality;
        best = j;
      }
    }
    return best;
  }

  static double turn_sine(P2 a, P2 b, P2 c) {
    const P2 e1 = b - a, e2 = c - b;
    const double l = length(e1) * length(e2);
    return l > 0.0 ? cross(e1, e2) / l : 0.0;
  }

  /// An ear (a, b, c) under test, with each edge's containment slack times its length worked out
  /// once for all the vertices tested against it.
  struct Ear {
    std::size_t ia, i, ic;
    P2 a, b, c;
    double ab, bc, ca;  ///< -slack * |edge|
  };

  Ear ear_at(std::size_t i) const {
    const double slack = kEarContainmentRelative * diameter_;
    Ear e{prev_[i], i, next_[i], p_[prev_[i]], p_[i], p_[next_[i]], 0.0, 0.0, 0.0};
    e.ab = -slack * length(e.b - e.a);
    e.bc = -slack * length(e.c - e.b);
    e.ca = -slack * length(e.a - e.c);
    return e;
  }

  static bool inside_or_on(const Ear& e, P2 q) {
    // cross(edge, q - start) = |edge| * signed distance of q from the edge (positive inside).
    return cross(e.b - e.a, q - e.a) >= e.ab && cross(e.c - e.b, q - e.b) >= e.bc &&
           cross(e.a - e.c, q - e.c) >= e.ca;
  }

  /// Vertex j blocks the ear: a remaining vertex other than the ear's corners that is not
  /// strictly convex and lies inside or on it.
  bool blocks(std::size_t j, const Ear& e) const {
    ++vertex_tests_;
    if (!alive_[j] || j == e.ia || j == e.i || j == e.ic) return false;
    if (sine_[j] > kCollinearRelativeSine) return false;
    const P2 q = p_[j];
    if (same(q, e.a) || same(q, e.b) || same(q, e.c)) return false;
    return inside_or_on(e, q);
  }

  bool is_ear(std::size_t i) const {
    if (sine_[i] <= kCollinearRelativeSine) return false;  // reflex or flat
    const Ear e = ear_at(i);
    // Only a vertex that is not strictly convex can lie inside an ear of a simple polygon; a
    // vertex at the same place as a corner (a polygon touching itself) does not block it. The
    // grid gives the vertices near the ear: those in the cells that the ear, grown by the
    // containment slack, covers.
    double lo_x = 0.0, lo_y = 0.0, hi_x = 0.0, hi_y = 0.0;
    const bool bounded = slack_bounds(e.a, e.b, e.c, lo_x, lo_y, hi_x, hi_y);
    const std::size_t x0 = cell_x(lo_x), x1 = cell_x(hi_x);
    const std::size_t y0 = cell_y(lo_y), y1 = cell_y(hi_y);
    // A thin ear that bounds nothing, or a large one over more cells than vertices remain: the
    // list of remaining vertices is the shorter search.
    if (!bounded || (x1 - x0 + 1) * (y1 - y0 + 1) > remaining_) {
      for (std::size_t j = next_[e.ic]; j != e.ia; j = next_[j]) {
        if (blocks(j, e)) return false;
      }
      return true;
    }
    for (std::size_t y = y0; y <= y1; ++y) {
      for (std::size_t x = x0; x <= x1; ++x) {
        const std::size_t cell = y * cells_x_ + x;
        for (std::size_t k = cell_start_[cell]; k < cell_start_[cell + 1]; ++k) {
          if (blocks(cell_vertex_[k], e)) return false;
        }
      }
    }
    for (const std::size_t j : late_blockers_) {
      if (blocks(j, e)) return false;
    }
    return true;
  }

  /// Bounds of every point inside_or_on(a, b, c, .) accepts: the triangle with each edge moved
  /// out by the slack is the triangle scaled about its incentre by (r + slack) / r, r the
  /// inradius. False when the triangle is too thin for that to bound anything usefully.
  bool slack_bounds(P2 a, P2 b, P2 c, double& lo_x, double& lo_y, double& hi_x,
                    double& hi_y) const {
    const double la = length(c - b), lb = length(a - c), lc = length(b - a);
    const double perimeter = la + lb + lc;
    const double twice_area = cross(b - a, c - a);
    if (!(perimeter > 0.0) || !(twice_area > 0.0)) return false;
    const double r = twice_area / perimeter;
    const double slack = kEarContainmentRelative * diameter_;
    const double scale = (r + slack) / r;
    if (!(scale < kMaxSlackScale)) return false;
    const P2 centre{(la * a.x + lb * b.x + lc * c.x) / perimeter,
                    (la * a.y + lb * b.y + lc * c.y) / perimeter};
    lo_x = hi_x = centre.x;
    lo_y = hi_y = centre.y;
    for (const P2 v : {a, b, c}) {
      const double x = centre.x + (v.x - centre.x) * scale;
      const double y = centre.y + (v.y - centre.y) * scale;
      lo_x = std::min(lo_x, x);
      hi_x = std::max(hi_x, x);
      lo_y = std::min(lo_y, y);
      hi_y = std::max(hi_y, y);
    }
    // Rounding in the tests and in these bounds: a margin far above it, far below any ear.
    const double margin = slack + kGridMarginRelative * diameter_;
    lo_x -= margin;
    lo_y -= margin;
    hi_x += margin;
    hi_y += margin;
    return true;
  }

  /// The grid of the remaining vertices that may block an ear (those not strictly convex; a
  /// convex corner stays convex as ears are clipped, and one that does not joins late_blockers_):
  /// about one remaining vertex per cell, over the polygon's projected bounding box. Rebuilt
  /// from the remaining vertices each time half of them have been clipped, so clipped vertices do
  /// not pile up in it (O(n) in all).
  void build_grid() {
    if (cell_start_.empty()) {
      grid_lo_ = grid_hi_ = p_[0];
      for (const P2 q : p_) {
        grid_lo_.x = std::min(grid_lo_.x, q.x);
        grid_lo_.y = std::min(grid_lo_.y, q.y);
        grid_hi_.x = std::max(grid_hi_.x, q.x);
        grid_hi_.y = std::max(grid_hi_.y, q.y);
      }
      in_grid_.assign(p_.size(), false);
    }
    // Square cells, about as many as remaining vertices (a long thin polygon gets a long thin
    // grid, not long thin cells).
    const double w = grid_hi_.x - grid_lo_.x, h = grid_hi_.y - grid_lo_.y;
    const double n = static_cast<double>(remaining_);
    const double cell = std::sqrt(std::max(w * h, std::max(w, h) * std::max(w, h) / n) / n);
    const auto cells_along = [&](double extent) {
      return cell > 0.0 ? static_cast<std::size_t>(std::clamp(std::ceil(extent / cell), 1.0, n))
                        : std::size_t{1};
    };
    cells_x_ = cells_along(w);
    cells_y_ = cells_along(h);
    inv_cell_x_ = w > 0.0 ? static_cast<double>(cells_x_) / w : 0.0;
    inv_cell_y_ = h > 0.0 ? static_cast<double>(cells_y_) / h : 0.0;
    cell_start_.assign(cells_x_ * cells_y_ + 1, 0);
    late_blockers_.clear();
    std::vector<std::pair<std::size_t, std::size_t>> entries;  // (cell, vertex)
    std::size_t j = head_;
    for (std::size_t k = 0; k < remaining_; ++k, j = next_[j]) {
      in_grid_[j] = sine_[j] <= kCollinearRelativeSine;
      if (!in_grid_[j]) continue;
      entries.emplace_back(cell_y(p_[j].y) * cells_x_ + cell_x(p_[j].x), j);
      ++cell_start_[entries.back().first + 1];
    }
    for (std::size_t c = 0; c + 1 < cell_start_.size(); ++c) cell_start_[c + 1] += cell_start_[c];
    cell_vertex_.resize(entries.size());
    std::vector<std::size_t> fill(cell_start_.begin(), cell_start_.end() - 1);
    for (const auto& [cell, vertex] : entries) cell_vertex_[fill[cell]++] = vertex;
    grid_remaining_ = remaining_;
  }

  /// Recomputes a corner whose neighbour was unlinked; a corner that turns non-convex and is not
  /// in the grid is tested with every ear from now on.
  void update_corner(std::size_t j) {
    sine_[j] = corner_sine(j);
    if (sine_[j] <= kCollinearRelativeSine && !in_grid_[j]) {
      in_grid_[j] = true;
      late_blockers_.push_back(j);
    }
  }

  std::size_t cell_x(double x) const { return cell_index(x, grid_lo_.x, inv_cell_x_, cells_x_); }
  std::size_t cell_y(double y) const { return cell_index(y, grid_lo_.y, inv_cell_y_, cells_y_); }
  static std::size_t cell_index(double v, double lo, double inv, std::size_t cells) {
    const double f = (v - lo) * inv;
    if (!(f > 0.0)) return 0;
    if (f >= static_cast<double>(cells)) return cells - 1;
    return static_cast<std::size_t>(f);
  }

  void clip(std::size_t i, TriangulationResult& out) {
    out.triangles.push_back({id_[prev_[i]], id_[i], id_[next_[i]]});
    unlink(i);
  }

  void unlink(std::size_t i) {
    if (i == head_) head_ = next_[i];  // the list runs in input order: next is the next lowest
    const std::size_t a = prev_[i], c = next_[i];
    next_[a] = c;
    prev_[c] = a;
    alive_[i] = false;
    --remaining_;
    // Only the neighbours' corners changed.
    update_corner(a);
    update_corner(c);
    if (remaining_ >= kMinGridRebuild && 2 * remaining_ < grid_remaining_) build_grid();
  }

  /// An ear whose slack-grown bounds are this many times its own is thin enough to test against
  /// every vertex instead (the grid would not narrow the search).
  static constexpr double kMaxSlackScale = 1e3;
  /// Margin of the grid search beyond the slack, relative to the diameter: above the rounding of
  /// the bounds (~1e-15), far below any ear.
  static constexpr double kGridMarginRelative = 1e-9;
  /// Below this many remaining vertices the grid is not rebuilt any more.
  static constexpr std::size_t kMinGridRebuild = 64;

  std::vector<P2> p_;
  std::vector<std::uint32_t> id_;
  std::vector<std::size_t> prev_, next_;
  std::vector<bool> alive_;
  std::vector<double> sine_;  ///< corner_sine of each remaining vertex, kept current by unlink()
  // The vertex grid: cell c holds cell_vertex_[cell_start_[c] .. cell_start_[c + 1]).
  P2 grid_lo_{}, grid_hi_{};
  std::size_t cells_x_ = 1, cells_y_ = 1;
  double inv_cell_x_ = 0.0, inv_cell_y_ = 0.0;
  std::vector<std::size_t> cell_start_, cell_vertex_;
  mutable std::size_t vertex_tests_ = 0;    ///< TriangulationResult::ear_vertex_tests
  std::size_t grid_remaining_ = 0;          ///< remaining_ when the grid was last built
  std::vector<bool> in_grid_;               ///< in the grid or in late_blockers_
  std::vector<std::size_t> late_blockers_;  ///< turned non-convex after the grid was built
  static constexpr std::size_t kNone = static_cast<std::size_t>(-1);
  std::size_t remaining_ = 0;
  std::size_t head_ = 0;  ///< the remaining vertex that comes first in the input
  double diameter_ = 1.0;
  EarChoice choice_ = EarChoice::Walk;
};

std::string format_relative(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3g", x);
  return buf;
}

}  // namespace

TriangulationResult triangulate_polygon(const std::vector<Vec3>& vertices, EarChoice choice) {
  TriangulationResult out;
  auto reject = [&out](std::string reason) {
    out.rejected = true;
    out.reason = std::move(reason);
    out.triangles.clear();
    return out;
  };
  const std::size_t n = vertices.size();
  if (n < 3) return reject("polygon has fewer than 3 vertices");
  Vec3 lo(kInfinity), hi(-kInfinity), centre(0.0);
  for (const Vec3& v : vertices) {
    if (!is_finite(v)) return reject("polygon has a non-finite vertex");
    lo = glm::min(lo, v);
    hi = glm::max(hi, v);
    centre += v;
  }
  centre /= static_cast<double>(n);
  const double diameter = glm::length(hi - lo);
  if (!(diameter > 0.0)) return reject("polygon has fewer than 3 distinct vertices");

  // Newell's normal and area.
  const Vec3 nn = newell_normal(vertices, centre);
  const double nlen = glm::length(nn);
  if (!(nlen > kPolygonDegenerateRelativeArea * diameter * diameter)) {
    return reject("polygon has zero area");
  }
  out.normal = nn / nlen;
  out.area = 0.5 * nlen;

  // Planarity: largest distance of a vertex from the plane through the centroid.
  double dev = 0.0;
  for (const Vec3& v : vertices) dev = std::fmax(dev, std::fabs(glm::dot(v - centre, out.normal)));
  out.plane_deviation = dev / diameter;
  if (out.plane_deviation > kNonPlanarRelativeTolerance) {
    out.warnings.push_back("polygon is not planar: a vertex is " +
                           format_relative(out.plane_deviation) +
                           " of the diameter off its plane (tolerance " +
                           format_relative(kNonPlanarRelativeTolerance) + ")");
  }

  // Project to the dominant plane, oriented so the polygon is counter-clockwise in 2-D.
  int k = 0;
  const Vec3 an = glm::abs(nn);
  if (an.y > an.x && an.y >= an.z) k = 1;
  if (an.z > an.x && an.z > an.y) k = 2;
  int ax = (k + 1) % 3, ay = (k + 2) % 3;
  if (nn[k] < 0.0) std::swap(ax, ay);
  auto project = [&](const Vec3& v) { return P2{v[ax] - centre[ax], v[ay] - centre[ay]}; };

  // Drop repeated consecutive vertices (3-D distance, so a non-planar copy is not merged).
  const double dup = kDuplicateRelativeDistance * diameter;
  std::vector<std::uint32_t> ids;
  ids.reserve(n);
  for (std::size_t i = 0; i < n; ++i) {
    if (!ids.empty() && glm::length(vertices[i] - vertices[ids.back()]) <= dup) {
      ++out.removed_duplicates;
      continue;
    }
    ids.push_back(static_cast<std::uint32_t>(i));
  }
  while (ids.size() > 1 && glm::length(vertices[ids.back()] - vertices[ids.front()]) <= dup) {
    ids.pop_back();
    ++out.removed_duplicates;
  }

  // Drop collinear vertices (straight runs and zero-width spikes) until none is left.
  std::vector<P2> pts;
  for (bool changed = true; changed && ids.size() >= 3;) {
    changed = false;
    pts.clear();
    for (std::uint32_t id : ids) pts.push_back(project(vertices[id]));
    std::vector<std::uint32_t> kept;
    std::vector<P2> kept_pts;
    const std::size_t m = ids.size();
    for (std::size_t i = 0; i < m; ++i) {
      // Compare against the last kept vertex so a whole straight run collapses in one pass.
      const P2 a = kept_pts.empty() ? pts[(i + m - 1) % m] : kept_pts.back();
      const P2 b = pts[i];
      const P2 c = pts[(i + 1) % m];
      const P2 e1 = b - a, e2 = c - b;
      const double l = length(e1) * length(e2);
      if (!(l > 0.0) || std::fabs(cross(e1, e2)) <= kCollinearRelativeSine * l) {
        ++out.removed_collinear;
        changed = true;
        continue;
      }
      kept.push_back(ids[i]);
      kept_pts.push_back(b);
    }
    ids.swap(kept);
  }
  if (ids.size() < 3) {
    return reject("polygon has fewer than 3 distinct, non-collinear vertices");
  }
  pts.clear();
  for (std::uint32_t id : ids) pts.push_back(project(vertices[id]));

  // An outline that crosses itself has no one interior to triangulate (its Newell area counts
  // the overlaps twice), and ear clipping on it forces ears in up to cubic time: rejected, on
  // every path (the functional renderer and every machine triangulate here).
  {
    std::vector<Point2> outline;
    outline.reserve(pts.size());
    for (const P2& p : pts) outline.push_back({p.x, p.y});
    if (const auto crossing = first_self_crossing(outline)) {
      out.not_simple = true;
      const auto edge = [&](std::size_t e) {
        return std::to_string(ids[e] + 1) + "-" + std::to_string(ids[(e + 1) % ids.size()] + 1);
      };
      return reject("polygon crosses itself (its edges from vertex " + edge(crossing->first) +
                    " and " + edge(crossing->second) + " cross)");
    }
  }

  EarClipper clipper(std::move(pts), std::move(ids), diameter, choice);
  clipper.run(out);
  if (out.triangles.empty()) return reject("polygon has zero area after removing collinear runs");

  // Self-check: for a simple polygon the triangles tile it exactly. A mismatch means the input
  // crosses itself (its Newell area counts overlaps twice) or ear clipping had to force ears.
  double covered = 0.0;
  for (const auto& t : out.triangles) {
    const Vec3 a = vertices[t[0]], b = vertices[t[1]], c = vertices[t[2]];
    covered += 0.5 * glm::dot(glm::cross(b - a, c - a), out.normal);
  }
  if (std::fabs(covered - out.area) > kAreaMismatchRelative * out.area) {
    out.not_simple = true;
    out.warnings.push_back("triangles cover " + format_relative(covered / out.area) +
                           " of the polygon's area (self-intersecting polygon?)");
  }
  return out;
}

}  // namespace rtsim::geometry
