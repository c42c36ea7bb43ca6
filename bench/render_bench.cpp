// Whole-render throughput of the functional renderer, single thread: rays per second for the
// shared SPD scenes and the built-in scenes, with each acceleration structure.
// Run: build/bench/render_bench --benchmark_min_time=1   (figures in docs/benchmarks.md)
#include <benchmark/benchmark.h>

#include "platform/functional/auto_view.hpp"
#include "platform/functional/functional_renderer.hpp"
#include "platform/functional/scene_geometry.hpp"
#include "platform/functional/scene_tracer.hpp"
#include "scenes/scene_loader.hpp"

namespace {

using namespace rtsim;

void render_scene(benchmark::State& state, const std::string& spec, functional::AccelKind accel) {
  scenes::Scene scene = scenes::load_scene(spec);
  functional::RenderSettings settings;
  settings.accel = accel;
  auto geometry = functional::convert_scene(scene, settings);
  if (!scene.has_camera) functional::frame_automatically(scene, geometry.scene_bounds);
  settings.shade.scene_extent = functional::scene_extent(geometry.scene_bounds);
  const auto tracer = functional::make_tracer(geometry, scene, settings);
  functional::RenderOptions opts;
  opts.width = 128;
  opts.height = 128;
  opts.threads = 1;
  opts.shade = settings.shade;
  std::uint64_t rays = 0, tests = 0;
  for (auto _ : state) {
    const auto r = functional::render(scene, *tracer, opts);
    rays += r.counters.total_rays();
    tests += r.counters.intersection_tests;
    benchmark::DoNotOptimize(r.rgb.data());
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(rays));
  state.counters["tests_per_ray"] =
      static_cast<double>(tests) / static_cast<double>(std::max<std::uint64_t>(rays, 1));
}

const std::string kShared = RTSIM_SHARED_DIR;

}  // namespace

#define RTSIM_RENDER_BENCH(name, spec, accel)                               \
  BENCHMARK_CAPTURE(render_scene, name, spec, functional::AccelKind::accel) \
      ->Unit(benchmark::kMillisecond)

RTSIM_RENDER_BENCH(balls_s2_grid, kShared + "/scenes/balls-s2.nff", Grid);
RTSIM_RENDER_BENCH(balls_s2_shells, kShared + "/scenes/balls-s2.nff", Shells);
RTSIM_RENDER_BENCH(balls_s3_grid, kShared + "/scenes/balls-s3.nff", Grid);
RTSIM_RENDER_BENCH(balls_s3_shells, kShared + "/scenes/balls-s3.nff", Shells);
RTSIM_RENDER_BENCH(tetra_s3_grid, kShared + "/scenes/tetra-s3.nff", Grid);
RTSIM_RENDER_BENCH(tetra_s3_shells, kShared + "/scenes/tetra-s3.nff", Shells);
RTSIM_RENDER_BENCH(teapot_s2_grid, kShared + "/scenes/teapot-s2.nff", Grid);
RTSIM_RENDER_BENCH(teapot_s2_shells, kShared + "/scenes/teapot-s2.nff", Shells);
RTSIM_RENDER_BENCH(teapot_bpt_grid, kShared + "/scenes/teapot.bpt", Grid);
RTSIM_RENDER_BENCH(teapot_bpt_shells, kShared + "/scenes/teapot.bpt", Shells);
RTSIM_RENDER_BENCH(default_grid, "builtin:default", Grid);
RTSIM_RENDER_BENCH(default_shells, "builtin:default", Shells);
RTSIM_RENDER_BENCH(npp412_shells, "builtin:npp-412", Shells);
RTSIM_RENDER_BENCH(npp412_grid, "builtin:npp-412", Grid);
RTSIM_RENDER_BENCH(ullner_cubes_grid, "builtin:ullner-cubes", Grid);
RTSIM_RENDER_BENCH(ullner_cubes_shells, "builtin:ullner-cubes", Shells);
