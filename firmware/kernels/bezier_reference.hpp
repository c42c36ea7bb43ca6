#pragma once
// Double-precision reference ray/bicubic-Bezier-patch intersection, the yardstick for Wang's
// pipeline (seed 002 §2.10 compared against Bezier clipping and printed no number, L266).
//
// Method: recursive subdivision of the control net with a conservative test in the ray's frame
// (every subpatch whose control-point box, projected on the plane perpendicular to the ray,
// contains the ray, and whose control points' ray-parameter range overlaps [t_min, best t]), ALL
// such regions explored, nearer first. At kReferenceLeafDepth each surviving region starts a
// Newton iteration on F(u, v, t) = Q(u, v) - (O + t D) = 0 on the ORIGINAL patch, projected onto
// the square [0, 1]^2 and slightly damped (Levenberg) so that it stays finite where Q_u or Q_v
// vanishes (the teapot's collapsed edges). A region is settled when its Newton start lands on a
// root whose parameters lie in the region, or whose point lies in the region's control box (at a
// pole one point has a whole segment of parameters); otherwise it is subdivided further, down to
// kReferenceMaxDepth, so a root is not lost to a Newton start that wandered off. Roots with
// t in [t_min, t_max] are kept; the nearest wins.
#include <cstdint>

#include "firmware/bounds.hpp"
#include "firmware/hit.hpp"
#include "firmware/kernels/bezier_patch_math.hpp"
#include "firmware/ray.hpp"
#include "firmware/scene.hpp"

namespace rtsim::kernels {

/// First Newton starts at parameter intervals of 2^-7: small enough that a transversal crossing
/// lies well inside Newton's quadratic basin (tested on the teapot), large enough that a
/// crossing costs only ~7 x 4 box tests.
inline constexpr int kReferenceLeafDepth = 7;
/// Deepest refinement for regions whose Newton start failed (near tangency / silhouettes):
/// 2^-22 of the parameter range is below anything the tests resolve.
inline constexpr int kReferenceMaxDepth = 22;

/// What the reference solver did (accumulated).
struct ReferenceCounters {
  std::uint64_t calls = 0;
  std::uint64_t box_tests = 0;      ///< subpatches tested in the ray frame
  std::uint64_t subdivisions = 0;   ///< four-way splits
  std::uint64_t newton_starts = 0;  ///< regions that started a Newton iteration
  std::uint64_t newton_iterations = 0;
  std::uint64_t roots = 0;  ///< accepted roots (each nearer than the best so far)
};

/// Nearest root with u, v in [0, 1] and t in [t_min, t_max]. The ray direction need not be unit
/// (t is in its units), but must be non-zero. SurfaceHit: t, (u, v) in the patch's parameters
/// (u along a .bpt row, see bezier_patch_math.hpp), unit normal Q_u x Q_v (both normals).
bool reference_intersect(const ControlNet<double>& net, const Ray& ray, double t_min, double t_max,
                         SurfaceHit& hit, ReferenceCounters* counters = nullptr);

/// The same as a kernel (same shape as BezierPatchKernel): a slow, accurate golden intersector.
class BezierReferenceKernel {
 public:
  static BezierReferenceKernel from(const scenes::BezierPatch& patch);
  bool intersect(const Ray& ray, double t_min, double t_max, SurfaceHit& hit,
                 ReferenceCounters* counters = nullptr) const;
  Bounds bounds() const { return bounds_; }
  const ControlNet<double>& net() const { return net_; }

 private:
  ControlNet<double> net_;
  Bounds bounds_;
  bool valid_ = false;
};

}  // namespace rtsim::kernels
