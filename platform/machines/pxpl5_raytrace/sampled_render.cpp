#include "platform/machines/pxpl5_raytrace/sampled_render.hpp"

#include <chrono>

#include "platform/functional/frame_state.hpp"
#include "platform/machines/pxpl5_raytrace/camera_path.hpp"
#include "platform/machines/pxpl5_raytrace/region_cast.hpp"

namespace rtsim::platform::pxpl5 {

functional::RenderResult sampled_render(const scenes::Scene& scene, const Tracer& tracer,
                                        const functional::RenderOptions& opts, Layout layout,
                                        const CameraPath& path,
                                        const tasks::RefinementSchedule& schedule,
                                        int display_frame) {
  const auto start = std::chrono::steady_clock::now();
  layout.width = opts.width > 0 ? opts.width : scene.camera.width;
  layout.height = opts.height > 0 ? opts.height : scene.camera.height;
  const int w = layout.width, h = layout.height, spp = std::max(1, opts.spp);
  const tasks::SampleLattice lattice = layout.lattice();
  functional::FrameState frame(w, h, spp, opts.aov_id, opts.aov_depth);
  tasks::ShadeTask shade(scene, opts.shade);
  tasks::LatticeRayTask task(tracer, shade, frame.counters());
  // The compositors' persistent array, whole: a frame's first copy of a position replaces the
  // last frame's; a replicated copy in the same frame keeps the better (Compositor::run).
  std::vector<tasks::LatticeSample> kept(lattice.size());
  for (std::size_t k = 0; k < kept.size(); ++k) kept[k].index = static_cast<std::uint32_t>(k);
  std::vector<int> written(kept.size(), -1);
  const std::vector<Region> regions = layout.regions();
  for (int fr = 0; fr <= display_frame; ++fr) {
    const shading::PinholeCamera camera(frame_camera(scene.camera, path, fr), w, h);
    const bool shown = fr == display_frame;
    for (const Region& g : regions)
      cast_region(layout, schedule, task, camera, spp, g, fr, shown ? &frame : nullptr,
                  [&](const tasks::LatticeSample& s) {
                    tasks::keep_copy(kept[s.index], written[s.index], s, fr);
                  });
    if (opts.progress) opts.progress(fr + 1, display_frame + 1);
  }
  // The splat processors' resampling, on the grid of the level the frame is displayed at.
  const int step = schedule.step(schedule.plan(display_frame).display_level);
  const auto at = [&](int i, int j) -> const std::array<std::int64_t, 3>& {
    return kept[lattice.index(i, j)].sum;
  };
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      frame.fb().add_raw(static_cast<std::uint32_t>(y) * static_cast<std::uint32_t>(w) +
                             static_cast<std::uint32_t>(x),
                         lattice.resample(x, y, step, at));
  const double wall =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return frame.finish(wall);
}

}  // namespace rtsim::platform::pxpl5
