#pragma once
// The three messages around a PERT's ring (seed 001 §4.5, Fig. 4-9, 4-11, 4-13; L744-L798).
// Field lists are the thesis's; word counts are ours (the thesis gives no sizes; note 001
// §6.2): 32-bit words, PIXEL = 2, RGB = 3, RAYEQN = 6, INTER = 6 (point and normal), LSS = 2.
// The simulator also carries the whole traced ray and the functional hit along, which the
// hardware does not need to see.
#include <cstdint>
#include <systemc>
#include <vector>

#include "firmware/accel/shell_traversal.hpp"
#include "firmware/hit.hpp"
#include "firmware/shading/traced_ray.hpp"
#include "modules/latency_probe.hpp"

namespace rtsim::platform::gaudet {

/// What follows a ray around the ring: the ray and the bookkeeping of its ShadeProcessor.
struct RayTicket {
  shading::TracedRay ray;
  std::uint64_t id = 0;       ///< ray number within its PERT
  std::uint32_t tree = 0;     ///< slot of the initial ray it descends from (pixel bookkeeping)
  double t_min = 0.0;         ///< the search range is (t_min, ray.t_max)
  bool first_sample = false;  ///< sample 0 of a primary ray: its answer fills the AOVs
  sc_core::sc_time sent;      ///< when the ShadeProcessor sent it (ray latency)
  /// --latency-probe (ray_probe.hpp): the ray's journey, kNoJourney when not probed, and the
  /// time up to which its journey is accounted.
  modules::LatencyProbe::Journey journey = modules::LatencyProbe::kNoJourney;
  sc_core::sc_time accounted_to;
};

/// SHADE_TO_SHELL (Fig. 4-9, L744-L749): ray_type, pixel_index, factor, ray.
struct ShadeToShell {
  RayTicket ticket;
  static constexpr unsigned kWords = 1 + 2 + 3 + 6;
};

/// SHELL_TO_PRIM (Fig. 4-11, L761-L768): ShadeToShell's fields, LeafShellList[50] sorted on t,
/// LeafShellCount. Only the entries in use travel.
struct ShellToPrim {
  RayTicket ticket;
  std::vector<accel::LeafShellEntry> leaf_shells;  ///< sorted on increasing t
  unsigned words() const {
    const auto n = std::min(leaf_shells.size(), accel::kLeafShellListCapacity);
    return ShadeToShell::kWords + 1 + 2 * static_cast<unsigned>(n);
  }
};

/// PRIM_TO_SHADE (Fig. 4-13, L790-L798): ray_type, hit_type, pixel_index, factor, ray, point
/// and normal, surface_index.
struct PrimToShade {
  RayTicket ticket;
  bool found = false;
  Hit hit;
  static constexpr unsigned kWords = 1 + 1 + 2 + 3 + 6 + 6 + 1;
};

}  // namespace rtsim::platform::gaudet
