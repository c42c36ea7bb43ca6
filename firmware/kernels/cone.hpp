#pragma once
// Ray / open cone or cylinder intersection for the NFF `c` primitive: the lateral surface between
// a base circle (centre `base`, radius r0) and an apex circle (centre `apex`, radius r1), without
// end caps. |r| is used (a negative NFF radius only means "seen from inside"); r0 == r1 is a
// cylinder, a zero radius is a true cone point.
//
// Like the sphere this is a quadric (seed 000 L943-L953: substitute the ray, solve the quadratic).
// In the cone's local frame (origin at the base centre, z along the axis, height h) the surface is
//   x^2 + y^2 = rho(z)^2,   rho(z) = r0 + k z,   k = (r1 - r0) / h,   accepted for 0 <= z <= h.
// With the local ray o + t d:
//   a  = dx^2 + dy^2 - (k dz)^2
//   b' = ox dx + oy dy - (k dz) rho(oz)       (half b)
//   c  = ox^2 + oy^2 - rho(oz)^2
// Numerical care:
// * Before transforming, the ray origin is moved along the ray to its point closest to the
//   cone's centre (t_shift = d . (centre - o)); the local coefficients are then of the size of the
//   cone, not of the origin's distance, and t = t_shift + t_local.
// * disc = b'^2 - a c uses an FMA-compensated difference of products (Kahan), and the roots
//   q = -(b' + sgn(b') sqrt(disc)), t = q / a and t = c / q avoid cancellation. a == 0 (ray
//   parallel to a slant line, or to a cylinder's axis) needs no special case: q / a is then not
//   finite and rejected, c / q is the single root (or also rejected).
// * Normal: the gradient of x^2 + y^2 - rho(z)^2 is 2 rho(z) (cos phi, sin phi, -k), so the unit
//   normal is (cos phi, sin phi, -k) / sqrt(1 + k^2) with (cos phi, sin phi) the radial direction
//   of the hit -- outward, and correct for the slanted side. At an exact cone point (x = y = 0)
//   the radial direction is undefined; the side facing the ray is used.
#include <cmath>
#include <optional>
#include <string>
#include <utility>

#include "firmware/bounds.hpp"
#include "firmware/cost.hpp"
#include "firmware/hit.hpp"
#include "firmware/math.hpp"
#include "firmware/ray.hpp"
#include "firmware/scene.hpp"

namespace rtsim::kernels {

/// Cone ends closer than this, relative to the largest coordinate magnitude of the two ends, are
/// "coincident": the axis direction would be rounding noise. 1e-12 is ~5000 double ulps.
/// (Seeds give no value; assumption.)
inline constexpr double kConeCoincidentRelative = 1e-12;

class ConeKernel {
 public:
  /// nullopt (and a reason in *why, if given) for non-finite input, coincident ends or both
  /// radii zero.
  static std::optional<ConeKernel> from(const scenes::Cone& cone, std::string* why = nullptr);

  /// Nearest hit on the lateral surface with t in (t_min, t_max) and 0 <= z <= h.
  /// Fills t, v = z / h (0 at the base, 1 at the apex), u = 0, and the outward unit normal as both
  /// the geometric and the shading normal.
  bool intersect(const Ray& ray, double t_min, double t_max, SurfaceHit& hit) const {
    const Vec3& d = ray.direction;
    // Move the origin to the ray point closest to the cone's centre.
    const Vec3 to_centre = centre_ - ray.origin;    // 3a
    const double t_shift = glm::dot(to_centre, d);  // 3m 2a
    const Vec3 e = t_shift * d - to_centre;         // 3m 3a: shifted origin - centre
    // Local frame (rows u_, v_, w_): direction and origin (the centre is at z = h/2).
    const double dx = glm::dot(u_, d), dy = glm::dot(v_, d), dz = glm::dot(w_, d);  // 9m 6a
    const double ox = glm::dot(u_, e), oy = glm::dot(v_, e);                        // 6m 4a
    const double oz = glm::dot(w_, e) + half_height_;                               // 3m 3a
    const double rho = r0_ + k_ * oz;                                               // 1m 1a
    const double kdz = k_ * dz;                                                     // 1m
    const double a = dx * dx + dy * dy - kdz * kdz;                                 // 3m 2a
    const double b = ox * dx + oy * dy - kdz * rho;                                 // 3m 2a
    const double c = ox * ox + oy * oy - rho * rho;                                 // 3m 2a
    const double disc = difference_of_products(b, b, a, c);  // 2m + 2 fma (4m 4a counted)
    if (!(disc >= 0.0)) return false;                        // 1a
    const double sq = std::sqrt(disc);
    const double q = (b >= 0.0) ? -(b + sq) : (sq - b);  // 2a
    double t0 = q / a;                                   // 1d
    double t1 = c / q;                                   // 1d
    // Non-finite roots (a == 0 or q == 0) never pass the range tests below (NaN compares false;
    // +-inf is outside any finite range and caught by isfinite).
    if (!(t0 <= t1)) std::swap(t0, t1);  // 1a
    double tl;
    double z;
    if (accept(t0, t_shift, t_min, t_max, oz, dz, z)) {
      tl = t0;
    } else if (accept(t1, t_shift, t_min, t_max, oz, dz, z)) {
      tl = t1;
    } else {
      return false;
    }
    // Outward normal from the radial direction of the hit.
    const double x = ox + tl * dx, y = oy + tl * dy;  // 2m 2a
    const double radial = std::sqrt(x * x + y * y);   // 2m 1a 1s
    double cx, cy;
    if (radial > 0.0) {
      const double inv_radial = 1.0 / radial;  // 1d
      cx = x * inv_radial;                     // 2m
      cy = y * inv_radial;
    } else {
      // Exact cone point: take the side facing the ray (or any side for a ray along the axis).
      const double l = std::sqrt(dx * dx + dy * dy);
      cx = (l > 0.0) ? -dx / l : 1.0;
      cy = (l > 0.0) ? -dy / l : 0.0;
    }
    const Vec3 n = (cx * normal_radial_scale_) * u_ + (cy * normal_radial_scale_) * v_ +
                   normal_axial_ * w_;  // 2m + 9m 6a
    if (!is_finite(n)) return false;
    hit.t = t_shift + tl;
    hit.u = 0.0;
    hit.v = z * inv_height_;
    hit.geometric_normal = n;
    hit.shading_normal = n;
    return std::isfinite(hit.t) && std::isfinite(hit.v);
  }

