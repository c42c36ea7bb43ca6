#pragma once
// Ullner's ray / convex-quadrilateral intersection, as formulated in his thesis section 2.2
// (seed 000 L265-L456) and pipelined in section 2.3.2 (seed 000 L480-L546, Figs. 2-12 to 2-16).
//
// The polygon is the bilinear map of the unit square (seed 000 L283-L291)
//   p(u,v) = p_a uv + p_b u + p_c v + p_d,
//   p_a = p00 - p01 + p11 - p10,  p_b = p10 - p00,  p_c = p01 - p00,  p_d = p00.
// A ray r(t) = (r1 - r0) t + r0 (L271) meets the polygon's plane s_p(q) = n_p.q + d_p (L295) at
//   t = (n_p.r0 + d_p) / (n_p.(r0 - r1))                                             (L305)
// giving p_r = (r1 - r0) t + r0 (Fig. 2-12, L507). u and v are then found independently, each
// from a family of planes perpendicular to the polygon (L307-L410):
//   d_u2 u^2 + (n_a.p_r + d_u1) u + (n_c.p_r + d_u0) = 0                               (L362)
//   d_v2 v^2 + (n_a.p_r + d_v1) v + (n_b.p_r + d_v0) = 0                               (L400)
// with n_a = p_a x n_p, n_b = p_b x n_p, n_c = p_c x n_p (L343, L390) and the d's of L354/L394.
// The host stores the coefficients prescaled by 1/(2 d_u2), 1/d_u2 (L370, L404) so that
//   u = -B +- sqrt(B^2 - C),  B = (n_a/2d_u2).p_r + d_u1/2d_u2,  C = (n_c/d_u2).p_r + d_u0/d_u2,
// or, when the v = 0 and v = 1 edges are parallel (d_u2 = 0), unscaled so that
//   u = -(n_c.p_r + d_u0) / (n_a.p_r + d_u1)                                          (L380)
// (L408 prints q for p_r; it is p_r, cf. Fig. 2-12 -- seed note section 8 errata). These are the
// twenty polygon parameters of L538-L544 (L540/L541 print n_a/(2d_u1), n_a/(2d_v1); the formulas
// at L370/L404 show the divisor is 2d_u2, 2d_v2 -- errata).
//
// What this model adds to the thesis, each a named constant below:
//  * The quadratic is solved in the numerically stable form: the larger-magnitude root
//    q = -B - sgn(B) sqrt(B^2 - C) and the other root C/q. As d_u2 -> 0, B and C grow like
//    1/d_u2, q ~ -2B and C/q -> -(n_c.p_r + d_u0)/(n_a.p_r + d_u1): the formula degrades smoothly
//    into the parallel-case one. The parallel case uses the same divider with q = -B, so one
//    division per coordinate serves both cases (the host's parallel flag selects q).
//  * The host's parallel decision uses the sine of the angle between the two opposite edges
//    (a relative, scale-invariant test) instead of d_u2 == 0 exactly.
//  * The root is chosen by a host-supplied branch bit (-B + s or -B - s): over a convex quad the
//    real root stays on one branch, and the literal rule "the root in [0,1]" (L372) fails for
//    quads with a nearly collapsed edge, whose spurious root lies at ~0 or ~1 (UllnerRootChoice).
//  * Range tests on u, v accept a small tolerance, so a ray exactly through an edge or vertex of
//    two quads that share it hits at least one of them (no cracks), and the discriminant may be
//    slightly negative by rounding.
//  * A triangle given as a quad with two equal vertices works: the family of lines whose edge
//    collapsed to a point is a pencil through that vertex (stored as the parallel case; the host
//    supplies pole thresholds so a point at the apex is accepted), and the other family has a
//    spurious root at the collapsed edge (n_v(v) has the factor (1 - v) or v), which the host
//    divides out, storing the remaining linear equation in the parallel-case slots. An edge
//    shorter than the range tolerance is collapsed this way by the host.
//
// Validity bits (L522-L530): every stage produces a value and a bit. t is valid when the ray is
// not parallel to the plane, the division is finite and t_min < t < t_max (t > 0 in the thesis,
// L275). p_r inherits t's bit. u is valid when its bit from p_r is set, the root is real and the
// root on the host's branch lies in [0,1] (within the tolerance); v likewise. The hit is
// t & u & v, as the closest-hit stage sees it (L528). Non-finite intermediates (overflow in
// float) clear the bit, so no NaN/inf is ever reported with a set bit.
//
// Accuracy limits (measured in tests/ullner_quad_stress_test.cpp): the thesis computes t first
// and p_r from t, and t's numerator n_p.r0 + d_p loses ~eps |r0| absolutely, so p_r moves along
// the plane by ~eps |r0| / cos(angle to the normal); u, v are relative coordinates, so near a
// short edge (length e) or in a thin quad (height h) their error grows like 1/e, 1/h. In float
// (the thesis's 24-bit fraction) this decides rays within ~1e-5 of an edge or vertex; in double
// it is invisible except for grazing rays and edges shorter than ~1e-7 of the quad.
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <optional>
#include <string_view>
#include <type_traits>

