#pragma once
// The auxiliary processor's search (seed 000 L594): feed the intersection processor the polygon
// addresses of the current subvolume; if the closest intersection lies within the subvolume it
// is the answer, otherwise go on to the next subvolume along the ray, until a hit is found or
// the ray leaves the modelling space. Shadow rays accept any hit (L472).
//
// PrimTest: double test(std::uint32_t slot, double t_min, double t_max) returns the t of the
// primitive's closest hit in (t_min, t_max), or +inf on a miss. Every finite return below the
// current best is a new closest hit, so the callback may remember the hit's details then.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <span>

#include "firmware/accel/dda.hpp"

namespace rtsim::accel {

struct GridHit {
  std::int32_t prim = -1;  ///< primitive slot, -1 for a miss
  double t = kInfinity;
  bool valid() const { return prim >= 0; }
};

struct GridTraversalStats {
  std::uint64_t rays = 0;
  std::uint64_t cells_visited = 0;
  std::uint64_t steps = 0;       ///< DDA steps, charged t_d each (seed 000 L654)
  std::uint64_t prim_tests = 0;  ///< polygon addresses fed to the intersection processor

  GridTraversalStats& operator+=(const GridTraversalStats& o) {
    rays += o.rays;
    cells_visited += o.cells_visited;
    steps += o.steps;
    prim_tests += o.prim_tests;
    return *this;
  }
};

/// Closest hit in (t_min, t_max). A polygon in several subvolumes is tested in each of them,
/// as the auxiliary processor would (no mailbox in the thesis).
template <class PrimTest>
GridHit grid_closest_hit(const Dda& dda, const Ray& ray, double t_min, double t_max,
                         PrimTest&& test, GridTraversalStats& stats) {
  GridHit best;
  best.t = t_max;
  ++stats.rays;
  const DdaResult r = dda.traverse(
      ray, t_min, t_max,
      [&](const CellIndex&, std::span<const std::uint32_t> slots, double, double t_exit) {
        for (const std::uint32_t slot : slots) {
          ++stats.prim_tests;
          const double t = test(slot, t_min, best.t);
          if (t > t_min && t < best.t) {
            best.t = t;
            best.prim = static_cast<std::int32_t>(slot);
          }
        }
        // "if the point of intersection lies within the subvolume, then the proper
        // intersection point has been found" (L594).
        return best.valid() && best.t <= t_exit;
      });
  stats.cells_visited += r.cells_visited;
  stats.steps += r.steps;
  if (!best.valid()) best.t = kInfinity;
  return best;
}

/// The closest hit within one subvolume whose part of the ray ends at `t_exit` (the ray-tracing
/// array's node, seed 000 L807: "the processor either will find an intersection point within
/// its subvolume, or it will not"). A hit beyond t_exit is not this subvolume's: the polygon
/// touches the next subvolume too and is found there. The bound handed to `test` is already
/// the limit, so every finite return is a new closest hit (the callback's contract).
template <class PrimTest>
GridHit subvolume_closest_hit(std::span<const std::uint32_t> slots, double t_min, double t_max,
                              double t_exit, PrimTest& test, GridTraversalStats& stats) {
  GridHit best;
  best.t = std::min(t_max, std::nextafter(t_exit, kInfinity));
  for (const std::uint32_t slot : slots) {
    ++stats.prim_tests;
    const double t = test(slot, t_min, best.t);
    if (t > t_min && t < best.t) {
      best.t = t;
      best.prim = static_cast<std::int32_t>(slot);
    }
  }
  if (!best.valid()) best.t = kInfinity;
  return best;
}

/// Closest hit in (t_min, t_max) searched subvolume by subvolume, each looking only within
/// itself (subvolume_closest_hit): the array's search, and its functional twin's. The answer
/// is the grid_closest_hit answer; only ties between polygons at the same t may resolve
/// otherwise.
template <class PrimTest>
GridHit grid_closest_hit_by_subvolume(const Dda& dda, const Ray& ray, double t_min, double t_max,
                                      PrimTest&& test, GridTraversalStats& stats) {
  GridHit best;
  ++stats.rays;
  const DdaResult r = dda.traverse(
      ray, t_min, t_max,
      [&](const CellIndex&, std::span<const std::uint32_t> slots, double, double t_exit) {
        best = subvolume_closest_hit(slots, t_min, t_max, t_exit, test, stats);
        return best.valid();
      });
  stats.cells_visited += r.cells_visited;
  stats.steps += r.steps;
  return best;
}

/// Any hit in (t_min, t_max): the shadow-ray search, which stops at the first occluder.
template <class PrimTest>
GridHit grid_any_hit(const Dda& dda, const Ray& ray, double t_min, double t_max, PrimTest&& test,
                     GridTraversalStats& stats) {
  GridHit hit;
  ++stats.rays;
  const DdaResult r =
      dda.traverse(ray, t_min, t_max,
                   [&](const CellIndex&, std::span<const std::uint32_t> slots, double, double) {
                     for (const std::uint32_t slot : slots) {
                       ++stats.prim_tests;
                       const double t = test(slot, t_min, t_max);
                       if (t > t_min && t < t_max) {
                         hit.t = t;
                         hit.prim = static_cast<std::int32_t>(slot);
                         return true;
                       }
                     }
                     return false;
                   });
  stats.cells_visited += r.cells_visited;
  stats.steps += r.steps;
  return hit;
}

}  // namespace rtsim::accel
