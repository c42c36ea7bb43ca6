#pragma once
// Loading the --scene argument with the seed parameter applied to the generators.
#include <string>

#include "firmware/scene.hpp"
#include "params/registry.hpp"

namespace rtsim::app {

scenes::Scene load_scene_with_seed(const std::string& spec, const params::ParamRegistry& registry);

}  // namespace rtsim::app
