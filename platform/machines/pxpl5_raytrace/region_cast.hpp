#pragma once
// One screen region of pxpl5-raytrace cast with no timing, as a ray caster casts it
// (RayCaster::run): the region's lattice positions sampled by the layout's rule
// (tasks::sample_region), each cast by tasks::LatticeRayTask. Used by the functional twin of a
// sampled screen (sampled_render.cpp) and by a sampled run for the regions it does not simulate
// (functional_regions.cpp).
#include "firmware/shading/camera.hpp"
#include "firmware/tasks/lattice_ray_task.hpp"
#include "firmware/tasks/region_sampling.hpp"
#include "platform/functional/frame_state.hpp"
#include "platform/machines/pxpl5_raytrace/layout.hpp"

namespace rtsim::platform::pxpl5 {

/// Casts region `g` in frame `frame` of `schedule` (refinement and partial updating decide
/// which positions) and hands each
/// sample to `out`. The primary hits go into `primaries` (the image's frame: the last frame's;
/// null for an earlier frame). With `rays` false the samples are blank: the same positions, no
/// ray cast (what a --sample-error pilot, which wants only timing, needs).
template <class Out>
void cast_region(const Layout& layout, const tasks::RefinementSchedule& schedule,
                 tasks::LatticeRayTask& task, const shading::PinholeCamera& camera, int spp,
                 const Region& g, int frame, functional::FrameState* primaries, Out&& out,
                 bool rays = true) {
  const tasks::SampleLattice lattice = layout.lattice();
  const auto cast = [&](int i, int j) {
    if (!rays) {
      Sample blank;
      blank.index = lattice.index(i, j);
      return blank;
    }
    const std::int64_t pixel = primaries ? lattice.pixel(i, j) : -1;
    return task.cast(camera, lattice, i, j, spp, [&](bool found, const Hit& hit) {
      if (pixel >= 0) primaries->record_primary(static_cast<std::uint32_t>(pixel), found, hit);
    });
  };
  if (schedule.plan(frame).cast_level < 0) return;  // a resting view fully refined
  const auto update = [&](int i, int j) { return schedule.casts(i, j, frame); };
  tasks::sample_region(lattice, layout.rule, g.lattice, spp, cast, update, out);
}

}  // namespace rtsim::platform::pxpl5
