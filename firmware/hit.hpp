#pragma once
#include <cstdint>

#include "firmware/math.hpp"

namespace rtsim {

/// What an intersection kernel reports about a hit on one primitive.
/// Normals are unit length and are NOT flipped toward the ray: surfaces are two-sided and the
/// shader decides which side was hit.
struct SurfaceHit {
  double t = kInfinity;  ///< distance along the (unit-direction) ray
  double u = 0.0;        ///< surface parameter (kernel-specific: bilinear u, barycentric, ...)
  double v = 0.0;
  Vec3 geometric_normal{0.0, 0.0, 1.0};
  Vec3 shading_normal{0.0, 0.0, 1.0};  ///< interpolated normal where the primitive has one
  /// Bound on the distance of the reported point from the true surface: 0 for exact kernels,
  /// the final subpatch size for Wang's subdivision. Spawned rays are lifted at least this far.
  double position_error = 0.0;
};

/// The closest hit of a ray against a whole scene.
struct Hit {
  SurfaceHit surface;
  std::int32_t prim_id = -1;  ///< index of the primitive in scene-file order, -1 for a miss
  std::uint32_t material = 0;

  bool valid() const { return prim_id >= 0; }
};

}  // namespace rtsim
