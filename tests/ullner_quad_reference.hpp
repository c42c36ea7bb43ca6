#pragma once
// Test-only helpers for the Ullner quad tests: an independent double-precision reference
// (ray-plane intersection + point-in-convex-polygon by edge sign tests, no bilinear algebra at
// all), random convex quads and rays, and the bilinear map p(u,v) for u,v checks.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <random>

#include "firmware/kernels/ullner_quad.hpp"
#include "firmware/math.hpp"

namespace rtsim::quadtest {

using Quad = std::array<Vec3, 4>;  // p00, p10, p11, p01 (counter-clockwise)

struct RefHit {
  bool plane = false;  ///< the ray meets the plane at t_min < t < t_max
  bool inside = false;
  double t = 0.0;
  Vec3 p{0.0};
  /// Signed distance of p to the nearest edge line, positive inside, divided by the quad size.
  /// Reference and kernel may legitimately disagree only where this is within the tolerance.
  double edge_distance = 0.0;
};

inline double quad_size(const Quad& q) {
  return std::max(glm::length(q[2] - q[0]), glm::length(q[3] - q[1]));
}

inline Vec3 quad_normal(const Quad& q) {
  return glm::normalize(glm::cross(q[2] - q[0], q[3] - q[1]));
}

/// Reference: plane through the vertex centroid with the diagonal-cross normal; p inside when it
/// is on the inner side of every (non-collapsed) edge.
inline RefHit reference_intersect(const Quad& q, const Vec3& o, const Vec3& d, double t_min = 0.0,
                                  double t_max = kInfinity) {
  RefHit r;
  const Vec3 n = quad_normal(q);
  const Vec3 c = 0.25 * (q[0] + q[1] + q[2] + q[3]);
  const double den = glm::dot(n, d);
  if (den == 0.0) return r;
  r.t = glm::dot(n, c - o) / den;
  if (!(r.t > t_min && r.t < t_max)) return r;
  r.plane = true;
  r.p = o + r.t * d;
  const double size = quad_size(q);
  double dmin = kInfinity;
  for (int i = 0; i < 4; ++i) {
    const Vec3& a = q[static_cast<std::size_t>(i)];
    const Vec3& b = q[static_cast<std::size_t>((i + 1) % 4)];
    const Vec3 e = b - a;
    const double l = glm::length(e);
    if (l <= 1e-12 * size) continue;  // collapsed edge of a triangle given as a quad
    dmin = std::min(dmin, glm::dot(glm::cross(e, r.p - a), n) / l);
  }
  r.edge_distance = dmin / size;
  r.inside = dmin >= 0.0;
  return r;
}

inline Vec3 bilinear(const Quad& q, double u, double v) {
  // seed 000 L285
  return (1 - u) * (1 - v) * q[0] + (1 - u) * v * q[3] + u * (1 - v) * q[1] + u * v * q[2];
}

/// Orthonormal frame (t1, t2, n) from a unit normal.
inline void frame(const Vec3& n, Vec3& t1, Vec3& t2) {
  const Vec3 a = std::fabs(n.x) < 0.7 ? Vec3(1, 0, 0) : Vec3(0, 1, 0);
  t1 = glm::normalize(glm::cross(n, a));
  t2 = glm::cross(n, t1);
}

inline Vec3 random_unit(std::mt19937_64& rng) {
  std::normal_distribution<double> g(0.0, 1.0);
  for (;;) {
    const Vec3 v(g(rng), g(rng), g(rng));
    const double l = glm::length(v);
    if (l > 1e-6) return v / l;
  }
}

/// 2-D strict convexity margin: the sine of every corner's turn must exceed this.
inline bool convex2(const std::array<glm::dvec2, 4>& p, double min_sine) {
  for (int i = 0; i < 4; ++i) {
    const auto a = p[static_cast<std::size_t>((i + 3) % 4)];
    const auto b = p[static_cast<std::size_t>(i)];
    const auto c = p[static_cast<std::size_t>((i + 1) % 4)];
    const glm::dvec2 e1 = b - a, e2 = c - b;
    const double cr = e1.x * e2.y - e1.y * e2.x;
    if (cr <= min_sine * glm::length(e1) * glm::length(e2)) return false;
  }
  return true;
}

/// Embeds 2-D points in a plane with the given frame.
inline Quad embed(const std::array<glm::dvec2, 4>& p, const Vec3& center, const Vec3& t1,
                  const Vec3& t2) {
  Quad q;
  for (std::size_t i = 0; i < 4; ++i) q[i] = center + p[i].x * t1 + p[i].y * t2;
  return q;
}

/// A random convex quad of size ~2*radius, randomly oriented, centred within `spread` of the
/// origin; corners have turning sines above min_sine.
inline Quad random_convex_quad(std::mt19937_64& rng, double radius = 1.0, double spread = 2.0,
                               double min_sine = 0.05) {
  std::uniform_real_distribution<double> U(0.0, 1.0);
  for (;;) {
    std::array<double, 4> ang{};
    for (double& a : ang) a = U(rng) * 2.0 * kPi;
    std::sort(ang.begin(), ang.end());
    std::array<glm::dvec2, 4> p{};
    for (std::size_t i = 0; i < 4; ++i) {
      const double r = radius * (0.3 + 0.7 * U(rng));
      p[i] = glm::dvec2(r * std::cos(ang[i]), r * std::sin(ang[i]));
    }
    if (!convex2(p, min_sine)) continue;
    const Vec3 n = random_unit(rng);
    Vec3 t1, t2;
    frame(n, t1, t2);
    const Vec3 c((U(rng) * 2 - 1) * spread, (U(rng) * 2 - 1) * spread, (U(rng) * 2 - 1) * spread);
    Quad q = embed(p, c, t1, t2);
    // random choice of which corner is p00
    const int k = static_cast<int>(U(rng) * 4) % 4;
    std::rotate(q.begin(), q.begin() + k, q.end());
    return q;
  }
}

/// A ray from a random point at distance [dmin, dmax] from the quad's centroid toward a random
/// point of the quad's plane within `reach` times the quad size of the centroid. Unit direction.
inline void random_ray_at(std::mt19937_64& rng, const Quad& q, Vec3& o, Vec3& d, double reach = 0.8,
                          double dmin = 2.0, double dmax = 6.0) {
  std::uniform_real_distribution<double> U(0.0, 1.0);
  const Vec3 c = 0.25 * (q[0] + q[1] + q[2] + q[3]);
  const double s = quad_size(q);
  const Vec3 n = quad_normal(q);
  Vec3 t1, t2;
  frame(n, t1, t2);
  const Vec3 target = c + (U(rng) * 2 - 1) * reach * s * t1 + (U(rng) * 2 - 1) * reach * s * t2;
  o = c + random_unit(rng) * (s * (dmin + (dmax - dmin) * U(rng)));
  d = glm::normalize(target - o);
}

/// Disagreement band: where the kernel in arithmetic T may legitimately differ from the exact
/// reference, as a signed edge distance relative to the quad size. Two sources: the range
/// tolerance (4x, for the shape factor that converts u units to distance), and the rounding of
/// p_r, which the thesis computes from t (L305, L507): t's numerator n_p.r0 + d_p has an absolute
/// error ~eps (|r0| + |p|), amplified by 1/|cos| of the ray's angle to the normal, plus
/// ~eps (|r0| + t) from p_r = (r1 - r0) t + r0. The factor 64 is a generous constant for the
/// few roundings in each step.
template <typename T>
double disagreement_band(const Quad& q, const Vec3& o, const Vec3& d, double t) {
  const double eps = std::numeric_limits<T>::epsilon();
  const double size = quad_size(q);
  double pmax = 0.0;
  for (const Vec3& p : q) pmax = std::max(pmax, max_abs_component(p));
  const double cosang = std::fabs(glm::dot(quad_normal(q), d)) / glm::length(d);
  const double scale = max_abs_component(o) + std::fabs(t) * glm::length(d) + pmax;
  return 4.0 * kernels::UllnerArithmetic<T>::kRangeTolerance +
         64.0 * eps * scale / (std::max(cosang, 1e-300) * size);
}

/// Counts over a batch of ray/quad tests of one kernel against the reference.
struct Tally {
  long rays = 0;
  long ref_hits = 0;
  long hits = 0;
  long disagree = 0;          ///< hit != reference
  long unexplained = 0;       ///< ... outside the disagreement band
  long nonfinite = 0;         ///< a reported hit with a NaN/inf t, u, v or p_r
  double max_residual = 0.0;  ///< |p(u,v) - p_r| / size over hits inside by more than the band
  double worst_unexplained = 0.0;

