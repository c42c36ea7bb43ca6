#pragma once
// What travels down the ray-tracing pipeline's chain (seed 000 Fig. 2-24, L700-L713), from the
// host's end through every polygon processor to the far end.
#include <cstdint>
#include <systemc>

#include "firmware/kernels/ullner_quad.hpp"
#include "firmware/tasks/polygon_processor_task.hpp"

namespace rtsim::platform::ullner_pipeline {

/// What travels down the chain: the description's fields (Fig. 2-24, the words on the wire) and,
/// for the model, the ray's set-up (a function of r0 and r1 every processor forms alike: formed
/// once), which processor wrote the fields last, and where it is in time.
struct DescriptionInFlight {
  tasks::RayDescription description;
  kernels::UllnerRay<double> ray;
  std::uint64_t last_writer = ~std::uint64_t{0};  ///< no processor yet
  /// Absolute: when it arrives in the register it is sent to (a processor's input register or
  /// the host's end), and once accepted, when the processor is ready to pass it on. The chain
  /// times descriptions lazily (one waits behind another the host's end holds up, chain_timing.hpp)
  /// so a description's time may lie before the simulation's: it travels with the description
  /// rather than as a b_transport delay, which cannot be negative.
  sc_core::sc_time at = sc_core::SC_ZERO_TIME;
  /// When the first processor handed it to its link (for that link's statistics).
  sc_core::sc_time first_handed = sc_core::SC_ZERO_TIME;
};

}  // namespace rtsim::platform::ullner_pipeline
