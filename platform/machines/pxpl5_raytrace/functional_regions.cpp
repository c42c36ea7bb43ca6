#include "platform/machines/pxpl5_raytrace/functional_regions.hpp"

#include "platform/machines/pxpl5_raytrace/region_cast.hpp"

namespace rtsim::platform::pxpl5 {

std::vector<std::vector<Sample>> cast_functionally(const Setup& setup, MachineRun& run,
                                                   const std::function<bool(int)>& not_detailed,
                                                   bool cast_rays) {
  const Layout& lay = setup.layout;
  const tasks::SampleLattice lattice = lay.lattice();
  functional::FrameState& frame = run.frame();
  const int spp = frame.spp();
  tasks::ShadeTask shade(run.scene(), run.twin().settings.shade);
  tasks::LatticeRayTask task(*run.twin().tracer, shade, frame.counters());
  const shading::PinholeCamera& camera = setup.cameras.front();
  std::vector<std::vector<Sample>> by_compositor(static_cast<std::size_t>(lay.compositors));
  for (const Region& g : lay.regions()) {
    if (!not_detailed(g.id)) continue;
    const auto out = [&](const Sample& s) {
      by_compositor[static_cast<std::size_t>(lay.compositor_of_lattice_row(lattice.j_of(s.index)))]
          .push_back(s);
    };
    cast_region(lay, setup.schedule, task, camera, spp, g, 0, &frame, out, cast_rays);
  }
  return by_compositor;
}

}  // namespace rtsim::platform::pxpl5
