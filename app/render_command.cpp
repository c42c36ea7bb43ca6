// `rtsim render`: the functional renderer from the command line.
#include <cmath>
#include <fstream>
#include <iostream>

#include "app/cli.hpp"
#include "app/commands.hpp"
#include "app/configuration.hpp"
#include "app/image_files.hpp"
#include "app/output_set.hpp"
#include "app/progress_bar.hpp"
#include "app/stats_json.hpp"
#include "platform/functional/auto_view.hpp"
#include "platform/functional/functional_renderer.hpp"
#include "platform/functional/render_params.hpp"
#include "platform/functional/scene_geometry.hpp"
#include "platform/functional/scene_tracer.hpp"
#include "scenes/scene_loader.hpp"

namespace rtsim::app {

int run_render(const RenderArgs& args) {
  // Everything that can be wrong with the input is checked before any output exists.
  const auto registry = build_registry(args.config);
  auto settings = functional::read_render_settings(registry);
  if (args.spp > 0) settings.spp = args.spp;
  scenes::GeneratorSeeds seeds = scenes::default_generator_seeds();
  if (settings.scene_seed != 0) {
    seeds.npp = seeds.ullner_cubes = seeds.ullner_random = settings.scene_seed;
  }
  scenes::Scene scene = scenes::load_scene(args.scene, seeds);

  auto geometry = functional::convert_scene(scene, settings);
  if (!scene.has_camera) functional::frame_automatically(scene, geometry.scene_bounds);
  settings.shade.scene_extent = functional::scene_extent(geometry.scene_bounds);
  const auto tracer = functional::make_tracer(geometry, scene, settings);

  functional::RenderOptions opts;
  opts.width = args.width;
  opts.height = args.height;
  opts.spp = settings.spp;
  opts.threads = args.threads;
  opts.shade = settings.shade;
  for (const auto& a : args.aovs) {
    if (a == "id") opts.aov_id = true;
    if (a == "depth") opts.aov_depth = true;
  }
  ProgressBar bar(args.quiet ? std::string() : "render");
  if (!args.quiet) opts.progress = [&bar](int done, int total) { bar.update(done, total); };
  const auto result = functional::render(scene, *tracer, opts);

  OutputSet out(args.out_dir);
  write_png(out.stage("image.png"), result.width, result.height, result.rgb);
  write_exr(out.stage("image.exr"), result.width, result.height, 3, result.rgb);
  if (opts.aov_id) write_exr(out.stage("id.exr"), result.width, result.height, 1, result.id, "id");
  if (opts.aov_depth)
    write_exr(out.stage("depth.exr"), result.width, result.height, 1, result.depth, "Z");
  {
    std::ofstream stats(out.stage("stats.json"));
    stats << render_stats_json(scene, geometry, registry, settings, opts, result).dump(2) << "\n";
    if (!stats) throw std::runtime_error("cannot write stats.json");
  }
  out.commit();

  if (!args.quiet) {
    const double rays = static_cast<double>(result.counters.total_rays());
    std::cout << "rtsim render: " << scene.name << " at " << result.width << "x" << result.height
              << ", " << rays / 1e6 << " M rays in " << result.wall_time_s << " s\n"
              << "  image  " << (out.dir() / "image.png").string() << "  "
              << (out.dir() / "image.exr").string() << "\n"
              << "  stats  " << (out.dir() / "stats.json").string() << "\n";
    if (opts.aov_id || opts.aov_depth) {
      std::cout << "  aovs  ";
      if (opts.aov_id) std::cout << " " << (out.dir() / "id.exr").string();
      if (opts.aov_depth) std::cout << " " << (out.dir() / "depth.exr").string();
      std::cout << "\n";
    }
    if (geometry.report.rejected > 0)
      std::cout << "  note   " << geometry.report.rejected
                << " degenerate primitive(s) skipped; see stats.json geometry.messages\n";
  }
  return kExitOk;
}

}  // namespace rtsim::app
