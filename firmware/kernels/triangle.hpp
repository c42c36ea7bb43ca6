#pragma once
// Watertight ray/triangle intersection after Woop, Benthin & Wald, "Watertight Ray/Triangle
// Intersection", JCGT 2(1), 2013 (the paper is not a seed; the formulation is summarised here).
//
// The ray is moved into "ray space": translate so the ray origin is at 0, permute the axes so the
// largest direction component is z, and shear so the direction becomes (0, 0, 1). The ray is then
// the intersection of the two planes x' = 0 and y' = 0 -- the same representation Ullner proposes
// for his generalised-polygon pipeline ("the ray is represented as the intersection of two
// planes", seed 000 L923-L939). In ray space the hit test is a 2-D point-in-triangle test of the
// origin against the projected vertices, done with three edge functions
//   U = Cx*By - Cy*Bx   (edge B->C, weight of A)
//   V = Ax*Cy - Ay*Cx   (edge C->A, weight of B)
//   W = Bx*Ay - By*Ax   (edge A->B, weight of C)
// and the origin is inside when U, V, W do not have mixed signs.
//
// Why it is watertight:
//  * The transformed coordinates of a vertex depend only on the vertex and the ray, so two
//    triangles that share an edge compute bit-identical edge endpoints, and the edge function of
//    the shared edge is evaluated as exactly the same two rounded products (in the other
//    triangle's cyclic order the two products swap, so its value is the exact negation).
//  * Rounding is monotone, so fl(a*b) > fl(c*d) implies a*b > c*d: comparing the two rounded
//    products gives the sign of the exact edge function or a tie, never the wrong sign. The sign
//    is taken from that comparison (a comparison cannot be contracted into an FMA).
//  * A tie is resolved exactly: in float by recomputing the products in double (exact for 24-bit
//    mantissas), in double by the exact rounding errors of the two products from std::fma.
//  * An edge function that is exactly zero (the ray passes exactly through the edge line in ray
//    space) is resolved by a consistent tie rule (Woop et al. accept both triangles; we go one step
//    further, as rasterisers do with the top-left rule): the edge belongs to the triangle whose
//    inward edge normal g satisfies g.x > 0, or g.x == 0 and g.y > 0. This is the outcome of
//    moving the query point by the symbolic offset (eps, eps^2), so across any set of triangles
//    that tile a neighbourhood of the ray in ray space -- both sides of an interior edge, the
//    whole fan around an interior vertex -- exactly one triangle claims the ray.
// Compiler note: GCC contracts a*b - c into an FMA in C++ when FMA code generation is enabled
// (-mfma, -march=native). The edge signs are immune (they come from comparing two separately
// rounded products, which cannot be fused); the shear a.x - Sx*a.z may be fused, which changes
// its rounding but not the fact that every triangle computes the same value for a shared vertex,
// as long as all triangles run the same compiled code.
//
// The kernel is templated on the scalar type so the same formulation can be run in 32-bit float
// (the precision of the era's hardware) and compared against double.
#include <array>
#include <cmath>
#include <cstdint>
#include <optional>
#include <type_traits>
#include <utility>

#include "firmware/bounds.hpp"
#include "firmware/cost.hpp"
#include "firmware/hit.hpp"
#include "firmware/math.hpp"
#include "firmware/ray.hpp"

namespace rtsim::kernels {

/// A triangle is rejected by `from` when |(p1-p0) x (p2-p0)| <= kDegenerateRelativeArea * L^2,
/// L the longest edge (the cross product is then twice the area; its ratio to L^2 is the sine of
/// the largest angle deficit). 1e-14 is ~50 double ulps: below it the cross product is rounding
/// noise and the normal direction is meaningless. (Seeds give no value; assumption.)
inline constexpr double kDegenerateRelativeArea = 1e-14;

/// An interpolated shading normal shorter than this (vertex normals are normalised first) means
/// the vertex normals nearly cancel; the geometric normal is used instead. (Assumption.)
inline constexpr double kMinShadingNormalLength = 1e-6;

/// A ray transformed into Woop's ray space: the permutation (kx, ky, kz) and the shear (sx, sy, sz)
/// that map its direction to (0, 0, 1). Built once per ray; a machine would do this in the ray
/// setup, so it is counted separately (kSetupCost).
template <typename T>
struct ShearedRay {
  Vec3T<T> origin{T(0)};
  int kx = 0, ky = 1, kz = 2;
  T sx = T(0), sy = T(0), sz = T(1);

