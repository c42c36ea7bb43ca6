#pragma once
// A ray in flight, as the machines pass it between tasks. Following Gaudet (seed 001 §4.3.4,
// "no intersection tree", after Ullner), every ray carries its own contribution factor and its
// pixel, so whatever it finds is added straight into the frame buffer: no ray tree is kept.
#include <cstdint>

#include "firmware/ray.hpp"

namespace rtsim::shading {

struct TracedRay {
  Ray ray;
  RayKind kind = RayKind::Primary;
  std::uint8_t depth = 0;         ///< 0 for primary rays, +1 per reflection/refraction
  double t_max = kInfinity;       ///< shadow rays stop at the light
  Color weight{1.0};              ///< contribution factor of whatever this ray finds
  Color light_contribution{0.0};  ///< shadow rays: added to the pixel if the light is unobstructed
  std::uint32_t pixel = 0;        ///< y * width + x
  std::uint16_t light = 0;        ///< shadow rays: which light
};

}  // namespace rtsim::shading