#include "firmware/bounds.hpp"
#include "firmware/cost.hpp"
#include "firmware/hit.hpp"
#include "firmware/math.hpp"
#include "firmware/ray.hpp"

namespace rtsim::kernels {

// ---------------------------------------------------------------------------------------------
// Host-side (preprocessing) tolerances. The seed gives none; each value is an assumption with
// its reason. All are relative, so the decisions do not change when the scene is scaled.
// ---------------------------------------------------------------------------------------------

/// Opposite edges whose angle has |sin| <= this are treated as parallel (thesis: d_u2 = 0).
/// d_u2 = (e_v1 x e_v0).n_p = |e_v0||e_v1| sin(angle between the v=0 and v=1 edges), so the test
/// |d_u2| <= kUllnerParallelEdgeSine |e_v0||e_v1| compares d_u2 with the products it is made
/// of. Why 1e-9: dropping the d_u2 u^2 term changes u by about sin/sin(corner angle), i.e. by
/// ~1e-9 of the quad (far below float's 6e-8 resolution and a 512-pixel image); above it the
/// prescaled parameters stay below ~1e9 (|p|/L), so B^2 stays far from float overflow (3.4e38);
/// and it is 7 orders above the double rounding noise of d_u2 (~1e-16 |p|/L).
inline constexpr double kUllnerParallelEdgeSine = 1e-9;

/// A quad is non-planar when a vertex lies farther than this times the quad's size (its longest
/// diagonal or edge) from the fitted plane. The kernel intersects the plane, so a non-planar quad
/// would be flattened and neighbours could open cracks of that size; 1e-5 of the quad is 0.005
/// pixel even for a quad filling a 512-pixel image, and admits vertices printed with ~6 significant
/// digits.
inline constexpr double kUllnerPlanarityTolerance = 1e-5;

/// Twice the area below this times (longer diagonal)^2 is zero area (a needle or a point): the
/// cross product of the diagonals is then rounding noise and n_p has no direction.
inline constexpr double kUllnerMinRelativeArea = 1e-12;

// Collapsed edges: edges shorter than UllnerArithmetic<T>::kRangeTolerance times the quad's
// size are collapsed by precompute_checked (the two vertices snapped to their midpoint), making
// the quad an exact triangle. Near such an edge u (or v) is conditioned like 1/(edge/size), so
// rays exactly through its corners would miss half the time; the snap moves the boundary by at
// most tolerance x size / 2, the order of the band the range test and the pole test accept
// (narrower only across a thin triangle, where that band is tolerance x its height).

/// A corner whose turn has sine < -this (relative to its two edges) makes the quad non-convex
/// (seed 000 L320-L326: concave quads are excluded). Straight corners (sine ~ 0) are accepted:
/// the bilinear map stays injective; only its Jacobian vanishes at that corner.
inline constexpr double kUllnerConvexitySine = 1e-9;

/// An interpolated shading normal shorter than this (corner normals are unit) means the corner
/// normals nearly cancel there; the geometric normal is used instead.
inline constexpr double kUllnerMinShadingNormalLength = 1e-6;

/// The shading normal at (u, v) of a quad whose corner normals are interpolated as
/// nrm[0] uv + nrm[1] u + nrm[2] v + nrm[3] (seed 000 L452-L456), normalised; `n_p` where that
/// nearly vanishes or is not finite.
Vec3 ullner_shading_normal(const Vec3& nrm_a, const Vec3& nrm_b, const Vec3& nrm_c,
                           const Vec3& nrm_d, double u, double v, const Vec3& n_p);

// ---------------------------------------------------------------------------------------------
// Kernel-side tolerances, per arithmetic type.
// ---------------------------------------------------------------------------------------------

template <typename T>
struct UllnerArithmetic;

/// 32-bit float: the thesis's 24-bit fraction, 8-bit exponent format (seed 000 L582).
template <>
struct UllnerArithmetic<float> {
  /// u, v in [-tol, 1 + tol] are accepted. u is computed from p_r, whose rounding error is
  /// ~eps |p_r|; in u units that is ~eps |p_r| / L times a shape factor. 2^-14 = 512 eps covers
  /// |p_r| / L up to ~100 with margin, and the overlap it creates is 6e-5 of the quad
  /// (0.03 pixel for a quad spanning a 512-pixel image).
  static constexpr float kRangeTolerance = 6.103515625e-05f;  // 2^-14
  /// The discriminant is in u^2 units and near its zero locus grows linearly with the distance
  /// of p_r from the envelope of the constant-u lines (a fold of the bilinear map), so the same
  /// relative tolerance as the range test applies: B^2 - C >= -tol is clamped to 0.
  static constexpr float kDiscriminantTolerance = kRangeTolerance;
  /// |n_p.(r1 - r0)| <= this * ||r1 - r0||_1 means "ray parallel to the plane" (L305): the
  /// denominator is then indistinguishable from rounding noise (n_p is unit, so the rounding
  /// error of the dot product is a few eps times sum |n_pi d_i| <= ||d||_1).
  static constexpr float kRayParallelTolerance = 8.0f * std::numeric_limits<float>::epsilon();
};

template <>
struct UllnerArithmetic<double> {
  /// 2^-30 ~ 9.3e-10: covers the double rounding of u (~1e-16 |p_r|/L) for |p_r|/L up to ~1e5
  /// with margin; the overlap it creates is invisible.
  static constexpr double kRangeTolerance = 9.313225746154785e-10;  // 2^-30
  static constexpr double kDiscriminantTolerance = kRangeTolerance;
  static constexpr double kRayParallelTolerance = 8.0 * std::numeric_limits<double>::epsilon();
};

// ---------------------------------------------------------------------------------------------
// The twenty polygon parameters (seed 000 L532-L544).
// ---------------------------------------------------------------------------------------------

/// Index of each of the twenty stored parameters; one parameter memory each (L544).
/// Rows: plane (L295); u "B" term n_a/(2d_u2), d_u1/(2d_u2) (parallel: n_a, d_u1); u "C" term
/// n_c/d_u2, d_u0/d_u2 (parallel: n_c, d_u0); the same for v with n_a, d_v1 and n_b, d_v0.
// clang-format off
enum class QuadParam : std::uint8_t {
  n_px, n_py, n_pz, d_p,
  u_ax, u_ay, u_az, u_a0,
  u_cx, u_cy, u_cz, u_c0,
  v_ax, v_ay, v_az, v_a0,
  v_bx, v_by, v_bz, v_b0,
};
// clang-format on
inline constexpr std::size_t kUllnerParamCount = 20;

/// Names of the twenty parameters as the thesis writes them (non-parallel form; the parallel
/// form stores the same quantities without the 1/(2d_u2), 1/d_u2 scaling, L538-L542).
// clang-format off
inline constexpr std::array<std::string_view, kUllnerParamCount> kUllnerParamNames = {
    "n_p.x",         "n_p.y",         "n_p.z",         "d_p",
    "n_a/(2d_u2).x", "n_a/(2d_u2).y", "n_a/(2d_u2).z", "d_u1/(2d_u2)",
    "n_c/d_u2.x",    "n_c/d_u2.y",    "n_c/d_u2.z",    "d_u0/d_u2",
    "n_a/(2d_v2).x", "n_a/(2d_v2).y", "n_a/(2d_v2).z", "d_v1/(2d_v2)",
    "n_b/d_v2.x",    "n_b/d_v2.y",    "n_b/d_v2.z",    "d_v0/d_v2",
};
// clang-format on

/// Why the host rejected a quadrilateral.
enum class QuadRejection : std::uint8_t { None, NonFiniteVertex, ZeroArea, NonPlanar, NonConvex };
std::string_view to_string(QuadRejection r);

/// How the host stored one coordinate's family of constant-u (or constant-v) planes.
enum class QuadFamily : std::uint8_t {
  Quadratic,  ///< opposite edges not parallel: prescaled coefficients (L370 / L404)
  Parallel,   ///< opposite edges parallel (d_u2 = 0): unscaled coefficients (L380 / L408)
  Pencil,     ///< the opposite edge collapsed to a point (triangle): parallel form, pole there
  Deflated,   ///< an edge of this family collapsed (triangle): spurious root divided out
};
std::string_view to_string(QuadFamily f);

template <typename T>
struct UllnerQuadParams;

/// precompute's result: the parameters, or why there are none.
template <typename T>
struct UllnerQuadPrecompute {
  std::optional<UllnerQuadParams<T>> params;
  QuadRejection rejection = QuadRejection::None;
  bool ok() const { return params.has_value(); }
};

/// One polygon as the peripheral stores it: twenty T-valued parameters (fetched "640 bits at
/// once" from twenty memories, L891), the host-supplied parallel flags for u and v (the initial
/// validity bits that select the applicable branch, L530), and -- not in the thesis -- the
/// branch bits of the quadratic and the pole thresholds of the parallel form (see intersect()).
template <typename T>
struct UllnerQuadParams {
  std::array<T, kUllnerParamCount> word{};  ///< indexed by QuadParam
  bool u_parallel = false;  ///< host flag: u uses the L380 form (Parallel, Pencil, Deflated)
  bool v_parallel = false;  ///< host flag: v uses the L408 form
  bool u_plus_root = true;  ///< host flag: the real u root is -B + sqrt(B^2 - C) (quadratic only)
  bool v_plus_root = true;
  /// Parallel form: |B| <= u_pole_b and |C| <= u_pole_c means p_r lies within the range
  /// tolerance times the quad's size of the pencil's centre (B/|n_a| and C/|n_c| are the
  /// distances to two lines through it). 0 where there is no pencil centre to accept.
  T u_pole_b = T(0), u_pole_c = T(0);
  T v_pole_b = T(0), v_pole_c = T(0);
  QuadFamily u_family = QuadFamily::Quadratic;  ///< host bookkeeping; the kernel reads the flags
  QuadFamily v_family = QuadFamily::Quadratic;

