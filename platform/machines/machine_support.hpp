#pragma once
// Pieces every machine model shares.
#include "firmware/shading/traced_ray.hpp"
#include "firmware/tasks/shade_task.hpp"
#include "firmware/tracer.hpp"
#include "platform/machine.hpp"

namespace rtsim::platform {

/// The search a ray asks for: any hit for light (shadow) rays, the closest hit otherwise.
inline bool trace_one(const Tracer& tracer, const tasks::ShadeTask& shade,
                      const shading::TracedRay& r, Hit& hit, TraceCounters& counters) {
  return r.kind == RayKind::Shadow
             ? tracer.any_hit(r.ray, shade.t_min(r), r.t_max, counters)
             : tracer.closest_hit(r.ray, shade.t_min(r), r.t_max, hit, counters);
}

/// Converts the scene with the functional renderer's geometry conversion and builds its tracer.
FunctionalTwin make_functional_twin(scenes::Scene& scene, const functional::RenderSettings& s);

/// Sets the time resolution and the global quantum from `quantum`. Call before building modules.
void begin_simulation(const params::ParamRegistry& registry);

}  // namespace rtsim::platform
