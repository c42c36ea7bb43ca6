#include "firmware/kernels/bezier_reference.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <glm/matrix.hpp>

namespace rtsim::kernels {

namespace {

/// Slack of the ray-frame box test, as a fraction of the problem's length scale (patch size plus
/// origin distance): double rounding in the projections is ~1e-16 of that scale, and a root on a
/// patch edge or exactly on a box face must not be pruned.
constexpr double kBoxSlack = 1e-10;
/// A Newton root counts as a root if |F| is below this fraction of the length scale (double
/// evaluation of Q and O + tD carries ~1e-16 of it; tangential roots converge only linearly).
constexpr double kResidualTolerance = 1e-11;
/// Newton stops when the parameter step is below this (|du| + |dv|) and the t step below this
/// fraction of the scale.
constexpr double kNewtonStep = 1e-15;
constexpr int kMaxNewtonIterations = 40;
/// Levenberg damping of the Newton step, relative to trace(J^t J).
constexpr double kDamping = 1e-14;
/// A root within this of [0, 1] is on the patch (edge roots come out as 1 + 1e-16) and is clamped.
constexpr double kParamSlack = 1e-9;
/// A region counts as settled when its Newton start lands on a root within this fraction of the
/// region's width outside it (roots on a shared edge of two regions).
constexpr double kRegionMargin = 0.1;

struct Search {
  const ControlNet<double>& net;
  Vec3 o, d, e1, e2;
  double inv_dd = 1.0;  // 1 / |D|^2: converts (P - O).D into t units
  double t_min, t_max;
  double scale = 1.0;  // length scale for tolerances
  double best_t = kInfinity;
  double best_u = 0.0, best_v = 0.0;
  bool found = false;
  ReferenceCounters& counters;

  /// Conservative test of a subpatch: the ray passes through the box of its control points in
  /// the frame (e1, e2, D), within [t_min, best_t]. Returns false to prune; t_lo = lower t bound.
  bool box_passes(const ControlNet<double>& sub, double& t_lo) {
    ++counters.box_tests;
    double x0 = kInfinity, x1 = -kInfinity, y0 = kInfinity, y1 = -kInfinity;
    double s0 = kInfinity, s1 = -kInfinity;
    for (const auto& row : sub.p)
      for (const auto& p : row) {
        const Vec3 w = p - o;
        const double x = glm::dot(w, e1), y = glm::dot(w, e2), s = glm::dot(w, d) * inv_dd;
        x0 = std::min(x0, x);
        x1 = std::max(x1, x);
        y0 = std::min(y0, y);
        y1 = std::max(y1, y);
        s0 = std::min(s0, s);
        s1 = std::max(s1, s);
      }
    const double tol = kBoxSlack * scale;
    t_lo = s0;
    if (x0 > tol || x1 < -tol || y0 > tol || y1 < -tol) return false;
    if (s1 < t_min - tol * std::sqrt(inv_dd) || s0 > best_t + tol * std::sqrt(inv_dd)) return false;
    return true;
  }

  /// Newton on F(u, v, t) = Q(u, v) - O - t D from (u, v, t). True if it converged to a root;
  /// (u, v, t) is then the root (not yet range-checked).
  bool newton(double& u, double& v, double& t) {
    ++counters.newton_starts;
    Vec3 q, qu, qv;
    for (int k = 0; k < kMaxNewtonIterations; ++k) {
      ++counters.newton_iterations;
      evaluate_with_derivatives(net, u, v, q, qu, qv);
      const Vec3 f = q - o - t * d;
      // Newton step J (du, dv, dt) = -f with J = [Q_u Q_v -D], solved through the normal
      // equations with a tiny Levenberg damping: where J is singular (Q_u = 0 on the teapot's
      // collapsed edges) the free direction takes no step instead of an infinite one, and
      // elsewhere the step is Newton's to a relative 1e-14.
      const glm::dmat3 jac(qu, qv, -d);  // columns
      const glm::dmat3 jt = glm::transpose(jac);
      glm::dmat3 normal = jt * jac;
      const double lambda = kDamping * (normal[0][0] + normal[1][1] + normal[2][2]);
      for (int k2 = 0; k2 < 3; ++k2) normal[k2][k2] += lambda;
      const Vec3 delta = glm::inverse(normal) * (jt * -f);
      const double du = delta.x, dv = delta.y, dt = delta.z;
      if (!std::isfinite(du) || !std::isfinite(dv) || !std::isfinite(dt)) break;
      // Projected Newton: (u, v) stay in the patch's square. Roots outside it are not wanted,
      // and at a collapsed edge (a pole) the free parameter would otherwise run away.
      const double u1 = std::clamp(u + du, 0.0, 1.0), v1 = std::clamp(v + dv, 0.0, 1.0);
      const double step = std::fabs(u1 - u) + std::fabs(v1 - v);
      u = u1;
      v = v1;
      t += dt;
      if (step < kNewtonStep && std::fabs(dt) < kNewtonStep * (scale + std::fabs(t))) break;
    }
    evaluate_with_derivatives(net, u, v, q, qu, qv);
    const double residual = glm::length(q - o - t * d);
    return residual <= kResidualTolerance * (scale + std::fabs(t) * std::sqrt(1.0 / inv_dd));
  }

  /// Keep a root if it is on the patch, in range and nearer than the best so far.
  void offer(double u, double v, double t) {
    if (u < -kParamSlack || u > 1.0 + kParamSlack || v < -kParamSlack || v > 1.0 + kParamSlack)
      return;
    if (!(t >= t_min && t <= t_max) || !(t < best_t)) return;
    best_t = t;
    best_u = std::clamp(u, 0.0, 1.0);
    best_v = std::clamp(v, 0.0, 1.0);
    found = true;
    ++counters.roots;
  }

