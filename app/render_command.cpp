// `rtsim render`: the functional renderer from the command line.
#include <cmath>
#include <fstream>
#include <iostream>

#include "app/cli.hpp"
#include "app/commands.hpp"
#include "app/configuration.hpp"
#include "app/image_files.hpp"
#include "app/number_text.hpp"
#include "app/output_set.hpp"
#include "app/progress_bar.hpp"
#include "app/scene_input.hpp"
#include "app/stats_json.hpp"
#include "platform/functional/functional_renderer.hpp"
#include "platform/machine.hpp"
#include "platform/machine_registry.hpp"
#include "platform/machines/machine_support.hpp"

namespace rtsim::app {

int run_render(const RenderArgs& args) {
  // Everything that can be wrong with the input is checked before any output exists.
  const platform::Machine* machine =
      args.machine.empty() ? nullptr : &platform::find_machine(args.machine);
  auto registry = build_registry(args.config, machine);
  if (args.spp > 0) registry.apply_override("render.spp=" + std::to_string(args.spp));
  scenes::Scene scene = load_scene_with_seed(args.scene, registry);
  // With --machine: that machine's own geometry conversion and search, with no timing.
  platform::FunctionalTwin twin =
      machine ? machine->make_twin(scene, registry)
              : platform::make_functional_twin(scene, functional::read_render_settings(registry));
  const auto& settings = twin.settings;
  const auto& geometry = *twin.geometry;

  // The output folder is checked (and made) before the render: a bad --out costs no work.
  OutputSet out(args.out_dir);
  out.supersede(OutputSet::kFrameOutputs);
  functional::RenderOptions opts;
  opts.width = args.width;
  opts.height = args.height;
  opts.spp = settings.spp;
  opts.threads = args.threads;
  opts.shade = settings.shade;
  opts.aov_id = wants_aov(args.aovs, "id");
  opts.aov_depth = wants_aov(args.aovs, "depth");
  ProgressBar bar(args.quiet ? std::string() : "render");
  if (!args.quiet) opts.progress = [&bar](int done, int total) { bar.update(done, total); };
  const auto result = platform::render_twin(twin, scene, opts);
  bar.phase("writing outputs");
  if (result.threads < opts.threads)
    std::cerr << "rtsim: warning: the system would start only " << result.threads << " of the "
              << opts.threads << " worker threads asked for; rendered with " << result.threads
              << " (the image does not depend on it)\n";

  stage_images(out, result);
  {
    std::ofstream stats(out.stage("stats.json"));
    auto j = frame_stats_json("render", machine ? machine->name() : "functional", scene, geometry,
                              registry, settings, result, result.threads, -1.0);
    j["units"] = frame_units().to_json();
    stats << j.dump(2) << "\n";
    if (!stats) throw std::runtime_error("cannot write stats.json");
  }
  out.commit();
  bar.finish();

  if (!args.quiet) {
    const double rays = static_cast<double>(result.counters.total_rays());
    std::cout << "rtsim render: " << scene.name << " at " << result.width << "x" << result.height
              << ", " << format_significant(rays / 1e6) << " M rays in "
              << format_seconds(result.wall_time_s) << "\n"
              << "  image  " << (out.dir() / "image.png").string() << "  "
              << (out.dir() / "image.exr").string() << "\n"
              << "  stats  " << (out.dir() / "stats.json").string() << "\n";
    if (!result.drawing_svg.empty())
      std::cout << "  drawing  " << (out.dir() / "drawing.svg").string() << "\n";
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
