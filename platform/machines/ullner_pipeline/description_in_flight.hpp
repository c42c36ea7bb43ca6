#pragma once
// What travels down the ray-tracing pipeline's chain (seed 000 Fig. 2-24, L700-L713), from the
// host's end through every polygon processor to the far end.
#include <cstdint>

#include "firmware/kernels/ullner_quad.hpp"
#include "firmware/tasks/polygon_processor_task.hpp"

namespace rtsim::platform::ullner_pipeline {

/// What travels down the chain: the description's fields (Fig. 2-24, the words on the wire) and,
/// for the model, the ray's set-up (a function of r0 and r1 every processor forms alike: formed
/// once) and which processor wrote the fields last.
struct DescriptionInFlight {
  tasks::RayDescription description;
  kernels::UllnerRay<double> ray;
  std::uint64_t last_writer = ~std::uint64_t{0};  ///< no processor yet
};

}  // namespace rtsim::platform::ullner_pipeline
