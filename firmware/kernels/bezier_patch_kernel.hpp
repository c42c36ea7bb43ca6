#pragma once
// Kernel adapter for a bicubic Bezier patch intersected by Wang, Lewis & Hung's pipeline
// (bezier_wang.hpp): the shape every intersection kernel offers (from / intersect / bounds).
#include <cmath>
#include <optional>
#include <stdexcept>

#include "firmware/bounds.hpp"
#include "firmware/cost.hpp"
#include "firmware/hit.hpp"
#include "firmware/kernels/bezier_patch_math.hpp"
#include "firmware/kernels/bezier_wang.hpp"
#include "firmware/ray.hpp"
#include "firmware/scene.hpp"

namespace rtsim::kernels {

/// T is the precision of the pipeline's words: float models the paper's DSPs (seed 002 L296),
/// double is there for comparison. A float kernel may compute in another arithmetic
/// (bezier.arithmetic, wang_arithmetic.hpp: double, or fixed point) on its single-precision
/// words, as the machine's pipeline does. The measured position error at 10 iterations is the same
/// in both (subdivision error ~1e-4 of the teapot size dwarfs float rounding, see
/// tests/bezier_wang_test.cpp), so the default kernel is the faithful float one.
template <typename T>
class BezierPatchKernelT {
 public:
  /// Data-independent cost of one ray/patch job through the default 10-stage pipeline.
  static constexpr Cost kTestCost = wang_pipeline_cost(kWangLoopStages);

  /// Throws std::invalid_argument if iterations is outside [kWangMinIterations,
  /// kWangMaxIterations]. A patch with non-finite control points is accepted and never hit.
  /// `culler_key_bits`: the Culler's key width (Culler::kKeyBits: exact).
  static BezierPatchKernelT from(const scenes::BezierPatch& patch, int iterations = kWangLoopStages,
                                 int culler_key_bits = Culler::kKeyBits,
                                 const WangArithmetic& arithmetic = {});

  /// Nearest hit with t in [t_min, t_max]. The pipeline only looks forward from its origin
  /// (eq. 21), so the ray enters it from O + t_min D (t_min < 0 or infinite: from O).
  /// hit.t = (C - O).D for the centre C of the closest final subpatch; (u, v) = that centre in
  /// the original patch's parameters; both normals = the original patch's Q_u x Q_v at (u, v)
  /// (see the .cpp for why), unit, not flipped toward the ray.
  bool intersect(const Ray& ray, double t_min, double t_max, SurfaceHit& hit) const {
    return intersect(ray, t_min, t_max, hit, nullptr);
  }
  /// Same, adding what the pipeline did to *counters.
  bool intersect(const Ray& ray, double t_min, double t_max, SurfaceHit& hit,
                 WangCounters* counters) const;

  /// The two halves of intersect around the pipeline, for a machine that runs the pipeline's
  /// stages itself (wang_stage0, wang_loop_stage, wang_output on net()): where the ray enters
  /// it (O + t_min D, in its precision), nothing if the job cannot hit; and the hit from what
  /// the last stage output.
  std::optional<Vec3T<T>> entry(const Ray& ray, double t_min, double t_max) const;
  template <typename R>
  bool finish(const WangResult<R>& r, const Ray& ray, double t_min, double t_max,
              SurfaceHit& hit) const;
  const ControlNet<T>& net() const { return net_; }
  /// Where a job enters the ray: t_min when it is a positive finite number, else 0.
  static double entry_t(double t_min) { return std::isfinite(t_min) && t_min > 0.0 ? t_min : 0.0; }

  /// Box of the 16 control points (contains the patch).
  Bounds bounds() const { return bounds_; }
  int iterations() const { return iterations_; }
  int culler_key_bits() const { return culler_.key_bits; }
  const WangArithmetic& arithmetic() const { return arithmetic_; }
  /// The cost of one job through this kernel's pipeline length.
  Cost pipeline_cost() const { return wang_pipeline_cost(iterations_); }
  const ControlNet<double>& original() const { return original_; }

 private:
  ControlNet<double> original_;  ///< for the normal and the bounds
  ControlNet<T> net_;            ///< the pipeline's copy, in its precision
  Bounds bounds_;
  int iterations_ = kWangLoopStages;
  CullerConfig culler_;
  WangArithmetic arithmetic_;
  ControlNet<double> wide_net_;  ///< net_'s words in double, for a wide arithmetic
  bool valid_ = false;
};

extern template class BezierPatchKernelT<float>;
extern template class BezierPatchKernelT<double>;

using BezierPatchKernel = BezierPatchKernelT<float>;
using BezierPatchKernelDouble = BezierPatchKernelT<double>;

}  // namespace rtsim::kernels
