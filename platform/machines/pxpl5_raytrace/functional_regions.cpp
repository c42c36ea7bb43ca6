#include "platform/machines/pxpl5_raytrace/functional_regions.hpp"

#include "platform/machines/pxpl5_raytrace/region_cast.hpp"

namespace rtsim::platform::pxpl5 {

std::vector<std::vector<Sample>> cast_functionally(const Context& ctx,
                                                   const std::function<bool(int)>& functional,
                                                   bool cast_rays) {
  const Layout& lay = ctx.layout;
  const tasks::SampleLattice lattice = lay.lattice();
  const int spp = ctx.frame->spp();
  tasks::ShadeTask shade(*ctx.scene, ctx.shade);
  tasks::LatticeRayTask task(*ctx.tracer, shade, ctx.frame->counters());
  const shading::PinholeCamera& camera = ctx.cameras.front();
  std::vector<std::vector<Sample>> by_compositor(static_cast<std::size_t>(lay.compositors));
  for (const Region& g : lay.regions()) {
    if (!functional(g.id)) continue;
    const auto out = [&](const Sample& s) {
      by_compositor[static_cast<std::size_t>(lay.compositor_of_lattice_row(lattice.j_of(s.index)))]
          .push_back(s);
    };
    cast_region(lay, task, camera, spp, g, 0, ctx.frame, out, cast_rays);
  }
  return by_compositor;
}

}  // namespace rtsim::platform::pxpl5
