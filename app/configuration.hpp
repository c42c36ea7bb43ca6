#pragma once
// Builds the parameter registry of a command: compiled-in declarations (the common parameters
// and, with a machine, its preset), then the --config files in order, then the -p overrides.
#include "app/commands.hpp"
#include "params/registry.hpp"
#include "platform/machine.hpp"

namespace rtsim::app {

/// `machine` may be null (the functional renderer alone).
params::ParamRegistry build_registry(const ConfigArgs& args,
                                     const platform::Machine* machine = nullptr);

}  // namespace rtsim::app
