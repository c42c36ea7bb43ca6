#pragma once
// The figures of the sequential baseline: a DEC VAX-11/750 with floating-point unit running
// brute-force ray tracing, with Gaudet's cost model (seed 001 L310-L326; note 001 §1.2):
//   T_t = R_t (T_s + T_i O),  T_i = 429 us per intersection, T_s = 710 us per ray.
#include "platform/validation/validation.hpp"

namespace rtsim::validation {

/// Machine name of the baseline in `rtsim run`.
inline constexpr const char* kVaxMachine = "vax-750";

/// Gaudet's VAX-11/750 profile (seed 001 L317-L318), seconds.
inline constexpr double kVaxIntersectionTime = 429e-6;  ///< T_i
inline constexpr double kVaxRayTime = 710e-6;           ///< T_s
/// Gaudet's Fig 1-4 estimate (seed 001 L312-L326): R_0 = 512 x 384, D = 4, N = 1.1, L = 1,
/// O = 1093 objects; R_t = R_0 (N^D - 1)/(N - 1) (1 + L) = 1,824,915.46 rays; T_t ~ 238 h.
inline constexpr double kGaudetFig14Objects = 1093;
double gaudet_fig1_4_rays();

}  // namespace rtsim::validation
