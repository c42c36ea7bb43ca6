#pragma once
// Pixel-Planes 5's graphics processors (GPs, seed 004 L282): i860s with local memory. The master
// GP, the ray casters and the compositors are GPs; their timing and memory are one class of
// parameters (gp.*).
#include <cstddef>
#include <string>

#include "modules/processor_timing.hpp"
#include "params/registry.hpp"

namespace rtsim::platform::pxpl5 {

/// Declares gp.*: the i860's instruction timing, its memory and a caster's bytes per primitive.
void declare_gp_params(params::ParamRegistry& r);
/// A GP's instruction timing.
modules::ProcessorTiming read_gp_timing(const params::ParamRegistry& r);
/// A ray caster holds the whole scene (L310): `primitives` of scene `scene` must fit in a GP's
/// memory, or the run is bad input (exit 2).
void check_scene_fits(const std::string& scene, std::size_t primitives,
                      const params::ParamRegistry& r);

}  // namespace rtsim::platform::pxpl5
