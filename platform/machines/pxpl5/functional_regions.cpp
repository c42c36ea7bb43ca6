#include "platform/machines/pxpl5/functional_regions.hpp"

#include "firmware/tasks/lattice_ray_task.hpp"

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
    const auto cast = [&](int i, int j) {
      if (!cast_rays) {
        Sample blank;
        blank.index = lattice.index(i, j);
        return blank;
      }
      const std::int64_t pixel = lattice.pixel(i, j);
      return task.cast(camera, lattice, i, j, spp, [&](bool found, const Hit& hit) {
        if (pixel >= 0) ctx.frame->record_primary(static_cast<std::uint32_t>(pixel), found, hit);
      });
    };
    const auto update = [&](int i, int j) {
      return tasks::updated_in_frame(i, j, 0, lay.update_period);
    };
    const auto out = [&](const Sample& s) {
      by_compositor[static_cast<std::size_t>(lay.compositor_of_lattice_row(lattice.j_of(s.index)))]
          .push_back(s);
    };
    tasks::sample_region(lattice, lay.rule, g.lattice, spp, cast, update, out);
  }
  return by_compositor;
}

}  // namespace rtsim::platform::pxpl5
