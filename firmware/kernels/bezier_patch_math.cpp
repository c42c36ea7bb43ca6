#include "firmware/kernels/bezier_patch_math.hpp"

#include <algorithm>

namespace rtsim::kernels {

namespace {

/// A cross product shorter than this fraction of |Q_u| |Q_v|-scale (the squared control-net size)
/// is treated as zero: double rounding in Q_u x Q_v is ~1e-16 of that scale, so 1e-12 leaves a
/// wide margin while any real surface point of a sensible patch has a far larger value.
constexpr double kDegenerateNormal = 1e-12;

/// Parameter steps toward (1/2, 1/2) tried when the normal is degenerate at (u, v). The first is
/// below the resolution of Wang's 10-stage pipeline (2^-11, note 002 §2.8) so the nudged normal
/// belongs to the same final subpatch; the later ones handle wider degenerate regions.
constexpr double kNormalNudge[] = {1e-6, 1e-4, 1e-2, 0.1};

bool try_normal(const ControlNet<double>& net, double u, double v, double scale2, Vec3& n) {
  Vec3 q, qu, qv;
  evaluate_with_derivatives(net, u, v, q, qu, qv);
  const Vec3 c = glm::cross(qu, qv);
  const double len = glm::length(c);
  if (!(len > kDegenerateNormal * scale2) || !std::isfinite(len)) return false;
  n = c / len;
  return true;
}

}  // namespace

bool patch_normal(const ControlNet<double>& net, double u, double v, Vec3& normal) {
  const Vec3 extent = control_bounds(net).extent();
  const double scale2 = glm::dot(extent, extent);
  if (!(scale2 > 0.0) || !std::isfinite(scale2)) return false;
  if (try_normal(net, u, v, scale2, normal)) return true;
  for (double step : kNormalNudge) {
    const double su = u + std::clamp(0.5 - u, -step, step);
    const double sv = v + std::clamp(0.5 - v, -step, step);
    if (try_normal(net, su, sv, scale2, normal)) return true;
  }
  return false;
}

ControlNet<double> control_net_from(const scenes::BezierPatch& patch) {
  ControlNet<double> net;
  for (int a = 0; a < 4; ++a)
    for (int b = 0; b < 4; ++b) net.p[a][b] = patch.at(b, a);
  return net;
}

}  // namespace rtsim::kernels