  Bounds bounds() const;

  const Vec3& base() const { return base_; }
  const Vec3& apex() const { return apex_; }
  double base_radius() const { return r0_; }
  double apex_radius() const { return r1_; }
  double height() const { return height_; }
  bool is_cylinder() const { return k_ == 0.0; }
  /// Local frame: x, y radial, z along the axis from base to apex.
  const Vec3& axis() const { return w_; }

  /// Cost of a test that hits, counted line by line from intersect above (a = add/compare,
  /// m = multiply; an FMA counts as 1m + 1a):
  ///   shift 3m 5a; e 3m 3a; local d 9m 6a; local o 9m 7a; rho 1m 1a; kdz 1m; a, b', c 9m 6a;
  ///   disc 4m 3a; disc >= 0 1a; sqrt; q 2a; 2 root divides; order 1a;
  ///   accept (one root) z 1m 1a, t range 3a, z range 2a;
  ///   normal: x, y 2m 2a; radial 2m 1a 1 sqrt; cos/sin 1 divide 2m; n 11m 6a; t 1a.
  /// mem_words: base, centre, frame (9), r0, k, h/2, 1/h, two normal scales = 19 doubles.
  static constexpr Cost kTestCost{
      .fp_add = 5 + 3 + 6 + 7 + 1 + 6 + 3 + 1 + 2 + 1 + 1 + 3 + 2 + 2 + 1 + 6 + 1,
      .fp_mul = 3 + 3 + 9 + 9 + 1 + 1 + 9 + 4 + 1 + 2 + 2 + 2 + 11,
      .fp_div = 3,
      .fp_sqrt = 2,
      .mem_words = 38,
      .instructions = 12};

 private:
  ConeKernel() = default;

  /// a*b - c*d with Kahan's FMA compensation: relative error within 2 ulps (Jeannerod, Louvet &
  /// Muller 2013), so a near-tangent discriminant keeps its sign.
  static double difference_of_products(double a, double b, double c, double d) {
    const double cd = c * d;
    const double err = std::fma(-c, d, cd);  // cd - c*d exactly
    const double diff = std::fma(a, b, -cd);
    return diff + err;
  }

  /// A local root is accepted when its world t lies in (t_min, t_max) and its height in [0, h].
  bool accept(double tl, double t_shift, double t_min, double t_max, double oz, double dz,
              double& z) const {
    const double t = t_shift + tl;
    if (!(t > t_min && t < t_max) || !std::isfinite(t)) return false;
    z = oz + tl * dz;
    return z >= 0.0 && z <= height_;
  }

  Vec3 base_{0.0};
  Vec3 apex_{0.0, 0.0, 1.0};
  Vec3 centre_{0.0, 0.0, 0.5};
  Vec3 u_{1.0, 0.0, 0.0}, v_{0.0, 1.0, 0.0}, w_{0.0, 0.0, 1.0};
  double r0_ = 1.0, r1_ = 1.0;
  double k_ = 0.0;
  double height_ = 1.0, half_height_ = 0.5, inv_height_ = 1.0;
  double normal_radial_scale_ = 1.0;  // 1 / sqrt(1 + k^2)
  double normal_axial_ = 0.0;         // -k / sqrt(1 + k^2)
};

}  // namespace rtsim::kernels
