#pragma once
// The figures of Gaudet's multi-PERT machine (seed 001 Chapter 6; note 001 §4.3, §6.5): the
// test-scene counts of Fig. 6-1, the ShellProcessor's tree-order trade-off (Fig. 6-10), the
// broadcast order (Fig. 6-11), adaptive against non-adaptive broadcasting and direct memory
// (Fig. 6-9), the speed-ups over the VAX-11/750 (L1141, L1143, Figs. 6-12..6-14) and the
// worst-case latency analysis (L1064-L1099). Ids P1..P9.
#include "platform/validation/validation.hpp"

namespace rtsim::validation {

inline constexpr const char* kGaudetMachine = "gaudet-pert";

/// PERT counts of the speed-up curves.
std::vector<int> gaudet_pert_counts(bool quick);

}  // namespace rtsim::validation
