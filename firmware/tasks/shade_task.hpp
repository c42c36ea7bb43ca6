#pragma once
// What happens when the answer for a ray comes back (Ullner's host task 2, seed 000 L474;
// Gaudet's ShadeTask, seed 001 §4.5): a light ray that found nothing adds its light; any other
// ray that found nothing adds the background; a hit is shaded and spawns new rays. Every
// contribution goes straight into the frame buffer (no ray tree).
#include <vector>

#include "firmware/cost.hpp"
#include "firmware/hit.hpp"
#include "firmware/scene.hpp"
#include "firmware/shading/pixel_accumulator.hpp"
#include "firmware/shading/whitted_shader.hpp"

namespace rtsim::tasks {

class ShadeTask {
 public:
  ShadeTask(const scenes::Scene& scene, const shading::ShadeParams& params)
      : scene_(&scene), params_(params) {}

  /// Process the answer for `ray` (`found`/`hit` from the closest-hit or any-hit search).
  /// Adds contributions to `fb`; new rays go to `spawned` (cleared first). Returns the cost.
  Cost on_result(const shading::TracedRay& ray, bool found, const Hit& hit,
                 shading::PixelAccumulator& fb, std::vector<shading::TracedRay>& spawned);

  /// What on_result does, with the contribution handed back instead of added: the ray-tracing
  /// array's node puts it into a result message for the pixel's processor (seed 000 L809).
  struct Answer {
    Cost cost;
    bool contributes = false;  ///< `contribution` is to be added to the ray's pixel
  };
  Answer answer(const shading::TracedRay& ray, bool found, const Hit& hit, Color& contribution,
                std::vector<shading::TracedRay>& spawned);

  /// t_min of the search for `ray`: the hither plane for primary rays (NFF `hither`).
  double t_min(const shading::TracedRay& ray) const {
    return ray.kind == RayKind::Primary ? scene_->camera.hither : 0.0;
  }

 private:
  const scenes::Scene* scene_;
  shading::ShadeParams params_;
  shading::ShadeOutput scratch_;
};

}  // namespace rtsim::tasks
