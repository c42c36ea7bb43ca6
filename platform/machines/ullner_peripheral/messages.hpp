#pragma once
// The two messages between Ullner's host and peripheral (seed 000 L468-L472).
#include <cstdint>
#include <systemc>

#include "firmware/hit.hpp"
#include "firmware/shading/traced_ray.hpp"
#include "modules/latency_probe.hpp"

namespace rtsim::platform::ullner {

/// TraceRay: r0, r1 and the shadow mark (L468, L472); the host keeps the rest of the ray's
/// state with it here for convenience (it never reaches the peripheral's arithmetic).
struct RayRequest {
  shading::TracedRay ray;
  std::uint64_t id = 0;
  sc_core::sc_time sent;      ///< when the host sent it (ray latency and the probe start here)
  sc_core::sc_time arrived;   ///< when it reached the ray queue (over the ray link)
  bool first_sample = false;  ///< sample 0 of a primary ray: its answer fills the AOVs
  /// The ray's journey for `--latency-probe` (kNoJourney when the probe is off).
  modules::LatencyProbe::Journey journey = modules::LatencyProbe::kNoJourney;
  /// On the wire: r0 (3 words), r1 (3 words), shadow flag (1 word).
  static constexpr unsigned kWords = 7;
  static constexpr std::uint64_t kWireBits = 32 * kWords;
};

/// RayResult: hit flag, closest polygon id, p_r, (u, v), t (L468-L470).
struct RayResult {
  RayRequest request;
  bool found = false;
  Hit hit;
  sc_core::sc_time service_start;  ///< when the peripheral began on this ray
  sc_core::sc_time answered;       ///< when the answer left the closest-hit selection
  sc_core::sc_time arrived;        ///< when it reached the result queue (over the result link)
  /// On the wire: flag, id, p_r (3), u, v, t.
  static constexpr std::uint64_t kWireBits = 32 * 8;
};

}  // namespace rtsim::platform::ullner
