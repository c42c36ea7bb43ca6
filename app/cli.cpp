#include "app/cli.hpp"

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <iostream>

#include "app/commands.hpp"
#include "app/interrupt_cleanup.hpp"
#include "common/input_error.hpp"
#include "common/suggest.hpp"
#include "modules/sim_time.hpp"
#include "platform/functional/every_core.hpp"
#include "platform/machine_registry.hpp"

namespace rtsim::app {
namespace {

constexpr const char* kDescription =
    "rtsim: a SystemC/TLM-2.0 transaction-level model of the parallel ray-tracing machines of\n"
    "the early 1980s and their successors (Ullner's peripheral, pipeline and array; Gaudet's\n"
    "multi-PERT machine; Wang's Bezier pipeline; ray tracing on Pixel-Planes 5) that renders\n"
    "real images while it measures.";

constexpr const char* kFooter =
    "\nExit status: 0 success, 1 internal failure, 2 bad input (scene, config, parameter, usage).\n"
    "Scenes: an .nff or .bpt file, or builtin:NAME (see `rtsim list scenes`).\n"
    "Parameters: `rtsim list params` prints every name with its value, unit, default and source.";

constexpr const char* kSweepFooter =
    "\nThe sweep file (docs/sweeps.md has the whole format and examples):\n"
    "  machine = \"ullner-peripheral\"          a machine, or a list of them (an axis)\n"
    "  scene = \"builtin:ullner-sheets-1000\"   a scene, or a list (files: relative to the sweep)\n"
    "  width = 64                             image size (optional: the scene's)\n"
    "  height = 64\n"
    "  configs = [\"base.toml\"]                optional --config files for every point\n"
    "  [params]                               fixed parameters, as -p NAME=VALUE\n"
    "  \"shade.max_depth\" = 0\n"
    "  [[axes]]                               an axis: one parameter and its values\n"
    "  param = \"peripheral.grid.divisions\"\n"
    "  range = { start = 1, stop = 30, step = 1 }     or count = N; or values = [1, 2, 4]\n"
    "  [[axes]]\n"
    "  param = \"pert_count\"\n"
    "  range = { start = 1, stop = 64, count = 7, scale = \"log\" }    1, 2, 4, ..., 64\n"
    "  [[axes]]                               zipped: parameters that advance together\n"
    "  zip = [ { param = \"a\", values = [1, 2] }, { param = \"b\", values = [\"1 ns\", \"2 ns\"] "
    "} ]\n"
    "The points are the cartesian product of the axes: machine, scene, then [[axes]] in file\n"
    "order, the last varying fastest. Every name and value is checked before any point runs.\n"
    "Run options may be set or swept too: sample, sample-error, image, latency-probe, trace.\n"
    "Points that differ only in parameters the image does not depend on (rtsim list params\n"
    "marks those it does) render it once: the others run timing-only (--image none) and get\n"
    "its files; share-images = false renders every point's.\n"
    "\nOutputs in --out: results.csv and results.jsonl (one row per point, in point order: the\n"
    "swept values, status, exit code, error, wall time and every stats.json number), and\n"
    "points/NNNN/ (stats.json, images, run.log, done.json). A point whose folder holds a\n"
    "done.json with the same command line is not run again. With --report also report.html:\n"
    "the sweep file, the results table, plots of the headline stats against each axis\n"
    "(analysis/sweep_plot.py), the points' images and the parameters with their sources.\n"
    "\nExit status: 0 all points ran, 1 a point failed (the others still run), 2 bad sweep file.";

/// A value from a fixed set, with "did you mean" for a near miss (`list param`).
CLI::Validator one_of(std::vector<std::string> allowed) {
  std::string names;
  for (const auto& a : allowed) names += (names.empty() ? "" : ", ") + a;
  return CLI::Validator(
      [allowed, names](std::string& value) -> std::string {
        if (std::find(allowed.begin(), allowed.end(), value) != allowed.end()) return {};
        const std::vector<std::string_view> views(allowed.begin(), allowed.end());
        return "'" + value + "' is not one of " + names + did_you_mean(value, views);
      },
      "{" + names + "}");
}

void add_config_options(CLI::App* cmd, ConfigArgs& cfg) {
  cmd->add_option("--config", cfg.config_files,
                  "TOML file(s) layered on the preset, in order (later files win)")
      ->check(CLI::ExistingFile);
  cmd->add_option("-p,--param", cfg.overrides,
                  "Set a parameter, NAME=VALUE (e.g. -p shade.max_depth=3, -p \"x.time=400 ns\"); "
                  "repeatable, applied after --config");
}

/// --width, --height and --aov, the same for every command that writes an image.
void add_image_options(CLI::App* cmd, int& width, int& height, std::vector<std::string>& aovs) {
  cmd->add_option("--width", width, "Image width in pixels (default: the scene's)")
      ->check(CLI::Range(1, 16384));
  cmd->add_option("--height", height, "Image height in pixels (default: the scene's)")
      ->check(CLI::Range(1, 16384));
  cmd->add_option("--aov", aovs,
                  "Extra outputs, comma-separated: id (primitive index of the primary hit, -1 "
                  "for a miss) and depth (primary hit distance, inf for a miss)")
      ->delimiter(',')
      ->check(CLI::IsMember({"id", "depth"}));
}

}  // namespace

int run_cli_in_forked_child(const std::vector<std::string>& args) {
  restart_interrupt_cleanup_after_fork();
  std::vector<std::string> copy = args;
  std::vector<char*> argv;
  for (auto& a : copy) argv.push_back(a.data());
  argv.push_back(nullptr);
  return run_cli(static_cast<int>(copy.size()), argv.data());
}

namespace {

/// `rtsim render`: its options into `render`.
CLI::App* add_render_command(CLI::App& app, RenderArgs& render) {
  auto* r = app.add_subcommand(
      "render",
      "Render a scene with the functional renderer: the firmware kernels and shading\n"
      "with no timing. Its image is the golden reference for every machine.");
  r->add_option("--scene", render.scene, "Scene file (.nff, .bpt) or builtin:NAME")
      ->capture_default_str();
  r->add_option("--machine", render.machine,
                "Render with that machine's own geometry conversion and search (its functional "
                "twin: the image `rtsim run` must reproduce), still with no timing");
  r->add_option("--out", render.out_dir,
                "Output folder: image.png, image.exr, stats.json (+ id.exr, depth.exr)")
      ->capture_default_str();
  add_image_options(r, render.width, render.height, render.aovs);
  r->add_option("--spp", render.spp, "Samples per pixel (default: render.spp, 1)")
      ->check(CLI::Range(1, 4096));
  r->add_option("--threads", render.threads,
                "Worker threads, 1 to 256 (the image does not depend on it; if the system "
                "cannot start them all, the render uses those it could and says so)")
      ->capture_default_str()
      ->check(CLI::Range(1, 256));
  r->add_flag("-q,--quiet", render.quiet, "Print nothing but errors");
  add_config_options(r, render.config);
  return r;
}

/// `rtsim run`: its options into `runa`.
CLI::App* add_run_command(CLI::App& app, RunArgs& runa) {
  auto* run = app.add_subcommand(
      "run",
      "Run a machine model: SystemC/TLM-2.0 modules with annotated timing render one\n"
      "frame; writes the image, stats.json (frame time, utilisation, latency) and traces.");
  runa.machine = platform::default_machine().name();
  run->add_option("--machine", runa.machine, "Machine (`rtsim list machines`)")
      ->capture_default_str();
  run->add_option("--scene", runa.scene, "Scene file (.nff, .bpt) or builtin:NAME")
      ->capture_default_str();
  run->add_option("--out", runa.out_dir,
                  "Output folder: image.png, image.exr, stats.json (+ AOVs, traces)")
      ->capture_default_str();
  add_image_options(run, runa.width, runa.height, runa.aovs);
  run->add_option("--trace", runa.traces,
                  "Traces, comma-separated: vcd (signals for GTKWave: every module's busy level "
                  "and every queue's depth, by stats.json names) and perfetto (the same signals "
                  "as counters, and transactions as slices: Chrome trace events for "
                  "ui.perfetto.dev). Their time-weighted means are stats.json's utilisation and "
                  "mean occupancy; every event is written (see --trace-window, --trace-modules, "
                  "--trace-max-events)")
      ->delimiter(',')
      ->check(CLI::IsMember({"vcd", "perfetto"}));
  run->add_option("--trace-window", runa.trace_window,
                  "Trace only simulated time T0..T1: \"T0,T1\", times with a unit (\"10 ms,20 "
                  "ms\") or plain seconds, on the traces' own time axis (the frame starts after "
                  "the scene load: stats.json trace.stats_interval_s). Default: all of time")
      ->type_name("T0,T1");
  run->add_option("--trace-modules", runa.trace_modules,
                  "Trace only the modules whose stats.json name matches a shell pattern "
                  "(comma-separated; '*' also matches dots: \"pert0*\", \"*queue*\", "
                  "\"host,peripheral.pipeline\"). Default: every module")
      ->type_name("GLOB")
      ->delimiter(',');
  run->add_option("--trace-max-events", runa.trace_max_events,
                  "Write at most N events to each trace file (Perfetto events, VCD value "
                  "changes); what is dropped is printed and counted in stats.json `trace`. "
                  "Default 0: every event")
      ->type_name("N")
      ->check(CLI::Validator(
          [](const std::string& v) {
            // Checked before conversion: an unsigned conversion would wrap "-3" around.
            const bool digits = !v.empty() && v.size() <= 18 &&
                                v.find_first_not_of("0123456789") == std::string::npos;
            return digits ? std::string()
                          : "\"" + v + "\" is not 0 (no limit) or a number of events";
          },
          ""));
  run->add_option("--spp", runa.spp,
                  "Samples per pixel (parameter render.spp; default 1); a machine that cannot "
                  "take several says why")
      ->check(CLI::Range(1, 4096));
  run->add_option("--quantum", runa.quantum,
                  "Global TLM quantum, e.g. \"10 us\" (parameter `quantum`; 0 is the reference)");
  run->add_option("--image", runa.image,
                  "Image files written: all (image.png, image.exr and the --aov files), png "
                  "(image.png only), or none: a timing-only run, for sweeps whose image does not "
                  "depend on what they vary; with --sample or --sample-error the rows not "
                  "simulated in detail are then not rendered at all (stats.json image.files; "
                  "the counts of rays and tests cover what was rendered)")
      ->capture_default_str()
      ->check(one_of({"all", "png", "none"}));
  run->add_flag("--overhead", runa.overhead,
                "Also render the same frame with no timing in this process and report "
                "functional_wall_time_s and overhead_ratio");
  run->add_option("--sample", runa.sample,
                  "Sampled simulation: one window of rows in K in detail (the first and every "
                  "K-th after it), the rest rendered functionally (the image is the same); the "
                  "frame time is estimated with a 99.7% confidence interval (stats.json sample)")
      ->check(CLI::Range(2, 1000000));
  run->add_option("--sample-error", runa.sample_error,
                  "Sampled simulation with K chosen for a target error, e.g. \"1%\": a pilot run "
                  "(about ten windows in detail, in a forked process) measures how the windows "
                  "vary (with the work count, how far they stray from their work); K is the "
                  "largest whose 99.7% interval is expected within E of the frame "
                  "time (1, the whole frame in detail, if K = 2 would not be). stats.json "
                  "sample.plan; the pilot's time is in wall_time_s");
  run->add_option("--sample-window", runa.sample_window,
                  "Rows of a --sample window (default: the machine's; gaudet-pert's is its PERT "
                  "count, so that a window keeps every PERT busy; pxpl5-raytrace's windows are "
                  "screen regions, in the order its master hands them out, and this counts "
                  "regions)")
      ->check(CLI::Range(1, 1000000));
  run->add_option("--sample-warmup", runa.sample_warmup,
                  "Windows after window 0 that a --sample run simulates in detail before it "
                  "samples, and leaves out of the per-window mean: the machine's queues fill "
                  "meanwhile (default: the windows holding 512 vision rays, at most an eighth of "
                  "the frame; none on ullner-array, whose processors start their rays at once; "
                  "0: none). stats.json sample.warmup_windows. Not for pxpl5-raytrace, whose "
                  "casters share its regions")
      ->check(CLI::Range(0, 1000000));
  run->add_option("--sample-work-stride", runa.sample_work_stride,
                  "The work-weighted estimate of a --sample run (docs/sampling.md): the rows not "
                  "simulated in detail have every S-th pixel traced functionally to count their "
                  "intersection tests and rays, and the frame time is regressed on the work of "
                  "the windows simulated (default 2; larger S is faster and less exact, stats.json "
                  "sample.work; 0: no work counted, the systematic estimate from the windows' "
                  "completions alone, also where the work does not vary or there are too few "
                  "windows)")
      ->check(CLI::Range(0, 4096));
  run->add_flag("--latency-probe", runa.latency_probe,
                "Record each ray's end-to-end latency (from entering the machine until the host "
                "has its answer; on pxpl5-raytrace each sample's, from its caster to its "
                "compositor) broken down by stage (module or queue) into queueing, service "
                "and transfer time: stats.json `latency_probe` (docs/stats.md); with --report, "
                "a \"Where a ray spends its time\" section");
  run->add_option("--fault", runa.faults,
                  "Corrupt a word on its way into a memory, MEMORY:WORD:XOR (e.g. "
                  "peripheral.parameter_memories:3:0x80000000 flips the sign of polygon 0's "
                  "d_p): the word is stored XORed with the mask. Repeatable. The answers come "
                  "from the memories' words, so the image shows it; stats.json `faults` says how "
                  "often each was applied (docs/stats.md). Memories: "
                  "peripheral.parameter_memories (ullner-peripheral, 25 words a polygon), "
                  "shell_bus.memory and prim_bus.memory (gaudet-pert when broadcasting: the ID "
                  "list, 3 words an entry, then the packets), pipeline.polygon_registers "
                  "(ullner-pipeline, 21 words a processor), host.patch_memory (wang-bezier, 48 "
                  "words a patch), nodeK.memory (ullner-array: the lines kept, 28 or 52 words "
                  "each, then the attributes, lists and view), nodeK.frame_buffer "
                  "(ullner-array: its block of the image, 6 words a pixel); an unknown name "
                  "lists the machine's. In flight, host.broadcast (ullner-array: word WORD of the "
                  "host's broadcast, every processor receives it), nodeK.link_D (ullner-array: "
                  "every ray message the link carries, 17 words) and every "
                  "message corrupted on its way: pipeline.engineK.in (ullner-pipeline: each ray "
                  "description entering processor K, 13 words), pipeline.input (wang-bezier: "
                  "each job entering stage 0, 54 words) and pipeline.loopK.in (wang-bezier: "
                  "each job entering loop stage K, 206 words), counted in stats.json "
                  "pipeline.faults_in_flight and wang.faults_in_flight");
  run->add_flag("--report", runa.report,
                "Also write report.html: one self-contained page with the image, headline "
                "numbers, utilisation and latency plots (analysis/, python3-matplotlib) and the "
                "parameters with their sources");
  run->add_flag("-q,--quiet", runa.quiet, "Print nothing but errors");
  add_config_options(run, runa.config);
  return run;
}

/// `rtsim sweep`: its options into `sw`.
CLI::App* add_sweep_command(CLI::App& app, SweepArgs& sw) {
  auto* sweep = app.add_subcommand(
      "sweep",
      "Run a parameter sweep from a TOML file: each point of the product of its axes is one\n"
      "`rtsim run` process; writes one results table (CSV and JSON lines) and each point's\n"
      "stats.json. Re-running the same sweep skips the points already done.");
  sweep->footer(kSweepFooter);
  sweep->add_option("file", sw.file, "The sweep file (TOML)")->required();
  sweep->add_option("--out", sw.out_dir,
                    "Output folder: results.csv, results.jsonl, points/NNNN/ (default: "
                    "out/sweeps/<file name>)");
  sweep
      ->add_option("--jobs", sw.jobs,
                   "Points at once, each its own process (default: the cores; with --mpi, 1 "
                   "per rank; more than 1 per rank needs mpirun --bind-to none, or the points "
                   "share the rank's core)")
      ->check(CLI::Range(1, 1024));
  auto* mpi_flag = sweep->add_flag(
      "--mpi", sw.mpi,
      "Spread the points over MPI ranks (mpirun -np K rtsim sweep FILE --mpi): rank 0 hands "
      "them out one at a time and writes the table");
  sweep
      ->add_option("--one-host", sw.one_host,
                   "With --mpi, when the launcher says every rank is on this host: jobs (the "
                   "default) runs the points in rank 0 as local jobs, one for each rank's "
                   "--jobs, on all the ranks' CPUs, without starting MPI (its start-up is all "
                   "it would add); mpi hands them out over MPI as on many hosts")
      ->check(CLI::IsMember({"jobs", "mpi"}))
      ->needs(mpi_flag);
  sweep->add_flag("--force", sw.force, "Run every point again, even those done before");
  sweep->add_flag("--list", sw.list,
                  "Print each point's command line (and whether it is done); run nothing");
  sweep
      ->add_option("--rtsim", sw.rtsim,
                   "The rtsim binary to run for each point (default: this one)")
      ->check(CLI::ExistingFile);
  sweep->add_flag("--report", sw.report,
                  "Also write report.html in --out: one self-contained page with the sweep file, "
                  "the results table (failed points listed), plots of frame time, speed-up, "
                  "utilisation and latency against each axis (analysis/sweep_plot.py, "
                  "python3-matplotlib), thumbnails of the first 24 images and the parameters "
                  "with their sources");
  sweep
      ->add_option("--baseline", sw.baseline,
                   "With --report: compare every point with point N (as in points/NNNN): its "
                   "frame time, speed-up and largest changes against it (as `rtsim diff`)")
      ->check(CLI::NonNegativeNumber);
  sweep->add_flag("-q,--quiet", sw.quiet, "Print nothing but errors");
  return sweep;
}

/// `rtsim validate`: its options into `va`.
CLI::App* add_validate_command(CLI::App& app, ValidateArgs& va) {
  auto* validate = app.add_subcommand(
      "validate",
      "Reproduce the seeds' figures: run `rtsim run` (one process per simulation) and\n"
      "`rtsim render`, compare each figure with the seed's value within a stated tolerance,\n"
      "print a table, write validation.json and validation.csv. Exit 0 if every figure\n"
      "expected to pass passes: a known open figure (\"FAIL (open)\") does not count.\n"
      "docs/validation.md describes every figure.");
  validate->add_flag("--quick", va.quick,
                     "Smaller images and fewer grid sizes (CI); each row says how it scales");
  validate->add_option("--jobs", va.jobs, "Runs at once (each is its own process)")
      ->capture_default_str()
      ->check(CLI::Range(1, 1024));
  validate
      ->add_option("--only", va.only,
                   "Comma-separated figure ids, or groups (V2 = V2a..V2d); see --list")
      ->delimiter(',');
  validate->add_option("--out", va.out_dir,
                       "Folder for validation.json, validation.csv, fig2-18.csv (default: a "
                       "temporary folder, removed unless --keep)");
  validate->add_flag("--keep", va.keep, "Keep every run's folder (stats.json, images, logs)");
  validate->add_flag("--list", va.list, "List the figures, their tolerances and why; run nothing");
  validate->add_option("--rtsim", va.rtsim, "The rtsim binary to run (default: this one)")
      ->check(CLI::ExistingFile);
  validate->add_flag(
      "--sensitivity", va.sensitivity,
      "Also move each assumption a figure names (a parameter whose source is no seed line) by\n"
      "--factors, or to the values the figure states, run again, and report which figures\n"
      "move and whose verdict changes: a table, validation-sensitivity.json and\n"
      "validation-sensitivity.png (docs/validation.md)");
  validate
      ->add_option("--factors", va.factors,
                   "With --sensitivity: the factors a numeric assumption is moved by")
      ->delimiter(',')
      ->capture_default_str()
      ->check(CLI::Validator(
          [](const std::string& text) -> std::string {
            char* end = nullptr;
            const double v = std::strtod(text.c_str(), &end);
            if (end == text.c_str() || *end != '\0' || !std::isfinite(v) || v <= 0)
              return "'" + text + "' is not a positive number (e.g. --factors 0.5,2)";
            return {};
          },
          "FACTOR > 0"));
  auto* validate_mpi =
      validate->add_flag("--mpi", va.mpi,
                         "Spread the runs over MPI ranks as `rtsim sweep --mpi` does (mpirun -np "
                         "K rtsim validate --mpi ...); --jobs runs at once on each rank");
  validate
      ->add_option("--one-host", va.one_host,
                   "With --mpi, when the launcher says every rank is on this host: jobs (the "
                   "default) validates in rank 0 with every rank's --jobs as local jobs, without "
                   "starting MPI; mpi hands the runs out over MPI as on many hosts")
      ->check(CLI::IsMember({"jobs", "mpi"}))
      ->needs(validate_mpi);
  return validate;
}

/// `rtsim list`: its options into `list`.
CLI::App* add_list_command(CLI::App& app, ListArgs& list) {
  auto* l = app.add_subcommand(
      "list",
      "List built-in scenes, machines, parameters, or the assumptions (parameters whose source\n"
      "is no seed line) with the validation figures that rest on each");
  l->add_option("what", list.what, "scenes | machines | params | assumptions")
      ->required()
      ->check(one_of({"scenes", "machines", "params", "assumptions"}));
  l->add_option("pattern", list.pattern,
                "With params: only the names matching this shell pattern, '*' also matching "
                "dots (quote it): 'pert.*', '*word_time', 'peripheral.grid.*'");
  l->add_option(
      "--machine", list.machine,
      "With params or assumptions: the machine whose parameters to list (assumptions: every "
      "machine without it)");
  l->add_flag("--changed", list.changed,
              "With params: only those whose value is not the default (set by --config or -p)");
  l->add_option("--format", list.format,
                "text; with params or assumptions also markdown (docs/parameters.md, "
                "docs/assumptions.md); json with params (one "
                "object a parameter: name, kind, value, default, unit, min, max, allowed, "
                "source, affects_image), machines (name, description, sample_scene) or scenes "
                "(name, scene, description)")
      ->check(CLI::IsMember({"text", "markdown", "json"}))
      ->capture_default_str();
  add_config_options(l, list.config);
  return l;
}

/// `rtsim diff`: its options into `diff`.
CLI::App* add_diff_command(CLI::App& app, DiffArgs& diff) {
  auto* df = app.add_subcommand(
      "diff",
      "Compare two runs: the parameters that differ and every statistic that changed, with its\n"
      "relative change, largest first (wall-clock numbers apart). Exit 0 whether they differ or "
      "not.");
  df->add_option("A", diff.a, "A run folder (rtsim run --out) or its stats.json")->required();
  df->add_option("B", diff.b, "The other run")->required();
  df->add_flag("--all", diff.all,
               "Every changed statistic (default: the " + std::to_string(DiffArgs::kStatsShown) +
                   " largest changes)");
  df->add_option("--tolerance", diff.tolerance,
                 "Relative difference below which two numbers count as the same (e.g. 1e-9)")
      ->check(CLI::Validator(
          [](const std::string& text) -> std::string {
            // CLI::Range lets NaN through (every comparison with it is false).
            double v = 0.0;
            try {
              v = std::stod(text);
            } catch (const std::exception&) {
              return "not a number: " + text;
            }
            return v >= 0.0 && v <= 1.0 ? "" : "a relative difference from 0 to 1, got " + text;
          },
          "FLOAT in [0 - 1]"))
      ->capture_default_str();
  return df;
}

/// `rtsim describe`: its options into `da`.
CLI::App* add_describe_command(CLI::App& app, DescribeArgs& da) {
  auto* d = app.add_subcommand(
      "describe",
      "Print a machine's module tree: each module with its parameters and statistics, and the "
      "connections between modules; with --out, also a block diagram (DOT, and SVG if Graphviz "
      "is installed)");
  d->add_option("machine", da.machine, "The machine (`rtsim list machines`)")->required();
  d->add_option("--scene", da.scene,
                "The scene the machine is built for (default: a small one it can hold)");
  d->add_option("--out", da.out_dir, "Write MACHINE.dot and MACHINE.svg into this folder");
  add_config_options(d, da.config);
  return d;
}

}  // namespace

int run_cli(int argc, char** argv) {
  CLI::App app(kDescription, "rtsim");
  app.footer(kFooter);
  app.set_version_flag("--version", std::string("rtsim ") + RTSIM_VERSION);
  app.require_subcommand(1);

  RenderArgs render;
  render.threads = functional::every_core();
  RunArgs runa;
  SweepArgs sw;
  ValidateArgs va;
  va.jobs = render.threads;
  ListArgs list;
  DiffArgs diff;
  DescribeArgs da;
  auto* r = add_render_command(app, render);
  auto* run = add_run_command(app, runa);
  auto* sweep = add_sweep_command(app, sw);
  auto* validate = add_validate_command(app, va);
  auto* l = add_list_command(app, list);
  auto* df = add_diff_command(app, diff);
  auto* d = add_describe_command(app, da);

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return code == 0 ? kExitOk : kExitBadInput;
  }

  try {
    if (r->parsed()) return run_render(render);
    if (l->parsed()) return run_list(list);
    if (df->parsed()) return run_diff(diff);
    if (d->parsed()) return run_describe(da);
    if (run->parsed()) return run_run(runa);
    if (validate->parsed()) return run_validate(va);
    if (sweep->parsed()) return run_sweep(sw);
    return kExitFailure;
  } catch (const InputError& e) {
    std::cerr << "rtsim: error: " << e.what() << "\n";
    return kExitBadInput;
  } catch (const modules::TimeOverflow& e) {
    // Outside the simulation too (a load time or readout worked out from the parameters): the
    // parameters describe a frame longer than SystemC's time, which is bad input.
    std::cerr << "rtsim: error: " << e.what()
              << ": the frame these parameters describe is longer than the simulator can count; "
                 "shorten the times, the scene or the image\n";
    return kExitBadInput;
  } catch (const std::exception& e) {
    std::cerr << "rtsim: internal error: " << e.what() << "\n";
    return kExitFailure;
  }
}

}  // namespace rtsim::app
