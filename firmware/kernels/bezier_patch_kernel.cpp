#include "firmware/kernels/bezier_patch_kernel.hpp"

#include <algorithm>
#include <cmath>
#include <string>

namespace rtsim::kernels {

template <typename T>
BezierPatchKernelT<T> BezierPatchKernelT<T>::from(const scenes::BezierPatch& patch, int iterations,
                                                  int culler_key_bits,
                                                  const WangArithmetic& arithmetic) {
  if (iterations < kWangMinIterations || iterations > kWangMaxIterations)
    throw std::invalid_argument(
        "Bezier pipeline iterations must be in [" + std::to_string(kWangMinIterations) + ", " +
        std::to_string(kWangMaxIterations) + "], got " + std::to_string(iterations));
  BezierPatchKernelT k;
  k.original_ = control_net_from(patch);
  k.net_ = convert_net<T>(k.original_);
  k.iterations_ = iterations;
  if (culler_key_bits < Culler::kMinKeyBits || culler_key_bits > Culler::kKeyBits)
    throw std::invalid_argument(
        "Culler key bits must be in [" + std::to_string(Culler::kMinKeyBits) + ", " +
        std::to_string(Culler::kKeyBits) + "], got " + std::to_string(culler_key_bits));
  k.culler_.key_bits = culler_key_bits;
  k.arithmetic_ = arithmetic;
  k.wide_net_ = convert_net<double>(k.net_);
  // A net that is finite in double but overflows in float is as unusable as a NaN one.
  k.valid_ = is_finite_net(k.original_) && is_finite_net(k.net_);
  if (k.valid_) k.bounds_ = control_bounds(k.original_);
  return k;
}

template <typename T>
bool BezierPatchKernelT<T>::intersect(const Ray& ray, double t_min, double t_max, SurfaceHit& hit,
                                      WangCounters* counters) const {
  const auto start = entry(ray, t_min, t_max);
  if (!start) return false;
  if (arithmetic_.wide()) {
    // The job's single-precision words, computed on in double or stored as fixed point.
    const WangResult<double> r = wang_intersect<double>(
        wide_net_, Vec3T<double>(*start), Vec3T<double>(Vec3T<T>(ray.direction)), iterations_,
        counters, culler_, arithmetic_.words());
    return finish(r, ray, t_min, t_max, hit);
  }
  const WangResult<T> r =
      wang_intersect<T>(net_, *start, Vec3T<T>(ray.direction), iterations_, counters, culler_);
  return finish(r, ray, t_min, t_max, hit);
}

template <typename T>
std::optional<Vec3T<T>> BezierPatchKernelT<T>::entry(const Ray& ray, double t_min,
                                                     double t_max) const {
  if (!valid_ || !(t_min <= t_max) || !is_finite(ray.origin) || !is_finite(ray.direction))
    return std::nullopt;
  if (!(glm::dot(ray.direction, ray.direction) > 0.0)) return std::nullopt;
  // The host's cull: a ray that misses the box of the control points from t_min on cannot hit
  // the patch (it lies in its convex hull), so the job is not issued. The box is tested against
  // the ray's whole forward range, not t_max: a subpatch centre inside the box can project
  // before the box's entry, so a tighter test could drop a hit the pipeline would report.
  double t0 = 0.0, t1 = 0.0;
  if (!bounds_.intersect(ray, entry_t(t_min), kInfinity, t0, t1)) return std::nullopt;
  // Enter the pipeline at O + t_min D, so its "not behind" test (eq. 21) enforces t >= t_min.
  return Vec3T<T>(ray.at(entry_t(t_min)));
}

template <typename T>
template <typename R>
bool BezierPatchKernelT<T>::finish(const WangResult<R>& r, const Ray& ray, double t_min,
                                   double t_max, SurfaceHit& hit) const {
  if (!r.hit) return false;
  const double t_enter = entry_t(t_min);
  const Vec3 c(r.point);
  if (!is_finite(c)) return false;
  // t = (C - O).D with D unit (seed 002 L100). The pipeline tested (C - entry).D >= 0 in its own
  // precision; recomputed in double it can fall a rounding error short of t_enter: clamp.
  const double t = std::max(glm::dot(c - ray.origin, ray.direction), t_enter);
  if (!(t >= t_min && t <= t_max)) return false;
  // Normal from the ORIGINAL patch's partial derivatives at the tracked (u, v), in double, rather
  // than from the final subpatch: the final net's control points lie ~2^-11 of the patch apart,
  // so differences of them lose ~11 bits (in float, a normal good to only ~1e-3), while the
  // original net gives the exact normal at that parameter, and it also lets patch_normal step
  // off a degenerate edge (teapot lid and bottom poles) inside the original patch.
  Vec3 n;
  if (!patch_normal(original_, r.u, r.v, n)) return false;
  hit.t = t;
  hit.u = r.u;
  hit.v = r.v;
  hit.geometric_normal = n;
  hit.shading_normal = n;
  // The reported point is the centre of the final subpatch, which spans 2^-level of the
  // parameter range: its distance from the true surface point is bounded by the subpatch's
  // extent, at most the control box's diagonal scaled by 2^-level. Spawned rays are lifted
  // off the surface by at least this (see SurfaceHit::position_error).
  hit.position_error = glm::length(bounds_.extent()) * std::ldexp(1.0, -static_cast<int>(r.level));
  return true;
}

template class BezierPatchKernelT<float>;
template class BezierPatchKernelT<double>;
template bool BezierPatchKernelT<float>::finish(const WangResult<float>&, const Ray&, double,
                                                double, SurfaceHit&) const;
template bool BezierPatchKernelT<float>::finish(const WangResult<double>&, const Ray&, double,
                                                double, SurfaceHit&) const;
template bool BezierPatchKernelT<double>::finish(const WangResult<double>&, const Ray&, double,
                                                 double, SurfaceHit&) const;

}  // namespace rtsim::kernels