  T& operator[](QuadParam p) { return word[static_cast<std::size_t>(p)]; }
  T operator[](QuadParam p) const { return word[static_cast<std::size_t>(p)]; }
  Vec3T<T> vec(QuadParam first) const {
    const auto i = static_cast<std::size_t>(first);
    return Vec3T<T>(word[i], word[i + 1], word[i + 2]);
  }
  Vec3T<T> n_p() const { return vec(QuadParam::n_px); }
  T d_p() const { return (*this)[QuadParam::d_p]; }
  Vec3T<T> u_a() const { return vec(QuadParam::u_ax); }  ///< n_a/(2d_u2) or n_a
  T u_a0() const { return (*this)[QuadParam::u_a0]; }    ///< d_u1/(2d_u2) or d_u1
  Vec3T<T> u_c() const { return vec(QuadParam::u_cx); }  ///< n_c/d_u2 or n_c
  T u_c0() const { return (*this)[QuadParam::u_c0]; }    ///< d_u0/d_u2 or d_u0
  Vec3T<T> v_a() const { return vec(QuadParam::v_ax); }  ///< n_a/(2d_v2) or n_a
  T v_a0() const { return (*this)[QuadParam::v_a0]; }    ///< d_v1/(2d_v2) or d_v1
  Vec3T<T> v_b() const { return vec(QuadParam::v_bx); }  ///< n_b/d_v2 or n_b
  T v_b0() const { return (*this)[QuadParam::v_b0]; }    ///< d_v0/d_v2 or d_v0

