#pragma once
// The figures of Ullner's ray-tracing array (seed 000 §2.5.3, L860-L895; note 000 §4.4-4.5 and
// §7.4 V17-V19): the parameter-fetch bandwidth that makes 40 processors match the peripheral and
// 100 run 250% as fast, an eye to the side piling the load onto one edge under the straight
// mapping and the skewed torus spreading it, and the array "a few times faster" than the
// peripheral.
#include "platform/validation/validation.hpp"

namespace rtsim::validation {

/// Machine name of the array in `rtsim run`.
inline constexpr const char* kArrayMachine = "ullner-array";

}  // namespace rtsim::validation