  /// Did a Newton start from region (iu, iv, width) find that region's root? Yes if the root's
  /// parameters lie in the region (with a margin: roots on a shared edge), or if the root's point
  /// lies in the region's control-point box (with the same margin): at a collapsed edge (the
  /// teapot's lid and bottom poles) one point has a whole segment of parameters, and every region
  /// along that edge contains it.
  bool settles(const ControlNet<double>& sub, std::uint32_t iu, std::uint32_t iv, double width,
               double u, double v, double t) const {
    const double m = kRegionMargin * width;
    if (u >= iu * width - m && u <= (iu + 1) * width + m && v >= iv * width - m &&
        v <= (iv + 1) * width + m)
      return true;
    const Bounds box = control_bounds(sub);
    const Vec3 slack = kRegionMargin * box.extent() + Vec3(kBoxSlack * scale);
    const Vec3 p = o + t * d;
    return glm::all(glm::greaterThanEqual(p, box.lo - slack)) &&
           glm::all(glm::lessThanEqual(p, box.hi + slack));
  }

  void explore(const ControlNet<double>& sub, std::uint32_t iu, std::uint32_t iv, int level) {
    const double width = 1.0 / static_cast<double>(std::uint64_t{1} << level);
    if (level >= kReferenceLeafDepth) {
      double u = (iu + 0.5) * width, v = (iv + 0.5) * width;
      double t = glm::dot(evaluate(net, u, v) - o, d) * inv_dd;
      if (newton(u, v, t)) {
        offer(u, v, t);
        if (settles(sub, iu, iv, width, u, v, t)) return;  // this region's root is found
      }
      if (level >= kReferenceMaxDepth) return;
    }
    ControlNet<double> kids[4];
    split4(sub, kids);
    ++counters.subdivisions;
    std::array<double, 4> t_lo;
    std::array<int, 4> order{0, 1, 2, 3};
    std::array<bool, 4> pass;
    for (int q = 0; q < 4; ++q) pass[q] = box_passes(kids[q], t_lo[q]);
    std::sort(order.begin(), order.end(), [&](int a, int b) { return t_lo[a] < t_lo[b]; });
    for (int q : order) {
      if (!pass[q]) continue;
      if (t_lo[q] > best_t + kBoxSlack * scale * std::sqrt(inv_dd)) continue;  // best improved
      explore(kids[q], 2 * iu + static_cast<std::uint32_t>(quadrant_u_half(q)),
              2 * iv + static_cast<std::uint32_t>(quadrant_v_half(q)), level + 1);
    }
  }
};

}  // namespace

bool reference_intersect(const ControlNet<double>& net, const Ray& ray, double t_min, double t_max,
                         SurfaceHit& hit, ReferenceCounters* counters) {
  ReferenceCounters local;
  ++local.calls;
  const double dd = glm::dot(ray.direction, ray.direction);
  if (!(dd > 0.0) || !std::isfinite(dd) || !is_finite(ray.origin) || !is_finite_net(net) ||
      !(t_min <= t_max)) {
    if (counters) *counters = local;
    return false;
  }
  Search s{.net = net,
           .o = ray.origin,
           .d = ray.direction,
           .e1 = {},
           .e2 = {},
           .inv_dd = 1.0 / dd,
           .t_min = t_min,
           .t_max = t_max,
           .counters = local};
  // Orthonormal ray frame: Wang's PlaneGenerator normals (seed 002 L130-L133), normalised.
  const Vec3 dn = ray.direction / std::sqrt(dd);
  const Vec3 ad = glm::abs(dn);
  const Vec3 axis = (ad.x <= ad.y && ad.x <= ad.z) ? Vec3(1, 0, 0)
                    : (ad.y <= ad.z)               ? Vec3(0, 1, 0)
                                                   : Vec3(0, 0, 1);
  s.e1 = glm::normalize(glm::cross(axis, dn));
  s.e2 = glm::cross(dn, s.e1);
  const Bounds box = control_bounds(net);
  s.scale = glm::length(box.extent()) + glm::length(box.center() - ray.origin);

  double t_lo;
  if (s.box_passes(net, t_lo)) s.explore(net, 0, 0, 0);
  if (counters) {
    counters->calls += local.calls;
    counters->box_tests += local.box_tests;
    counters->subdivisions += local.subdivisions;
    counters->newton_starts += local.newton_starts;
    counters->newton_iterations += local.newton_iterations;
    counters->roots += local.roots;
  }
  if (!s.found) return false;
  Vec3 n;
  if (!patch_normal(net, s.best_u, s.best_v, n)) return false;
  hit.t = s.best_t;
  hit.u = s.best_u;
  hit.v = s.best_v;
  hit.geometric_normal = n;
  hit.shading_normal = n;
  return true;
}

BezierReferenceKernel BezierReferenceKernel::from(const scenes::BezierPatch& patch) {
  BezierReferenceKernel k;
  k.net_ = control_net_from(patch);
  k.valid_ = is_finite_net(k.net_);
  if (k.valid_) k.bounds_ = control_bounds(k.net_);
  return k;
}

bool BezierReferenceKernel::intersect(const Ray& ray, double t_min, double t_max, SurfaceHit& hit,
                                      ReferenceCounters* counters) const {
  if (!valid_) return false;
  return reference_intersect(net_, ray, t_min, t_max, hit, counters);
}

}  // namespace rtsim::kernels