  /// Host preprocessing (seed 000 L283-L410), computed in double and rounded to T.
  /// Vertices are the corners of the unit square: p00 = p(0,0), p10 = p(1,0), p11 = p(1,1),
  /// p01 = p(0,1) (L283); listed p00, p10, p11, p01 they go round the quad counter-clockwise
  /// seen from the side n_p points to. A triangle may be given with two equal adjacent vertices.
  static UllnerQuadPrecompute<T> precompute_checked(const Vec3& p00, const Vec3& p10,
                                                    const Vec3& p11, const Vec3& p01);
  static std::optional<UllnerQuadParams<T>> precompute(const Vec3& p00, const Vec3& p10,
                                                       const Vec3& p11, const Vec3& p01) {
    return precompute_checked(p00, p10, p11, p01).params;
  }
};

extern template struct UllnerQuadParams<float>;
extern template struct UllnerQuadParams<double>;

/// The ray as the peripheral receives it: r0 and the per-ray difference r1 - r0, plus the
/// per-ray threshold of the "parallel to the plane" test. Formed once per ray (kSetupCost).
template <typename T>
struct UllnerRay {
  Vec3T<T> r0{T(0)};
  Vec3T<T> r1_minus_r0{T(0), T(0), T(1)};
  T parallel_threshold = T(0);  ///< kRayParallelTolerance * ||r1 - r0||_1