  static ShearedRay make(const Ray& ray) {
    ShearedRay s;
    s.origin = Vec3T<T>(ray.origin);
    const Vec3T<T> d(ray.direction);
    // kz = axis of the largest |d| component, so sz = 1/d[kz] is as small as it can be.
    const T ax = std::fabs(d.x), ay = std::fabs(d.y), az = std::fabs(d.z);
    s.kz = (ax > ay) ? (ax > az ? 0 : 2) : (ay > az ? 1 : 2);
    s.kx = (s.kz + 1) % 3;
    s.ky = (s.kx + 1) % 3;
    // Swap x and y when d[kz] < 0 so the permutation+shear keeps the triangles' winding.
    if (d[s.kz] < T(0)) std::swap(s.kx, s.ky);
    s.sz = T(1) / d[s.kz];
    s.sx = d[s.kx] * s.sz;
    s.sy = d[s.ky] * s.sz;
    return s;
  }

  // Counted: 3 |.| (sign-bit clears: instructions), 2 compares for kz, 1 compare for the swap;
  // 1 divide; 2 multiplies; index arithmetic and the swap: ~6 instructions.
  static constexpr Cost kSetupCost{
      .fp_add = 3, .fp_mul = 2, .fp_div = 1, .fp_sqrt = 0, .mem_words = 0, .instructions = 9};
};

template <typename T>
class TriangleKernelT {
 public:
  using Scalar = T;

  /// Builds the kernel; nullopt for a zero-area (or non-finite) triangle. `vertex_normals`, when
  /// not null, points to 3 normals (any length; they are normalised here). If one of them is zero
  /// or not finite, all three are ignored and the triangle is flat-shaded.
  /// The vertices are stored rounded to T; the degeneracy test is done on the rounded vertices.
  static std::optional<TriangleKernelT> from(const Vec3& p0, const Vec3& p1, const Vec3& p2,
                                             const Vec3* vertex_normals) {
    TriangleKernelT k;
    k.p_ = {Vec3T<T>(p0), Vec3T<T>(p1), Vec3T<T>(p2)};
    const Vec3 q0(k.p_[0]), q1(k.p_[1]), q2(k.p_[2]);
    if (!is_finite(q0) || !is_finite(q1) || !is_finite(q2)) return std::nullopt;
    const Vec3 e1 = q1 - q0, e2 = q2 - q0, e3 = q2 - q1;
    const Vec3 n = glm::cross(e1, e2);
    const double len = glm::length(n);
    const double longest2 =
        std::fmax(glm::dot(e1, e1), std::fmax(glm::dot(e2, e2), glm::dot(e3, e3)));
    if (!(len > kDegenerateRelativeArea * longest2) || !std::isfinite(len)) return std::nullopt;
    k.geometric_normal_ = n / len;
    if (vertex_normals != nullptr) {
      bool ok = true;
      for (int i = 0; i < 3; ++i) {
        const double l = glm::length(vertex_normals[i]);
        if (!(l > 0.0) || !std::isfinite(l)) {
          ok = false;
          break;
        }
        k.normals_[static_cast<std::size_t>(i)] = vertex_normals[i] / l;
      }
      k.has_normals_ = ok;
    }
    return k;
  }

