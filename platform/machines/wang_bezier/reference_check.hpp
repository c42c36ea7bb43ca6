#pragma once
// The accuracy study of Wang, Lewis & Hung's machine (`accuracy.check`): every answer the
// pipeline returned is checked against the double-precision reference solver
// (kernels::reference_intersect) on the same job. The paper compared its pipeline with Bezier
// clipping on the teapot and printed no number (seed 002 L264-L266; note 002 "Functional
// correctness" asks for the hit/miss agreement and the final subpatch size), so this measures
// them: per (ray, patch) job and per ray (its nearest patch hit), how often the pipeline and the
// reference disagree on hit or miss, and the distribution of the distance between the point the
// pipeline returned (the centre of its nearest surviving subpatch, seed 002 L100) and the
// reference's hit point, in units of the patch's size (its control box's diagonal).
//
// It only checks: the image and the timing come from the pipeline's answers whether it runs or
// not, and it costs no simulated time.
#include <cmath>
#include <cstdint>
#include <map>
#include <nlohmann/json.hpp>
#include <vector>

#include "firmware/kernels/bezier_wang.hpp"
#include "firmware/ray.hpp"
#include "platform/functional/scene_geometry.hpp"

namespace rtsim::platform::wang_bezier {

/// A point further than this many final subpatch widths from the reference's is on another
/// surface: the centre of a subpatch that holds the hit is within half a width of it, and the
/// Culler may keep a neighbour one width away (measured on the teapot: p99 about 1.5 widths).
/// So at few stages (wide subpatches) surfaces closer than this are not told apart.
inline constexpr double kAnotherSurfaceWidths = 8.0;

/// Hit/miss agreement and hit-point error over a set of comparisons (jobs, or rays).
struct Agreement {
  std::uint64_t compared = 0;
  std::uint64_t both = 0;     ///< both hit
  std::uint64_t neither = 0;  ///< both miss
  std::uint64_t missed = 0;   ///< the reference hits, the pipeline misses
  std::uint64_t phantom = 0;  ///< the pipeline hits, the reference misses
  /// Both hit, but further apart than kAnotherSurfaceWidths final subpatch widths: the pipeline
  /// kept a subpatch of another surface (another fold of the patch, or another patch in front of
  /// or behind the reference's), not a rounding of the right one.
  std::uint64_t another_surface = 0;
  /// Over the rest of `both` (the same surface): the rounding of the right answer.
  std::vector<double> point_error;  ///< |pipeline point - reference point| / patch size
  std::vector<double> depth_error;  ///< |pipeline t - reference t| / patch size
  std::vector<double> pixel_error;  ///< the point error over the pixel's footprint there

  /// `width`: the final subpatch's width in patch sizes (2^-(N+1)); `footprint`: a pixel's
  /// width at the reference's hit, in patch sizes (NaN: not a primary ray).
  void add(bool pipeline_hit, bool reference_hit, double point_error, double depth_error,
           double width, double footprint);
  /// {compared, both, neither, missed, phantom, another_surface,
  ///  disagreement (missed + phantom over compared), disagreement_of_hits (over the reference's
  ///  hits), wrong_of_hits (missed + phantom + another_surface over the reference's hits),
  ///  point_error and depth_error {mean, p10, p50, p90, p99, max} in patch sizes,
  ///  pixel_error {...} in pixels when measured}.
  nlohmann::ordered_json to_json() const;
};

class ReferenceCheck {
 public:
  /// `loop_stages`: the pipeline's N; its final subpatches span 2^-(N+1) of a patch's
  /// parameters. `pixel_angle`: the angle between neighbouring primary rays (radians), so a
  /// pixel is pixel_angle x t wide at distance t.
  ReferenceCheck(const functional::SceneGeometry& geometry, int loop_stages, double pixel_angle)
      : geometry_(geometry),
        width_(std::ldexp(1.0, -(loop_stages + 1))),
        pixel_angle_(pixel_angle) {}

  /// A ray whose jobs are all answered: `answers` by patch slot (the pairs the host culled are
  /// not among them: their box cannot hold a hit). Each job is compared with the reference
  /// over [t_min, t_max]; for a primary ray (a pixel's first sample) also its nearest patch hit.
  void ray(const Ray& ray, double t_min, double t_max, bool primary,
           const std::map<std::uint32_t, kernels::WangResult<double>>& answers);

  /// {jobs: Agreement over every job, rays: Agreement over the primary rays with at least one
  /// job}. Only primary rays: which secondary rays exist depends on the primary rays' answers.
  nlohmann::ordered_json to_json() const;

 private:
  const functional::SceneGeometry& geometry_;
  double width_;  ///< a final subpatch's width in patch sizes
  double pixel_angle_;
  Agreement jobs_, rays_;
};

}  // namespace rtsim::platform::wang_bezier
