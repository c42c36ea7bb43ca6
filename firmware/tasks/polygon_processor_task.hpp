#pragma once
// One polygon processor of Ullner's ray-tracing pipeline (seed 000 §2.4.1, L690-L713): it holds
// one polygon and passes ray descriptions (Fig. 2-24) from its input to its output. "When it
// receives a ray description, the processor determines whether that ray intersects its stored
// polygon ... If the ray and polygon intersect, and if the distance ... is smaller than the
// distance carried in the ray description", it replaces the intersection fields and substitutes
// its own identity; otherwise it "does not disturb the ray description" (L713).
//
// The test is Ullner's quad kernel (firmware/kernels/ullner_quad.hpp), the same one the
// peripheral pipelines, on the parameters the processor's registers hold.
#include <cstdint>

#include "firmware/cost.hpp"
#include "firmware/kernels/ullner_quad.hpp"
#include "firmware/math.hpp"

namespace rtsim::tasks {

/// A ray description (Fig. 2-24, L700-L711): thirteen 32-bit numbers on the pipeline's wires.
/// The model carries them in double, as the peripheral's messages do, and charges 32 bits each.
struct RayDescription {
  Vec3 r0{0.0};  ///< origin of the ray
  /// r1 - r0 for "some other point along the ray" r1 (L698): the host sends the difference the
  /// processors would otherwise each form first (UllnerRay), the same three numbers.
  Vec3 r1_minus_r0{0.0, 0.0, 1.0};
  Vec3 p_r{0.0};         ///< intersection of ray and polygon
  double t = kInfinity;  ///< distance along the ray of the intersection point
  double u = 0.0;        ///< (u, v): polygon coordinates of the intersection point
  double v = 0.0;
  std::uint32_t i = kNoPolygon;  ///< identity of the intersecting polygon

  /// The identity field before any processor has written it.
  static constexpr std::uint32_t kNoPolygon = 0xFFFFFFFFu;
  static constexpr unsigned kWords = 13;  // 3 + 3 + 3 + 1 + 2 + 1 (L727)
  static constexpr std::uint64_t kWireBits = 32 * kWords;
};

/// The handler of one processor: intersects the description's ray with its polygon `P`
/// (identity `id`) and overwrites the intersection fields if it is hit closer than the carried
/// t. `ray` is the description's ray as the processor's arithmetic holds it (formed once per
/// description). Returns whether it overwrote.
inline bool pass_ray_description(RayDescription& d, const kernels::UllnerRay<double>& ray,
                                 const kernels::UllnerQuadParams<double>& P, std::uint32_t id) {
  // t < the carried t is the kernel's own range test (t_valid), so u and v are formed only for
  // a closer plane hit: the same fields as computing them always and comparing after (L713).
  // t > 0 (L275): the near limit of every ray.
  const auto r = kernels::intersect(P, ray, 0.0, d.t);
  if (!r.hit()) return false;
  d.p_r = r.p_r;
  d.t = r.t;
  d.u = r.u;
  d.v = r.v;
  d.i = id;
  return true;
}

/// What one processor computes per description: the ray set-up, the intersection and the
/// comparison with the carried t (comparisons count as fp_add, firmware/cost.hpp).
inline constexpr Cost kPolygonProcessorCost = kernels::UllnerRay<double>::kSetupCost +
                                              kernels::kUllnerQuadPreparedTestCost +
                                              Cost{.fp_add = 1};

}  // namespace rtsim::tasks
