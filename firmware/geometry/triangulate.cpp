#include "firmware/geometry/triangulate.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

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
    if (remaining_ == 3 && corner_sine(i) > kCollinearRelativeSine) clip(i, out);
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
      const double s = corner_sine(j);
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
      const double quality = std::min({corner_sine(j), turn_sine(b, c, a), turn_sine(c, a, b)});
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

  bool inside_or_on(P2 a, P2 b, P2 c, P2 q) const {
    const double slack = kEarContainmentRelative * diameter_;
    // cross(edge, q - start) = |edge| * signed distance of q from the edge (positive inside).
    return cross(b - a, q - a) >= -slack * length(b - a) &&
           cross(c - b, q - b) >= -slack * length(c - b) &&
           cross(a - c, q - c) >= -slack * length(a - c);
  }

  bool is_ear(std::size_t i) const {
    if (corner_sine(i) <= kCollinearRelativeSine) return false;  // reflex or flat
    const std::size_t ia = prev_[i], ic = next_[i];
    const P2 a = p_[ia], b = p_[i], c = p_[ic];
    // Only a vertex that is not strictly convex can lie inside an ear of a simple polygon; a
    // vertex at the same place as a corner (a polygon touching itself) does not block it.
    for (std::size_t j = next_[ic]; j != ia; j = next_[j]) {
      if (corner_sine(j) > kCollinearRelativeSine) continue;
      const P2 q = p_[j];
      if (same(q, a) || same(q, b) || same(q, c)) continue;
      if (inside_or_on(a, b, c, q)) return false;
    }
    return true;
  }

  void clip(std::size_t i, TriangulationResult& out) {
    out.triangles.push_back({id_[prev_[i]], id_[i], id_[next_[i]]});
    unlink(i);
  }

  void unlink(std::size_t i) {
    if (i == head_) head_ = next_[i];  // the list runs in input order: next is the next lowest
    next_[prev_[i]] = next_[i];
    prev_[next_[i]] = prev_[i];
    --remaining_;
  }

  std::vector<P2> p_;
  std::vector<std::uint32_t> id_;
  std::vector<std::size_t> prev_, next_;
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
