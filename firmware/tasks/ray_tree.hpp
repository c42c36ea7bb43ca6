#pragma once
// Tracing a ray and the rays its answers spawn, depth first, as one processor running every
// task would (the functional renderer, the VAX baseline). Machines that split the work between
// processors use trace_one alone and pass the spawned rays around as messages.
#include <vector>

#include "firmware/shading/pixel_accumulator.hpp"
#include "firmware/shading/traced_ray.hpp"
#include "firmware/tasks/shade_task.hpp"
#include "firmware/trace_counters.hpp"
#include "firmware/tracer.hpp"

namespace rtsim::tasks {

/// The search a ray asks for: any hit for light (shadow) rays, the closest hit otherwise.
inline bool trace_one(const Tracer& tracer, const ShadeTask& shade, const shading::TracedRay& r,
                      Hit& hit, TraceCounters& counters) {
  return r.kind == RayKind::Shadow
             ? tracer.any_hit(r.ray, shade.t_min(r), r.t_max, counters)
             : tracer.closest_hit(r.ray, shade.t_min(r), r.t_max, hit, counters);
}

/// Traces `primary` and everything it spawns, in spawn order; contributions go into `fb`.
/// `on_ray(ray, found, hit)` is called after each ray is answered (the primary first).
/// `stack` and `spawned` are scratch space kept by the caller.
template <class OnRay>
void trace_ray_tree(const shading::TracedRay& primary, const Tracer& tracer, ShadeTask& shade,
                    shading::PixelAccumulator& fb, TraceCounters& counters,
                    std::vector<shading::TracedRay>& stack,
                    std::vector<shading::TracedRay>& spawned, OnRay&& on_ray) {
  stack.clear();
  stack.push_back(primary);
  while (!stack.empty()) {
    const shading::TracedRay r = stack.back();
    stack.pop_back();
    counters.count_ray(r.kind);
    Hit hit;
    const bool found = trace_one(tracer, shade, r, hit, counters);
    on_ray(r, found, hit);
    counters.cost += shade.on_result(r, found, hit, fb, spawned);
    // Push in reverse so rays are traced in the order they were spawned.
    for (auto it = spawned.rbegin(); it != spawned.rend(); ++it) stack.push_back(*it);
  }
}

}  // namespace rtsim::tasks
