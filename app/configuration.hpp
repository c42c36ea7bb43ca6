#pragma once
// Builds the parameter registry of a command: compiled-in declarations (presets), then the
// --config files in order, then the -p overrides.
#include "app/commands.hpp"
#include "platform/params/registry.hpp"

namespace rtsim::app {

params::ParamRegistry build_registry(const ConfigArgs& args);

}  // namespace rtsim::app