  static UllnerRay make(const Vec3T<T>& origin, const Vec3T<T>& r1_minus_r0) {
    UllnerRay r;
    r.r0 = origin;
    r.r1_minus_r0 = r1_minus_r0;
    r.parallel_threshold =
        UllnerArithmetic<T>::kRayParallelTolerance *
        (std::fabs(r1_minus_r0.x) + std::fabs(r1_minus_r0.y) + std::fabs(r1_minus_r0.z));
    return r;
  }
  /// 2 additions, 1 multiplication (absolute values are sign-bit operations).
  static constexpr Cost kSetupCost{.fp_add = 2, .fp_mul = 1};
};

/// What the intersection pipeline delivers to the closest-hit stage: values and validity bits.
template <typename T>
struct UllnerQuadResult {
  T t = T(0);
  Vec3T<T> p_r{T(0)};
  T u = T(0);  ///< clamped to [0,1] when u_valid
  T v = T(0);
  bool t_valid = false;  ///< ray not parallel to the plane, t finite, t_min < t < t_max
  bool u_valid = false;  ///< t_valid and a real root u in [0,1] (within the range tolerance)
  bool v_valid = false;  ///< t_valid and a real root v in [0,1]
  bool hit() const { return t_valid && u_valid && v_valid; }
};

/// How the non-parallel branch picks its root.
enum class UllnerRootChoice : std::uint8_t {
  /// The host's branch bit (u_plus_root / v_plus_root) selects -B + s or -B - s (default). Over a
  /// convex quad the discriminant does not vanish, so the real root stays on one branch; the
  /// host finds it at the quad's centre. In the spirit of L530 ("initial values for validity
  /// bits ... extinguish the inapplicable branch of the computation").
  HostBranch,
  /// The thesis as printed (L372): the root that lies in [0,1]. Fails for quads with a nearly
  /// collapsed edge, whose spurious root then lies within the range tolerance of 0 or 1 (the
  /// stress test measures it); kept for comparison.
  InRange,
};

namespace ullner_detail {

template <typename T>
inline T dot3(const Vec3T<T>& a, const Vec3T<T>& b) {
  // Written out so that the order of the additions is the pipeline's (Fig. 2-14): (x + y) + z.
  return (a.x * b.x + a.y * b.y) + a.z * b.z;
}

template <typename T>
inline bool in_unit_range(T x) {
  constexpr T tol = UllnerArithmetic<T>::kRangeTolerance;
  return x >= -tol && x <= T(1) + tol;  // false for NaN
}

/// One coordinate (u or v) from p_r: the seven-stage pipeline of Fig. 2-16 (L536).
/// a, a0: the "B" coefficients (n_a/(2d_u2), d_u1/(2d_u2), or n_a, d_u1 in the parallel case);
/// c, c0: the "C" coefficients (n_c/d_u2, d_u0/d_u2, or n_c, d_u0). `plus`: the host's branch
/// bit (the real root is -B + sqrt(B^2 - C) when set). Returns validity; writes the chosen root
/// (clamped to [0,1]) to out.
template <typename T, UllnerRootChoice kChoice>
inline bool solve_coordinate(const Vec3T<T>& a, T a0, const Vec3T<T>& c, T c0, bool parallel,
                             bool plus, T pole_b, T pole_c, const Vec3T<T>& p_r, T& out) {
  const T B = dot3(a, p_r) + a0;  // L370 first bracket; L380 denominator (parallel)
  const T C = dot3(c, p_r) + c0;  // L370 second bracket; L380 numerator (parallel)
  T r;
  if (parallel) {
    // L380: u = -C / B. At the pencil's centre (B = C = 0) every constant-u line passes through
    // p_r and u is undetermined; the host's pole threshold accepts p_r there (any u gives the
    // same point when the centre is a collapsed vertex; elsewhere the other coordinate is out of
    // range). Not in the thesis, where the division would mark u invalid.
    if (std::fabs(B) <= pole_b && std::fabs(C) <= pole_c) {
      out = T(0.5);
      return true;
    }
    r = C / -B;  // the divider of the quadratic branch, fed q = -B
  } else {
    // L370: u = -B +- sqrt(B^2 - C), stable form: q = -B - sgn(B) sqrt(B^2 - C), roots q, C/q.
    T disc = B * B - C;
    if (!(disc >= -UllnerArithmetic<T>::kDiscriminantTolerance)) return false;  // complex, NaN
    if (disc < T(0)) disc = T(0);
    const T s = std::sqrt(disc);
    const T q = (B >= T(0)) ? -B - s : -B + s;
    if (!std::isfinite(q)) return false;  // overflow: the divider's input is invalid
    // q = 0 only for B = 0 and B^2 - C = 0: a double root at 0.
    const T other = q != T(0) ? C / q : T(0);
    if constexpr (kChoice == UllnerRootChoice::HostBranch) {
      // q is the "+" root -B + s exactly when B < 0.
      r = (plus == (B < T(0))) ? q : other;
    } else {
      // L372 as printed: whichever root lies in [0,1]; if both do, the one nearer the middle.
      const bool ok1 = in_unit_range(q), ok2 = in_unit_range(other);
      r = (ok1 && (!ok2 || std::fabs(q - T(0.5)) <= std::fabs(other - T(0.5)))) ? q : other;
    }
  }
  if (!in_unit_range(r)) return false;  // L372, L382: out of range (or NaN)
  out = std::fmin(std::fmax(r, T(0)), T(1));
  return true;
}

}  // namespace ullner_detail

/// The intersection computation of Fig. 2-12 with validity bits (L522-L530).
template <typename T, UllnerRootChoice kChoice = UllnerRootChoice::HostBranch>
inline UllnerQuadResult<T> intersect(const UllnerQuadParams<T>& P, const UllnerRay<T>& ray,
                                     T t_min = T(0), T t_max = std::numeric_limits<T>::infinity()) {
  using ullner_detail::dot3;
  UllnerQuadResult<T> res;
  // Stage t (Fig. 2-14, L488-L501): q10 = n_p.r0 + d_p, q11 = n_p.(r0 - r1), t = q10 / q11.
  const Vec3T<T> n_p = P.n_p();
  const T q10 = (n_p.x * ray.r0.x + n_p.y * ray.r0.y) + (n_p.z * ray.r0.z + P.d_p());
  const T q11 = -dot3(n_p, ray.r1_minus_r0);  // n_p.(r0 - r1): the sign flip is free
  if (!(std::fabs(q11) > ray.parallel_threshold)) return res;  // L305: parallel to the plane
  res.t = q10 / q11;                                           // L305
  res.t_valid = std::isfinite(res.t) && res.t > t_min && res.t < t_max;
  if (!res.t_valid) return res;  // p_r, u, v inherit the invalid bit (L526)
  // Stage p_r (Fig. 2-15): p_r = (r1 - r0) t + r0 (L507).
  res.p_r = ray.r1_minus_r0 * res.t + ray.r0;
  // Stage u and v (Fig. 2-16), in parallel.
  res.u_valid = ullner_detail::solve_coordinate<T, kChoice>(P.u_a(), P.u_a0(), P.u_c(), P.u_c0(),
                                                            P.u_parallel, P.u_plus_root, P.u_pole_b,
                                                            P.u_pole_c, res.p_r, res.u);
  res.v_valid = ullner_detail::solve_coordinate<T, kChoice>(P.v_a(), P.v_a0(), P.v_b(), P.v_b0(),
                                                            P.v_parallel, P.v_plus_root, P.v_pole_b,
                                                            P.v_pole_c, res.p_r, res.v);
  return res;
}

/// Convenience: r0 and the direction r1 - r0 (any length; t is in units of its length, L275).
template <typename T, UllnerRootChoice kChoice = UllnerRootChoice::HostBranch>
inline UllnerQuadResult<T> intersect(const UllnerQuadParams<T>& P, const Vec3T<T>& r0,
                                     const Vec3T<T>& r1_minus_r0, T t_min = T(0),
                                     T t_max = std::numeric_limits<T>::infinity()) {
  return intersect<T, kChoice>(P, UllnerRay<T>::make(r0, r1_minus_r0), t_min, t_max);
}

/// Per-test cost of the hardware formulation above (one ray against one polygon, non-parallel
/// branch, the longer one). Comparisons count as fp_add (firmware/cost.hpp).
///   t   (Fig. 2-14): 6 mul, 5 add (q7..q11), 1 div; + 1 compare (parallel ray) + 2 (t range).
///   p_r (Fig. 2-15): 3 mul, 3 add.
///   u   (Fig. 2-16): B = a.p_r + a0 and C = c.p_r + c0: 6 mul, 6 add; B^2: 1 mul; B^2 - C: 1 add;
///        discriminant test and clamp: 2 compares; sqrt: 1; q = -B - sgn(B) s: 1 add (sgn is a
///        sign-bit select); C/q: 1 div; branch select (sign of B against the host bit): 1 compare;
///        range test of the chosen root: 2 compares
///        => 7 mul, 8 add + 5 compares, 1 div, 1 sqrt.
///   v: the same.
/// Arithmetic alone: 23 mul, 24 add, 3 div, 2 sqrt = 52 ops; the thesis counts 23 mul, 26 add,
/// 3 div, 2 sqrt = 54 (L588): the stable form needs one "-B +- s" add instead of two and shares
/// one divider between the parallel (-C/B) and non-parallel (C/q) branches.
/// Memory: the twenty 32-bit polygon parameters (L538-L544, L891) plus the four pole
/// thresholds (the parallel form's two compares replace the quadratic's, so are not added).
inline constexpr Cost kUllnerQuadPreparedTestCost{
    .fp_add = 24 + 3 + 5 + 5, .fp_mul = 23, .fp_div = 3, .fp_sqrt = 2, .mem_words = 24};

/// Adapter with the interface shared by all kernels: double arithmetic internally, unit-length
/// ray direction (so t is a distance), u/v, unit geometric normal n_p and the Phong-interpolated
/// shading normal of the corner normals (seed 000 L452-L456).
struct UllnerQuadKernel {
  /// As the peripheral stores them: rounded through its 32-bit words (ullner_quad_words.hpp,
  /// seed 000 L582), so a machine that reads them back computes exactly what this kernel does.
  UllnerQuadParams<double> params;
  Bounds box;
  /// Normal-interpolation coefficients n_r = nrm_a uv + nrm_b u + nrm_c v + nrm_d (L454; named
  /// nrm_* to keep them apart from the constant-u plane normals n_a, n_b, n_c of L343/L390).
  Vec3 nrm_a{0.0}, nrm_b{0.0}, nrm_c{0.0}, nrm_d{0.0};
  bool has_corner_normals = false;

