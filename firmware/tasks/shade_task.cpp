#include "firmware/tasks/shade_task.hpp"

namespace rtsim::tasks {

Cost ShadeTask::on_result(const shading::TracedRay& ray, bool found, const Hit& hit,
                          shading::PixelAccumulator& fb, std::vector<shading::TracedRay>& spawned) {
  Color add{0.0};
  const auto [cost, adds] = answer(ray, found, hit, add, spawned);
  if (adds) fb.add(ray.pixel, add);
  return cost;
}

ShadeTask::Answer ShadeTask::answer(const shading::TracedRay& ray, bool found, const Hit& hit,
                                    Color& contribution, std::vector<shading::TracedRay>& spawned) {
  spawned.clear();
  Cost cost;
  cost.instructions += 4;
  if (ray.kind == RayKind::Shadow) {
    // The light ray reached its light unobstructed: add the light it carries.
    if (!found) {
      contribution = shading::miss_contribution(ray, scene_->background);
      cost.fp_add += 3;
      cost.mem_words += 3;
      return {cost, true};
    }
    return {cost, false};
  }
  if (!found) {
    contribution = shading::miss_contribution(ray, scene_->background);
    cost.fp_add += 3;
    cost.fp_mul += 3;
    cost.mem_words += 3;
    return {cost, true};
  }
  cost += shading::shade_hit(ray, hit, scene_->materials[hit.material], scene_->lights, params_,
                             scratch_);
  contribution = scratch_.local;
  spawned.assign(scratch_.spawned.begin(), scratch_.spawned.end());
  return {cost, true};
}

}  // namespace rtsim::tasks
