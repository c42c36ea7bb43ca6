#pragma once
// Pieces every machine model shares.
#include "platform/machine.hpp"

namespace rtsim::platform {

/// Converts the scene with the functional renderer's geometry conversion and builds its tracer.
FunctionalTwin make_functional_twin(scenes::Scene& scene, const functional::RenderSettings& s);

/// Sets the global TLM quantum from the parameter `quantum`. Call before building modules.
void begin_simulation(const params::ParamRegistry& registry);

}  // namespace rtsim::platform