  /// Watertight test against a ray already moved into ray space (see ShearedRay).
  /// On a hit with t in (t_min, t_max) fills `hit` (t, barycentrics u = weight of p1,
  /// v = weight of p2, unit geometric normal, shading normal) and returns true.
  bool intersect(const ShearedRay<T>& r, double t_min, double t_max, SurfaceHit& hit) const {
    // Vertices relative to the ray origin (9 adds).
    const Vec3T<T> a = p_[0] - r.origin;
    const Vec3T<T> b = p_[1] - r.origin;
    const Vec3T<T> c = p_[2] - r.origin;
    // Shear into ray space (6 multiplies, 6 adds).
    const T ax = a[r.kx] - r.sx * a[r.kz];
    const T ay = a[r.ky] - r.sy * a[r.kz];
    const T bx = b[r.kx] - r.sx * b[r.kz];
    const T by = b[r.ky] - r.sy * b[r.kz];
    const T cx = c[r.kx] - r.sx * c[r.kz];
    const T cy = c[r.ky] - r.sy * c[r.kz];
    // Edge functions (6 multiplies); signs from comparing the two rounded products.
    T u = T(0), v = T(0), w = T(0);
    const int su = edge_sign(cx, by, cy, bx, u);
    const int sv = edge_sign(ax, cy, ay, cx, v);
    const int sw = edge_sign(bx, ay, by, ax, w);
    // Mixed signs: the ray passes outside (bitwise ops: one well-predicted branch, not six).
    const bool any_neg = (su < 0) | (sv < 0) | (sw < 0);
    const bool any_pos = (su > 0) | (sv > 0) | (sw > 0);
    if (any_neg & any_pos) return false;
    // Orientation of the triangle in ray space: the common sign of the non-zero edge functions.
    const int s = (su != 0) ? su : (sv != 0 ? sv : sw);
    if (s == 0) return false;  // all three zero: the triangle is edge-on to the ray
    // Tie rule for edges that pass exactly through the ray (see the file comment).
    if (su == 0 && !owns_edge(bx, by, cx, cy, s)) return false;
    if (sv == 0 && !owns_edge(cx, cy, ax, ay, s)) return false;
    if (sw == 0 && !owns_edge(ax, ay, bx, by, s)) return false;
    const T det = u + v + w;  // 2 adds; twice the signed ray-space area
    if (det == T(0)) return false;
    // Scaled z of the vertices and the interpolated hit distance (6 multiplies, 2 adds).
    const T az = r.sz * a[r.kz];
    const T bz = r.sz * b[r.kz];
    const T cz = r.sz * c[r.kz];
    const T t_scaled = u * az + v * bz + w * cz;
    const T inv_det = T(1) / det;  // 1 divide
    const double t = static_cast<double>(t_scaled * inv_det);
    if (!(t > t_min && t < t_max) || !std::isfinite(t)) return false;
    // Barycentrics (2 multiplies). Same-signed edge functions make them >= 0 and sum to <= 1 up
    // to rounding.
    const double bu = static_cast<double>(v * inv_det);
    const double bv = static_cast<double>(w * inv_det);
    if (!std::isfinite(bu) || !std::isfinite(bv)) return false;
    hit.t = t;
    hit.u = bu;
    hit.v = bv;
    hit.geometric_normal = geometric_normal_;
    hit.shading_normal = shading_normal(bu, bv);
    return true;
  }

  bool intersect(const Ray& ray, double t_min, double t_max, SurfaceHit& hit) const {
    return intersect(ShearedRay<T>::make(ray), t_min, t_max, hit);
  }

  Bounds bounds() const {
    Bounds b;
    for (const auto& p : p_) b.extend(Vec3(p));
    return b;
  }

  /// The stored (T-rounded) vertex i, in double.
  Vec3 vertex(int i) const { return Vec3(p_[static_cast<std::size_t>(i)]); }
  const Vec3& geometric_normal() const { return geometric_normal_; }
  bool has_vertex_normals() const { return has_normals_; }

  /// Normalised barycentric interpolation of the vertex normals at (u, v), or the geometric
  /// normal when there are none or the interpolation nearly vanishes.
  Vec3 shading_normal(double u, double v) const {
    if (!has_normals_) return geometric_normal_;
    const Vec3 n = (1.0 - u - v) * normals_[0] + u * normals_[1] + v * normals_[2];
    const double l = glm::length(n);
    if (!(l > kMinShadingNormalLength) || !std::isfinite(l)) return geometric_normal_;
    return n / l;
  }

