#pragma once
// The figures of Wang, Lewis & Hung's ray/Bezier-patch pipeline (seed 002 §4.3, Table 4,
// L436-L441; note 002 "Validation figures"): the pipeline cycle and throughput, the substages'
// times, and the what-ifs of L326 (faster SplitInHalf, the Culler next) and L432 (software Culler).
#include "platform/validation/validation.hpp"

namespace rtsim::validation {

inline constexpr const char* kWangMachine = "wang-bezier";

}  // namespace rtsim::validation
