#pragma once
// Every figure `rtsim validate` knows: one figure set per machine.
#include "platform/validation/validation.hpp"

namespace rtsim::validation {

/// The figures of Ullner's peripheral (ullner_figures.hpp) and of the VAX-11/750 baseline
/// (vax_figures.hpp), with their runs and artifacts.
Plan make_validation_plan(const PlanOptions& options);

}  // namespace rtsim::validation