  /// Cost of one test that reaches the distance computation, excluding the ray setup and the
  /// rare exact tie-break (counted from intersect(const ShearedRay&) above):
  ///   fp_add: 9 translate + 6 shear + 3 edge subtractions + 6 edge compares (p > q, p < q)
  ///           + 2 det + 1 det == 0 + 2 t sum + 2 range compares = 31
  ///   fp_mul: 6 shear + 6 edge products + 3 z scale + 3 t sum + 1 t + 2 barycentric = 21
  ///   fp_div: 1 (1/det)
  ///   mem_words: the 9 vertex coordinates + the 3 normal components copied on a hit, in
  ///   32-bit words of T
  ///   instructions: sign logic, index arithmetic and branches, ~12
  static constexpr Cost kPreparedTestCost{.fp_add = 31,
                                          .fp_mul = 21,
                                          .fp_div = 1,
                                          .fp_sqrt = 0,
                                          .mem_words = (9 + 3) * (sizeof(T) / 4),
                                          .instructions = 12};
  /// intersect(const Ray&): the ray setup is redone for every test.
  static constexpr Cost kTestCost = ShearedRay<T>::kSetupCost + kPreparedTestCost;

 private:
  TriangleKernelT() = default;

  /// Sign of the edge function p - q with p = a*b, q = c*d; `value` receives fl(p - q) (or the
  /// tie-break estimate). Never returns the wrong sign: monotone rounding makes fl(a*b) > fl(c*d)
  /// imply a*b > c*d, and a tie is settled exactly.
  static int edge_sign(T a, T b, T c, T d, T& value) {
    const T p = a * b;
    const T q = c * d;
    value = p - q;
    const int sign = int(p > q) - int(p < q);  // branch-free: the sign is data-dependent
    if (sign != 0) [[likely]]
      return sign;
    // Tie: fl(a*b) == fl(c*d). Settle the sign of a*b - c*d exactly.
    double exact;
    if constexpr (std::is_same_v<T, float>) {
      // Products of two 24-bit mantissas are exact in double; one rounding keeps the sign.
      exact = static_cast<double>(a) * static_cast<double>(b) -
              static_cast<double>(c) * static_cast<double>(d);
      value = static_cast<T>(exact);
    } else {
      // a*b = p + e1 and c*d = q + e2 exactly (fma gives the product's rounding error), and
      // p == q, so a*b - c*d = e1 - e2, whose rounded difference has the exact sign.
      const double e1 =
          std::fma(static_cast<double>(a), static_cast<double>(b), -static_cast<double>(p));
      const double e2 =
          std::fma(static_cast<double>(c), static_cast<double>(d), -static_cast<double>(q));
      exact = e1 - e2;
      value = static_cast<T>(exact);
    }
    return (exact > 0.0) - (exact < 0.0);
  }

  /// Tie rule for an edge P->Q whose edge function is exactly zero, for a triangle of ray-space
  /// orientation s. The inward normal of the edge is g = s * (Qy - Py, Px - Qx) (the gradient of
  /// the edge function, pointing to the side where it has sign s). Coordinate differences of
  /// floating-point numbers have exact signs, and the neighbour across the edge sees exactly -g.
  static bool owns_edge(T px, T py, T qx, T qy, int s) {
    const T gx = (s > 0) ? (qy - py) : (py - qy);
    const T gy = (s > 0) ? (px - qx) : (qx - px);
    return gx > T(0) || (gx == T(0) && gy > T(0));
  }

  std::array<Vec3T<T>, 3> p_{};
  Vec3 geometric_normal_{0.0, 0.0, 1.0};
  std::array<Vec3, 3> normals_{};
  bool has_normals_ = false;
};

using TriangleKernel = TriangleKernelT<double>;
using TriangleKernelFloat = TriangleKernelT<float>;

extern template class TriangleKernelT<double>;
extern template class TriangleKernelT<float>;

}  // namespace rtsim::kernels
