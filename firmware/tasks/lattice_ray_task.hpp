#pragma once
// A ray caster's task for one position of the sample lattice (sample_lattice.hpp; seed 004
// L360-L369): the `spp` vision rays a pixel at that position would have (sample 0 through its
// centre, later ones on the R2 sequence, as VisionRayTask), each traced with the ray tree it
// spawns, summed in fixed point. A position may lie one past the image's last column or row: the
// camera extends there.
#include <vector>

#include "firmware/shading/camera.hpp"
#include "firmware/shading/pixel_accumulator.hpp"
#include "firmware/tasks/ray_tree.hpp"
#include "firmware/tasks/sample_lattice.hpp"
#include "firmware/tasks/vision_ray_task.hpp"

namespace rtsim::tasks {

class LatticeRayTask {
 public:
  LatticeRayTask(const Tracer& tracer, ShadeTask& shade, TraceCounters& counters)
      : tracer_(&tracer), shade_(&shade), counters_(&counters), scratch_(1, 1) {}

  /// The value at position (i, j) of `lattice` seen through `camera`; `on_primary(found, hit)`
  /// is told sample 0's primary answer (the AOVs).
  template <class OnPrimary>
  LatticeSample cast(const shading::PinholeCamera& camera, const SampleLattice& lattice, int i,
                     int j, int spp, OnPrimary&& on_primary) {
    LatticeSample out;
    out.index = lattice.index(i, j);
    const double x = static_cast<double>(i) * lattice.finest();
    const double y = static_cast<double>(j) * lattice.finest();
    for (int s = 0; s < spp; ++s) {
      double dx = 0.5, dy = 0.5;
      sample_offset(s, dx, dy);
      shading::TracedRay r;
      r.ray = camera.primary(x + dx, y + dy);
      r.kind = RayKind::Primary;
      r.pixel = 0;  // the scratch accumulator's one pixel
      counters_->cost += VisionRayTask::kCost;
      bool first = true;
      trace_ray_tree(r, *tracer_, *shade_, scratch_, *counters_, stack_, spawned_,
                     [&](const shading::TracedRay&, bool found, const Hit& hit) {
                       if (first && s == 0) {
                         out.id = found ? static_cast<std::int32_t>(hit.prim_id) : -1;
                         on_primary(found, hit);
                       }
                       first = false;
                     });
    }
    out.sum = scratch_.raw(0);
    scratch_.clear(0);
    return out;
  }

 private:
  const Tracer* tracer_;
  ShadeTask* shade_;
  TraceCounters* counters_;
  shading::PixelAccumulator scratch_;
  std::vector<shading::TracedRay> stack_, spawned_;
};

}  // namespace rtsim::tasks