  /// corner_normals: nullptr, or 4 normals n00, n10, n11, n01 (normalised here; a zero or
  /// non-finite one drops all four, and the geometric normal is used).
  static std::optional<UllnerQuadKernel> from(const Vec3& p00, const Vec3& p10, const Vec3& p11,
                                              const Vec3& p01,
                                              const Vec3* corner_normals = nullptr);
  /// Same, with the reason of a rejection.
  static std::optional<UllnerQuadKernel> from(const Vec3& p00, const Vec3& p10, const Vec3& p11,
                                              const Vec3& p01, const Vec3* corner_normals,
                                              QuadRejection& why);

  bool intersect(const Ray& ray, double t_min, double t_max, SurfaceHit& hit) const {
    return intersect_with(params, ray, t_min, t_max, hit);
  }
  /// The same test on parameters `P` read back from a machine's memories; the shading normal is
  /// interpolated from this kernel's corner normals (the host's copy, seed 000 L452-L456).
  bool intersect_with(const UllnerQuadParams<double>& P, const Ray& ray, double t_min, double t_max,
                      SurfaceHit& hit) const;
  /// The hit a machine reports as t and (u, v) on this polygon (the ray-tracing pipeline's
  /// result fields, seed 000 L700-L711): the host's copy gives the geometric normal and the
  /// interpolated shading normal, as intersect_with does.
  SurfaceHit surface_at(double t, double u, double v) const;
  /// The corner normals interpolated at (u, v) and normalised (L452-L456); `n_p` without them.
  Vec3 shading_normal_at(double u, double v, const Vec3& n_p) const;
  Bounds bounds() const { return box; }
  Vec3 geometric_normal() const { return params.n_p(); }

  static constexpr Cost kTestCost = UllnerRay<double>::kSetupCost + kUllnerQuadPreparedTestCost;
};

}  // namespace rtsim::kernels