  void add(const Tally& o) {
    rays += o.rays;
    ref_hits += o.ref_hits;
    hits += o.hits;
    disagree += o.disagree;
    unexplained += o.unexplained;
    nonfinite += o.nonfinite;
    max_residual = std::max(max_residual, o.max_residual);
    worst_unexplained = std::max(worst_unexplained, o.worst_unexplained);
  }
  double disagree_rate() const { return rays > 0 ? double(disagree) / double(rays) : 0.0; }
};

/// One ray against one quad in arithmetic T (ray rounded to T), compared with the reference.
/// Returns the kernel's result.
/// Unexplained disagreements printed so far (the first few per test binary are shown).
inline int g_unexplained_printed = 0;

template <typename T, kernels::UllnerRootChoice kChoice = kernels::UllnerRootChoice::HostBranch>
kernels::UllnerQuadResult<T> tally_ray(const kernels::UllnerQuadParams<T>& P, const Quad& q,
                                       const Vec3& o, const Vec3& d, Tally& tally,
                                       bool print_unexplained = true) {
  const auto r = kernels::intersect<T, kChoice>(P, Vec3T<T>(o), Vec3T<T>(d));
  const RefHit ref = reference_intersect(q, o, d);
  const bool ref_hit = ref.plane && ref.inside;
  ++tally.rays;
  tally.ref_hits += ref_hit;
  tally.hits += r.hit();
  if (r.hit()) {
    const bool finite = std::isfinite(double(r.t)) && std::isfinite(double(r.u)) &&
                        std::isfinite(double(r.v)) && is_finite(Vec3(r.p_r));
    if (!finite) ++tally.nonfinite;
  }
  if (r.hit() != ref_hit) {
    ++tally.disagree;
    const double band = disagreement_band<T>(q, o, d, ref.t);
    if (!ref.plane || std::fabs(ref.edge_distance) > band) {
      ++tally.unexplained;
      tally.worst_unexplained = std::max(tally.worst_unexplained, std::fabs(ref.edge_distance));
      if (print_unexplained && g_unexplained_printed++ < 10) {
        std::printf(
            "  unexplained: kernel %d ref %d (plane %d) edge_distance %.3g band %.3g "
            "bits t%d u%d v%d u=%.9g v=%.9g\n",
            int(r.hit()), int(ref_hit), int(ref.plane), ref.edge_distance, band, int(r.t_valid),
            int(r.u_valid), int(r.v_valid), double(r.u), double(r.v));
      }
    }
  } else if (r.hit() && ref.edge_distance > disagreement_band<T>(q, o, d, ref.t)) {
    const double res =
        glm::length(bilinear(q, double(r.u), double(r.v)) - Vec3(r.p_r)) / quad_size(q);
    tally.max_residual = std::max(tally.max_residual, res);
  }
  return r;
}

}  // namespace rtsim::quadtest
