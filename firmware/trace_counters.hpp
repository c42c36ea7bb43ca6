#pragma once
// Counts of the work done while tracing, reported into stats.json. Integers only, summed per
// thread and then added together, so the totals do not depend on the thread count.
#include <array>
#include <cstdint>

#include "firmware/cost.hpp"
#include "firmware/ray.hpp"

namespace rtsim {

struct TraceCounters {
  std::array<std::uint64_t, 4> rays{};   ///< by RayKind
  std::uint64_t intersection_tests = 0;  ///< ray/primitive tests
  std::uint64_t hits = 0;
  std::uint64_t box_tests = 0;  ///< shell (bounding box) tests
  std::uint64_t dda_steps = 0;  ///< subvolume steps of the grid DDA
  std::uint64_t cells_visited = 0;
  std::uint64_t patch_subdivisions = 0;  ///< Wang 4-way splits
  Cost cost;                             ///< firmware cost (intersection + shading)

  std::uint64_t total_rays() const { return rays[0] + rays[1] + rays[2] + rays[3]; }
  void count_ray(RayKind k) { ++rays[static_cast<std::size_t>(k)]; }

  TraceCounters& operator+=(const TraceCounters& o) {
    for (std::size_t i = 0; i < rays.size(); ++i) rays[i] += o.rays[i];
    intersection_tests += o.intersection_tests;
    hits += o.hits;
    box_tests += o.box_tests;
    dda_steps += o.dda_steps;
    cells_visited += o.cells_visited;
    patch_subdivisions += o.patch_subdivisions;
    cost += o.cost;
    return *this;
  }
};

}  // namespace rtsim
