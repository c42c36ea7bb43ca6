#pragma once
// The figures of VOL2 on Pixel-Planes 5 (seed 004 §6, L333-L371; note 004 "Validation"), on
// pxpl5-raytrace: the gain of handing squares out in descending cost (L360), rows against squares
// at full screen and at low coverage (Fig. 9, L369-L371), and the by-pass measurements' shapes
// (Figs. 4-6, L344-L350). VOL2's plots carry no numbers: apart from L360's 10-20%, each figure is
// a stated shape, judged as a ratio.
#include "platform/validation/validation.hpp"

namespace rtsim::validation {

inline constexpr const char* kPxpl5Machine = "pxpl5-raytrace";

}  // namespace rtsim::validation
