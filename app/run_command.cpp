// `rtsim run`: a timed machine model (SystemC) renders one frame.
#include <algorithm>
#include <charconv>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <optional>
#include <thread>

#include "app/cli.hpp"
#include "app/commands.hpp"
#include "app/configuration.hpp"
#include "app/image_files.hpp"
#include "app/number_text.hpp"
#include "app/output_set.hpp"
#include "app/progress_bar.hpp"
#include "app/run_report.hpp"
#include "app/run_summary.hpp"
#include "app/sample_pilot.hpp"
#include "app/scene_input.hpp"
#include "app/stats_json.hpp"
#include "app/trace_options.hpp"
#include "common/input_error.hpp"
#include "platform/machine.hpp"
#include "platform/machine_registry.hpp"
#include "platform/machines/frame_sample.hpp"
#include "platform/runs/run_request.hpp"

namespace rtsim::app {

namespace {

/// The command as a user would type it again (for the report).
std::string command_line(const RunArgs& a) {
  std::string s = "rtsim run --machine " + runs::shell_quote(a.machine) + " --scene " +
                  runs::shell_quote(a.scene);
  if (a.width > 0) s += " --width " + std::to_string(a.width);
  if (a.height > 0) s += " --height " + std::to_string(a.height);
  for (const auto& c : a.config.config_files) s += " --config " + runs::shell_quote(c);
  for (const auto& p : a.config.overrides) s += " -p " + runs::shell_quote(p);
  if (!a.quantum.empty()) s += " --quantum " + runs::shell_quote(a.quantum);
  if (a.spp > 0) s += " --spp " + std::to_string(a.spp);
  for (const auto& t : a.traces) s += " --trace " + t;
  if (!a.trace_window.empty()) s += " --trace-window " + runs::shell_quote(a.trace_window);
  for (const auto& m : a.trace_modules) s += " --trace-modules " + runs::shell_quote(m);
  if (a.trace_max_events != 0) s += " --trace-max-events " + std::to_string(a.trace_max_events);
  for (const auto& v : a.aovs) s += " --aov " + v;
  if (a.image != "all") s += " --image " + a.image;
  if (a.overhead) s += " --overhead";
  if (a.latency_probe) s += " --latency-probe";
  if (a.sample > 0) s += " --sample " + std::to_string(a.sample);
  if (!a.sample_error.empty()) s += " --sample-error " + runs::shell_quote(a.sample_error);
  if (a.sample_window > 0) s += " --sample-window " + std::to_string(a.sample_window);
  if (a.sample_warmup >= 0) s += " --sample-warmup " + std::to_string(a.sample_warmup);
  if (a.sample_work_stride >= 0)
    s += " --sample-work-stride " + std::to_string(a.sample_work_stride);
  for (const auto& f : a.faults) s += " --fault " + runs::shell_quote(f);
  return s + " --report --out " + runs::shell_quote(a.out_dir);
}

/// --fault MEMORY:WORD:XOR (WORD decimal, XOR decimal or 0x hex, non-zero, 32 bits).
platform::MemoryFault parse_fault(const std::string& text) {
  const auto bad = [&text](const std::string& why) {
    return InputError("--fault " + text, 0,
                      why +
                          "; expected MEMORY:WORD:XOR, e.g. "
                          "peripheral.parameter_memories:3:0x80000000");
  };
  const std::size_t a = text.find(':');
  const std::size_t b = a == std::string::npos ? a : text.find(':', a + 1);
  if (b == std::string::npos || text.find(':', b + 1) != std::string::npos)
    throw bad("three fields separated by ':'");
  platform::MemoryFault f;
  f.memory = text.substr(0, a);
  const std::string word = text.substr(a + 1, b - a - 1), mask = text.substr(b + 1);
  const auto [wp, we] = std::from_chars(word.data(), word.data() + word.size(), f.word);
  if (f.memory.empty() || word.empty() || we != std::errc() || wp != word.data() + word.size())
    throw bad("WORD must be a word index (0, 1, ...)");
  const bool hex = mask.size() > 2 && mask[0] == '0' && (mask[1] == 'x' || mask[1] == 'X');
  const char* first = mask.data() + (hex ? 2 : 0);
  const auto [mp, me] =
      std::from_chars(first, mask.data() + mask.size(), f.xor_mask, hex ? 16 : 10);
  if (mask.empty() || me != std::errc() || mp != mask.data() + mask.size() || f.xor_mask == 0)
    throw bad("XOR must be a non-zero 32-bit mask (decimal or 0x hex)");
  return f;
}

}  // namespace

int run_run(const RunArgs& args) {
  // Everything that can be wrong with the input is checked before any output exists.
  const platform::Machine& machine = platform::find_machine(args.machine);
  auto registry = build_registry(args.config, &machine);
  if (!args.quantum.empty()) {
    try {
      // A bare 0 needs no unit.
      registry.apply_override("quantum=" +
                              (args.quantum == "0" ? std::string("0 s") : args.quantum));
    } catch (const InputError& e) {
      throw InputError("--quantum " + args.quantum, 0, e.message());
    }
  }
  // As `render --spp`: the parameter render.spp, which a machine that cannot take several
  // samples a pixel refuses with its reason.
  if (args.spp > 0) registry.apply_override("render.spp=" + std::to_string(args.spp));
  platform::RunOptions opts;
  for (const auto& f : args.faults) opts.faults.push_back(parse_fault(f));
  const modules::TraceFilter trace_filter =
      trace_filter_from(args.trace_window, args.trace_modules);
  if (args.traces.empty() &&
      (!args.trace_window.empty() || !args.trace_modules.empty() || args.trace_max_events != 0))
    throw InputError("--trace-window/--trace-modules/--trace-max-events", 0,
                     "narrow a trace, so they need --trace vcd and/or --trace perfetto");
  scenes::Scene scene = load_scene_with_seed(args.scene, registry);
  platform::FunctionalTwin twin = machine.make_twin(scene, registry);

  OutputSet out(args.out_dir);
  out.supersede(OutputSet::kFrameOutputs);
  opts.width = args.width;
  opts.height = args.height;
  opts.aov_id = wants_aov(args.aovs, "id");
  opts.aov_depth = wants_aov(args.aovs, "depth");
  opts.image = args.image != "none";
  if (!opts.image && !args.aovs.empty())
    throw InputError("--image none", 0, "writes no image, so it takes no --aov");
  if (args.image != "all" && !args.aovs.empty())
    throw InputError("--image " + args.image, 0,
                     "writes image.png only; the --aov files are EXR: use --image all");
  if (!opts.image && args.report)
    throw InputError("--image none", 0, "--report shows the image: use --image png or all");
  opts.latency_probe = args.latency_probe;
  const bool sampled = args.sample > 0 || !args.sample_error.empty();
  if (sampled && !machine.info().samples)
    throw InputError(args.sample > 0 ? "--sample" : "--sample-error " + args.sample_error, 0,
                     machine.name() + " does not sample: " + machine.info().sampling_refusal);
  if (args.sample_window > 0 && !sampled)
    throw InputError("--sample-window", 0,
                     "sizes the windows of --sample K or --sample-error E: give one of them too");
  if (args.sample_warmup >= 0 && !sampled)
    throw InputError("--sample-warmup", 0,
                     "is the warm-up of --sample K or --sample-error E: give one of them too");
  if (args.sample_work_stride >= 0 && !sampled)
    throw InputError("--sample-work-stride", 0,
                     "is the work count of --sample K or --sample-error E: give one of them too");
  if (args.sample > 0 && !args.sample_error.empty())
    throw InputError("--sample-error " + args.sample_error, 0,
                     "chooses K itself: give --sample K or --sample-error E, not both");
  const double sample_error =
      args.sample_error.empty() ? 0.0 : parse_sample_error(args.sample_error);
  const int width = args.width > 0 ? args.width : scene.camera.width;
  const int height = args.height > 0 ? args.height : scene.camera.height;
  if (sampled) {
    opts.sample_every = args.sample;
    opts.sample_window_rows =
        args.sample_window > 0 ? args.sample_window : machine.sample_window_rows(registry);
    // The warm-up: as asked, or the windows holding the machine's warm-up rays.
    opts.sample_warmup =
        args.sample_warmup >= 0
            ? args.sample_warmup
            : platform::FrameSample::default_warmup(
                  width, opts.sample_window_rows,
                  platform::FrameSample::windows_in(height, opts.sample_window_rows),
                  machine.sample_warmup_rays(registry));
    if (args.sample_work_stride >= 0) opts.sample_work_stride = args.sample_work_stride;
  }
  opts.trace_filter = trace_filter;
  opts.trace_max_events = args.trace_max_events;
  for (const auto& t : args.traces) {
    if (t == "vcd") opts.vcd_path = out.stage("trace.vcd");
    if (t == "perfetto") opts.perfetto_path = out.stage("trace.json");
  }
  std::optional<SamplePlan> plan;
  if (sample_error > 0) {
    plan = plan_sample(machine, scene, twin, registry, opts,
                       machine.sample_units(registry, width, height), sample_error);
    opts.sample_every = plan->every >= 2 ? plan->every : 0;
  }
  ProgressBar bar(args.quiet ? std::string() : "run " + machine.name());
  if (!args.quiet) opts.progress = [&bar](long done, long total) { bar.update(done, total); };
  // A trace too large to open is said while there is time to stop the run (Ctrl-C writes
  // nothing); the end of the run says it again with the file's size.
  opts.trace_too_large = [&bar](const std::string& file, std::uint64_t bytes, double at_s) {
    bar.note("rtsim: warning: " + file + (at_s >= 0 ? " has passed " : " will be about ") +
             std::to_string(bytes / 1000000) + " MB" +
             (at_s >= 0 ? " at " + format_seconds(at_s) + " of simulated time" : std::string()) +
             ", more than the " + std::to_string(kTraceWarnBytes / 1000000) + " MB " +
             (file.ends_with(".vcd") ? "GTKWave" : "Perfetto's UI") +
             " opens comfortably; Ctrl-C stops the run and writes nothing: keep "
             "less with --trace-window T0,T1, --trace-modules PATTERN or --trace-max-events N");
  };
  // The image library (OpenImageIO and the 260 libraries it brings) takes 0.2-0.6 s to load,
  // all of it relocations on one core: loaded on another while the machine runs, it is there
  // when the image is written. A jthread: joined on every way out (and call_once makes the
  // writer wait for it); its threads block the interrupt signals as this one does. Not under
  // --overhead: the ratio's simulation has the machine to itself, as the functional render it
  // is set against does.
  std::jthread image_module_load;
  if (args.image != "none" && !args.overhead)
    image_module_load = std::jthread([] {
      try {
        preload_image_module();
      } catch (...) {
        // Said where the image is written, with the places looked in.
      }
    });
  platform::RunResult result = machine.run(scene, twin, registry, opts);
  bar.phase(args.overhead ? "functional render (--overhead), writing outputs" : "writing outputs");
  // The pilot is part of what the run cost.
  if (plan) result.image.wall_time_s += plan->pilot_wall_s;

  auto stats = frame_stats_json("run", machine.name(), scene, *twin.geometry, registry,
                                twin.settings, result.image, 1, result.simulated_time_s);
  if (args.overhead) {
    // The same scene, the same geometry conversion, with no timing, in this process.
    functional::RenderOptions fo;
    fo.width = result.image.width;
    fo.height = result.image.height;
    fo.spp = twin.settings.spp;
    fo.threads = 1;
    fo.shade = twin.settings.shade;
    const auto functional_result = platform::render_twin(twin, scene, fo);
    stats["functional_wall_time_s"] = functional_result.wall_time_s;
    stats["overhead_ratio"] = result.image.wall_time_s / functional_result.wall_time_s;
    stats["functional_image_identical"] = functional_result.rgb == result.image.rgb;
  }
  // Machine keys are added; an object the app already wrote (scene_stats) is extended. Moved,
  // not copied: `modules` of a 32 x 32 array is 12 MB of JSON.
  for (auto& [key, value] : result.stats.items()) {
    if (value.is_object() && stats.contains(key) && stats[key].is_object())
      stats[key].update(value);
    else
      stats[key] = std::move(value);
  }
  if (plan) stats["sample"]["plan"] = plan->json;
  // The unit of every number above, from where each is declared (modules/stat_unit.hpp).
  stats["units"] = run_units(result.units).to_json();
  // Which image files the run wrote; with none, a sampled run rendered only its detailed rows.
  stats["image"]["files"] = args.image;

  // A trace that lost events says so wherever the numbers are read: here, stats.json `trace`,
  // the report.
  for (const std::string& warning : trace_warnings(stats))
    std::cerr << "rtsim: warning: " << warning << "\n";

  if (args.image == "all") stage_images(out, result.image);
  if (args.image == "png") stage_png(out, result.image);
  {
    std::ofstream f(out.stage("stats.json"));
    f << stats.dump(2) << "\n";
    if (!f) throw std::runtime_error("cannot write stats.json");
  }
  if (args.report) {
    // Drawn from the staged files, staged itself: it appears with the others or not at all.
    RunReportInputs in;
    in.stats_json = out.staged_path("stats.json");
    in.image_png = out.staged_path("image.png");
    in.trace_json = opts.perfetto_path;
    in.params = registry.list();
    in.command_line = command_line(args);
    ReportTools tools;
    tools.scratch_dir = out.staged_path(".report-plots");
    write_run_report(in, out.stage("report.html"), tools);
  }
  out.commit();

  bar.finish();
  if (!args.quiet) {
    std::vector<std::pair<std::string, std::string>> outputs;
    if (args.image == "all")
      outputs.emplace_back(
          "image", (out.dir() / "image.png").string() + "  " + (out.dir() / "image.exr").string());
    if (args.image == "png") outputs.emplace_back("image", (out.dir() / "image.png").string());
    if (args.image != "none" && !result.image.drawing_svg.empty())
      outputs.emplace_back("drawing", (out.dir() / "drawing.svg").string());
    outputs.emplace_back("stats", (out.dir() / "stats.json").string());
    if (!opts.vcd_path.empty()) outputs.emplace_back("trace", (out.dir() / "trace.vcd").string());
    if (!opts.perfetto_path.empty())
      outputs.emplace_back("trace", (out.dir() / "trace.json").string());
    if (args.report) outputs.emplace_back("report", (out.dir() / "report.html").string());
    std::cout << format_run_summary(stats, outputs);
  }
  return kExitOk;
}

}  // namespace rtsim::app
