#pragma once
// Whitted/Hall shading with NFF materials (seed 000 L412-L456, seed 001 §1.1):
//   I = R I_a + sum_lights (k_d C cos i + k_s (cos s)^n) I_p   [lights unobstructed only]
//       + k_s I_reflected + T I_transmitted
// Shadows, reflection and refraction are not computed here: the shader SPAWNS rays carrying
// their contribution factor, as a shade task on a machine would, and whatever they find is added
// to the pixel by whoever traces them.
#include <span>

#include "firmware/cost.hpp"
#include "firmware/hit.hpp"
#include "firmware/scene.hpp"
#include "firmware/shading/shade_params.hpp"
#include "firmware/shading/traced_ray.hpp"

namespace rtsim::shading {

/// Most rays one shade step can spawn: one per light plus reflected and refracted.
struct ShadeOutput {
  Color local{0.0};  ///< added to the pixel now (ambient term)
  std::vector<TracedRay> spawned;
};

/// Shade the hit of `in`. `out.spawned` is cleared and refilled (shadow rays in light order,
/// then the reflected ray, then the refracted ray). Returns the cost of the work done.
Cost shade_hit(const TracedRay& in, const Hit& hit, const scenes::Material& material,
               std::span<const scenes::Light> lights, const ShadeParams& params, ShadeOutput& out);

/// What a ray that hits nothing adds: its weight times the background colour (shadow rays
/// that reach their light add their carried contribution instead).
Color miss_contribution(const TracedRay& in, const Color& background);

/// Light intensity to use for `light_count` lights under `params`.
double effective_light_intensity(const ShadeParams& params, std::size_t light_count);

}  // namespace rtsim::shading
