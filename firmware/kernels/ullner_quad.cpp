#include "firmware/kernels/ullner_quad.hpp"

#include <algorithm>
#include <cmath>

#include "firmware/kernels/ullner_quad_words.hpp"

namespace rtsim::kernels {

std::string_view to_string(QuadRejection r) {
  switch (r) {
    case QuadRejection::None:
      return "none";
    case QuadRejection::NonFiniteVertex:
      return "non-finite vertex";
    case QuadRejection::ZeroArea:
      return "zero area";
    case QuadRejection::NonPlanar:
      return "non-planar";
    case QuadRejection::NonConvex:
      return "non-convex";
  }
  return "unknown";
}

std::string_view to_string(QuadFamily f) {
  switch (f) {
    case QuadFamily::Quadratic:
      return "quadratic";
    case QuadFamily::Parallel:
      return "parallel";
    case QuadFamily::Pencil:
      return "pencil";
    case QuadFamily::Deflated:
      return "deflated";
  }
  return "unknown";
}

namespace {

/// One coordinate's family, in double, before rounding to T: the "B" vector/scalar and the "C"
/// vector/scalar of solve_coordinate, the family kind, the branch bit of the quadratic and, for
/// the parallel forms, the references of the pole thresholds.
struct FamilyCoefficients {
  Vec3 a{0.0};
  double a0 = 0.0;
  Vec3 c{0.0};
  double c0 = 0.0;
  QuadFamily family = QuadFamily::Quadratic;
  double pole_b = 0.0;    ///< |a| * size: B at distance `size` from the line B = 0
  double pole_c = 0.0;    ///< |c| * size
  bool plus_root = true;  ///< quadratic: the real root is -B + sqrt(B^2 - C)
};

/// Quadratic or parallel form from the thesis coefficients d2 x^2 + (n_lin.q + d1) x +
/// (n_const.q + d0) = 0. `parallel` is the host's decision.
FamilyCoefficients thesis_family(const Vec3& n_lin, double d2, double d1, const Vec3& n_const,
                                 double d0, bool parallel, QuadFamily parallel_kind,
                                 const std::array<Vec3, 4>& corners, double size) {
  FamilyCoefficients f;
  if (parallel) {
    // L380 / L408: x = -(n_const.p_r + d0) / (n_lin.p_r + d1); stored unscaled (L538-L542).
    f.a = n_lin;
    f.a0 = d1;
    f.c = n_const;
    f.c0 = d0;
    f.family = parallel_kind;
    // B = n_lin.q + d1 and C = n_const.q + d0 vanish on two lines through the pencil's centre;
    // |B| / |n_lin| and |C| / |n_const| are the distances to them. Only a pencil's centre is a
    // point of the quad (its collapsed vertex, where -C / B is 0 / 0). Where two opposite edges
    // are parallel but whole, the constant-x lines meet, if at all, beyond an edge longer than
    // the collapse tolerance, and -C / B is a well-conditioned division everywhere on the quad:
    // no pole to accept, so no threshold to store (which lets the pipeline's 21-word description
    // carry every threshold there is, ullner_description_words.hpp).
    if (parallel_kind == QuadFamily::Pencil) {
      f.pole_b = glm::length(n_lin) * size;
      f.pole_c = glm::length(n_const) * size;
    }
  } else {
    // L370 / L404: prescaled by 1/(2 d2) and 1/d2 (L538-L542, with the 2d_u1 -> 2d_u2 erratum).
    f.a = n_lin / (2.0 * d2);
    f.a0 = d1 / (2.0 * d2);
    f.c = n_const / d2;
    f.c0 = d0 / d2;
    f.family = QuadFamily::Quadratic;
    // Branch bit: at the quad's centre p(1/2, 1/2) (the mean of the corners) the real root is
    // 1/2; the other root is elsewhere (the discriminant vanishes nowhere inside a convex quad).
    // Roots in the stable form: q = -B - sgn(B) s is the "+" root -B + s exactly when B < 0.
    const Vec3 centre = 0.25 * (corners[0] + corners[1] + corners[2] + corners[3]);
    const double B = glm::dot(f.a, centre) + f.a0;
    const double C = glm::dot(f.c, centre) + f.c0;
    const double s = std::sqrt(std::max(B * B - C, 0.0));
    const double q = B >= 0.0 ? -B - s : -B + s;
    const double other = q != 0.0 ? C / q : 0.0;
    const bool q_is_real = std::fabs(q - 0.5) <= std::fabs(other - 0.5);
    f.plus_root = q_is_real == (B < 0.0);
  }
  return f;
}

/// The family whose own edge collapsed (triangle given as a quad). Its constant-x lines are all
/// parallel to the remaining edge e, and n_x(x) has a factor (1 - x) or x that vanishes at the
/// collapsed edge, so the thesis quadratic has a spurious root there exactly. Dividing it out
/// leaves x = m.(q - p00) / (m.span), m = e x n_p, span = the vector from p00 along which x runs
/// (p_c for v, p_b for u). Stored in the parallel slots as B = 1 (a = 0, a0 = 1),
/// C = -(m.q - m.p00) / (m.span), so the same hardware computes x = -C / B.
FamilyCoefficients deflated_family(const Vec3& e, const Vec3& n_p, const Vec3& p00,
                                   const Vec3& span) {
  FamilyCoefficients f;
  const Vec3 m = glm::cross(e, n_p);
  const double den = glm::dot(m, span);
  f.a = Vec3(0.0);
  f.a0 = 1.0;
  f.c = -m / den;
  f.c0 = glm::dot(m, p00) / den;
  f.family = QuadFamily::Deflated;
  // B is identically 1 and a = 0, so pole_b = 0: the pole test never fires.
  return f;
}

template <typename T>
void store(UllnerQuadParams<T>& P, QuadParam first, const Vec3& v) {
  P[first] = static_cast<T>(v.x);
  P[static_cast<QuadParam>(static_cast<int>(first) + 1)] = static_cast<T>(v.y);
  P[static_cast<QuadParam>(static_cast<int>(first) + 2)] = static_cast<T>(v.z);
}

}  // namespace

template <typename T>
UllnerQuadPrecompute<T> UllnerQuadParams<T>::precompute_checked(const Vec3& p00_in,
                                                                const Vec3& p10_in,
                                                                const Vec3& p11_in,
                                                                const Vec3& p01_in) {
  UllnerQuadPrecompute<T> out;
  std::array<Vec3, 4> c = {p00_in, p10_in, p11_in, p01_in};  // p00, p10, p11, p01: CCW order
  for (const Vec3& p : c) {
    if (!is_finite(p)) {
      out.rejection = QuadRejection::NonFiniteVertex;
      return out;
    }
  }
  // Scale of the quad: the longer diagonal.
  const double diag = std::max(glm::length(c[2] - c[0]), glm::length(c[3] - c[1]));
  const double edge_max = std::max({glm::length(c[1] - c[0]), glm::length(c[2] - c[1]),
                                    glm::length(c[3] - c[2]), glm::length(c[0] - c[3])});
  const double scale = std::max(diag, edge_max);
  if (!(scale > 0.0) || !std::isfinite(scale)) {
    out.rejection = QuadRejection::ZeroArea;
    return out;
  }

  // Collapsed edges (triangle as a quad with two equal vertices). Edge k joins corner k and k+1
  // in CCW order: 0 = v=0 edge (p00-p10), 1 = u=1 edge (p10-p11), 2 = v=1 edge (p11-p01),
  // 3 = u=0 edge (p01-p00).
  int collapsed = -1;
  for (int k = 0; k < 4; ++k) {
    const auto i = static_cast<std::size_t>(k), j = static_cast<std::size_t>((k + 1) % 4);
    if (glm::length(c[j] - c[i]) <= UllnerArithmetic<T>::kRangeTolerance * scale) {
      if (collapsed >= 0) {  // two collapsed edges: a segment or a point
        out.rejection = QuadRejection::ZeroArea;
        return out;
      }
      collapsed = k;
    }
  }
  if (collapsed >= 0) {  // snap the two vertices together
    const auto i = static_cast<std::size_t>(collapsed);
    const auto j = static_cast<std::size_t>((collapsed + 1) % 4);
    const Vec3 m = 0.5 * (c[i] + c[j]);
    c[i] = m;
    c[j] = m;
  }
  const Vec3& p00 = c[0];
  const Vec3& p10 = c[1];
  const Vec3& p11 = c[2];
  const Vec3& p01 = c[3];

  // L287-L291: bilinear coefficients.
  const Vec3 p_a = p00 - p01 + p11 - p10;
  const Vec3 p_b = p10 - p00;
  const Vec3 p_c = p01 - p00;
  const Vec3 p_d = p00;

  // n_p (L295): unit normal from the cross product of the diagonals, which is twice the (vector)
  // area of a planar quad and of a triangle with a collapsed edge alike; it points to the side
  // from which p00, p10, p11, p01 run counter-clockwise.
  const Vec3 area2 = glm::cross(p11 - p00, p01 - p10);
  const double area2_len = glm::length(area2);
  if (!(area2_len > kUllnerMinRelativeArea * scale * scale)) {
    out.rejection = QuadRejection::ZeroArea;
    return out;
  }
  const Vec3 n_p = area2 / area2_len;
  // d_p (L295-L297): s_p(q) = n_p.q + d_p vanishes on the plane; the plane passes through the
  // vertex centroid (the least-squares choice for slightly non-planar input).
  const Vec3 centroid = 0.25 * (p00 + p10 + p11 + p01);
  const double d_p = -glm::dot(n_p, centroid);
  for (const Vec3& p : c) {
    if (std::fabs(glm::dot(n_p, p) + d_p) > kUllnerPlanarityTolerance * scale) {
      out.rejection = QuadRejection::NonPlanar;
      return out;
    }
  }
  // Convexity (L320-L326): every corner turns left about n_p. Corners on a collapsed edge are
  // skipped; the remaining triangle is convex and its orientation is n_p's by construction.
  for (int k = 0; k < 4; ++k) {
    if (collapsed == k || collapsed == (k + 3) % 4) continue;  // edges k-1 and k meet at k
    const auto i = static_cast<std::size_t>(k);
    const Vec3 e_in = c[i] - c[(i + 3) % 4];
    const Vec3 e_out = c[(i + 1) % 4] - c[i];
    const double s = glm::dot(glm::cross(e_in, e_out), n_p);
    if (s < -kUllnerConvexitySine * glm::length(e_in) * glm::length(e_out)) {
      out.rejection = QuadRejection::NonConvex;
      return out;
    }
  }

  // L338-L343, L388-L390: normals of the constant-u and constant-v plane families.
  const Vec3 n_a = glm::cross(p_a, n_p);
  const Vec3 n_b = glm::cross(p_b, n_p);
  const Vec3 n_c = glm::cross(p_c, n_p);
  // L349-L354: d_u(u) = d_u2 u^2 + d_u1 u + d_u0.
  const double d_u2 = -glm::dot(n_a, p_b);
  const double d_u1 = -(glm::dot(n_a, p_d) + glm::dot(n_c, p_b));
  const double d_u0 = -glm::dot(n_c, p_d);
  // L392-L394: d_v(v) = d_v2 v^2 + d_v1 v + d_v0.
  const double d_v2 = -glm::dot(n_a, p_c);
  const double d_v1 = -(glm::dot(n_a, p_d) + glm::dot(n_b, p_c));
  const double d_v0 = -glm::dot(n_b, p_d);

  // Edges: e_v0 = p10 - p00 (v = 0), e_v1 = p11 - p01 (v = 1), e_u0 = p01 - p00 (u = 0),
  // e_u1 = p11 - p10 (u = 1). d_u2 = (e_v1 x e_v0).n_p and d_v2 = (e_u1 x e_u0).n_p, so
  // |d_u2| / (|e_v0| |e_v1|) is the sine of the angle between the v = 0 and v = 1 edges (L364,
  // L374: d_u2 = 0 when they are parallel). kUllnerParallelEdgeSine justifies the threshold.
  const double l_v0 = glm::length(p10 - p00), l_v1 = glm::length(p11 - p01);
  const double l_u0 = glm::length(p01 - p00), l_u1 = glm::length(p11 - p10);

  FamilyCoefficients fu, fv;
  if (collapsed == 0 || collapsed == 2) {
    // A v-edge collapsed: the constant-u lines all pass through that vertex (a pencil: the
    // parallel case of L374-L382 with d_u2 = 0 exactly), and the v family is deflated.
    fu = thesis_family(n_a, 0.0, d_u1, n_c, d_u0, true, QuadFamily::Pencil, c, scale);
    fv = deflated_family(collapsed == 0 ? p11 - p01 : p10 - p00, n_p, p00, p_c);
  } else if (collapsed == 1 || collapsed == 3) {
    fv = thesis_family(n_a, 0.0, d_v1, n_b, d_v0, true, QuadFamily::Pencil, c, scale);
    fu = deflated_family(collapsed == 3 ? p11 - p10 : p01 - p00, n_p, p00, p_b);
  } else {
    const bool u_par = std::fabs(d_u2) <= kUllnerParallelEdgeSine * l_v0 * l_v1;
    const bool v_par = std::fabs(d_v2) <= kUllnerParallelEdgeSine * l_u0 * l_u1;
    fu = thesis_family(n_a, d_u2, d_u1, n_c, d_u0, u_par, QuadFamily::Parallel, c, scale);
    fv = thesis_family(n_a, d_v2, d_v1, n_b, d_v0, v_par, QuadFamily::Parallel, c, scale);
  }

  UllnerQuadParams<T> P;
  store(P, QuadParam::n_px, n_p);
  P[QuadParam::d_p] = static_cast<T>(d_p);
  store(P, QuadParam::u_ax, fu.a);
  P[QuadParam::u_a0] = static_cast<T>(fu.a0);
  store(P, QuadParam::u_cx, fu.c);
  P[QuadParam::u_c0] = static_cast<T>(fu.c0);
  store(P, QuadParam::v_ax, fv.a);
  P[QuadParam::v_a0] = static_cast<T>(fv.a0);
  store(P, QuadParam::v_bx, fv.c);
  P[QuadParam::v_b0] = static_cast<T>(fv.c0);
  P.u_family = fu.family;
  P.v_family = fv.family;
  P.u_parallel = fu.family != QuadFamily::Quadratic;
  P.v_parallel = fv.family != QuadFamily::Quadratic;
  P.u_plus_root = fu.plus_root;
  P.v_plus_root = fv.plus_root;
  // Pole thresholds: p_r within the range tolerance times the quad's size of the pencil's
  // centre, the same band the range test gives the edges.
  constexpr double tol = UllnerArithmetic<T>::kRangeTolerance;
  P.u_pole_b = static_cast<T>(tol * fu.pole_b);
  P.u_pole_c = static_cast<T>(tol * fu.pole_c);
  P.v_pole_b = static_cast<T>(tol * fv.pole_b);
  P.v_pole_c = static_cast<T>(tol * fv.pole_c);
  for (const T w : P.word) {
    if (!std::isfinite(w)) {  // only reachable for absurd inputs (overflow of a rounded value)
      out.rejection = QuadRejection::ZeroArea;
      return out;
    }
  }
  out.params = P;
  return out;
}

template struct UllnerQuadParams<float>;
template struct UllnerQuadParams<double>;

// ---------------------------------------------------------------------------------------------
// Adapter.
// ---------------------------------------------------------------------------------------------

std::optional<UllnerQuadKernel> UllnerQuadKernel::from(const Vec3& p00, const Vec3& p10,
                                                       const Vec3& p11, const Vec3& p01,
                                                       const Vec3* corner_normals) {
  QuadRejection why = QuadRejection::None;
  return from(p00, p10, p11, p01, corner_normals, why);
}

std::optional<UllnerQuadKernel> UllnerQuadKernel::from(const Vec3& p00, const Vec3& p10,
                                                       const Vec3& p11, const Vec3& p01,
                                                       const Vec3* corner_normals,
                                                       QuadRejection& why) {
  auto pre = UllnerQuadParams<double>::precompute_checked(p00, p10, p11, p01);
  why = pre.rejection;
  if (!pre.params) return std::nullopt;
  UllnerQuadKernel k;
  k.params = as_stored(*pre.params);
  k.box.extend(p00);
  k.box.extend(p10);
  k.box.extend(p11);
  k.box.extend(p01);
  if (corner_normals != nullptr) {
    std::array<Vec3, 4> n{};  // n00, n10, n11, n01
    bool ok = true;
    for (std::size_t i = 0; i < 4; ++i) {
      const double l = glm::length(corner_normals[i]);
      if (!(l > 0.0) || !std::isfinite(l)) {
        ok = false;
        break;
      }
      n[i] = corner_normals[i] / l;
    }
    if (ok) {
      // L454: n_r = (n00 - n01 + n11 - n10) uv + (n10 - n00) u + (n01 - n00) v + n00.
      k.nrm_a = n[0] - n[3] + n[2] - n[1];
      k.nrm_b = n[1] - n[0];
      k.nrm_c = n[3] - n[0];
      k.nrm_d = n[0];
      k.has_corner_normals = true;
    }
  }
  return k;
}

bool UllnerQuadKernel::intersect_with(const UllnerQuadParams<double>& P, const Ray& ray,
                                      double t_min, double t_max, SurfaceHit& hit) const {
  const auto r =
      kernels::intersect(P, UllnerRay<double>::make(ray.origin, ray.direction), t_min, t_max);
  if (!r.hit()) return false;
  hit.t = r.t;
  hit.u = r.u;
  hit.v = r.v;
  hit.geometric_normal = P.n_p();
  hit.shading_normal = shading_normal_at(r.u, r.v, hit.geometric_normal);
  return true;
}

Vec3 ullner_shading_normal(const Vec3& nrm_a, const Vec3& nrm_b, const Vec3& nrm_c,
                           const Vec3& nrm_d, double u, double v, const Vec3& n_p) {
  // L452-L456: interpolate, then normalise ("must be normalized before it can be used").
  const Vec3 n = nrm_a * (u * v) + nrm_b * u + nrm_c * v + nrm_d;
  const double l = glm::length(n);
  return l > kUllnerMinShadingNormalLength && std::isfinite(l) ? n / l : n_p;
}

Vec3 UllnerQuadKernel::shading_normal_at(double u, double v, const Vec3& n_p) const {
  if (!has_corner_normals) return n_p;
  return ullner_shading_normal(nrm_a, nrm_b, nrm_c, nrm_d, u, v, n_p);
}

SurfaceHit UllnerQuadKernel::surface_at(double t, double u, double v) const {
  SurfaceHit hit;
  hit.t = t;
  hit.u = u;
  hit.v = v;
  hit.geometric_normal = params.n_p();
  hit.shading_normal = shading_normal_at(u, v, hit.geometric_normal);
  return hit;
}

}  // namespace rtsim::kernels
