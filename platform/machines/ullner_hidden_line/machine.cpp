// ullner-hidden-line: Ullner's hidden-line elimination pipeline (seed 000 §3.4, L1679-L1914;
// note 000-ch3 §2.10): the scene's polygon edges pass as segments through a pipe of plane
// processors, one a boundary plane, each anti-clipping them against its plane exactly, with a
// cleanup processor after each polygon's planes turning the intersections into hidden parts,
// a string of cleanup processors at the end and a divider turning the rationals into points.
// What comes out is every edge's visible part, drawn as lines (the image, and drawing.svg).
// firmware/hiddenline/ puts the scene on the screen and does the processors' arithmetic.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <systemc>

#include "common/input_error.hpp"
#include "firmware/hiddenline/drawing.hpp"
#include "firmware/hiddenline/pipe.hpp"
#include "firmware/hiddenline/plane.hpp"
#include "firmware/hiddenline/point_check.hpp"
#include "firmware/hiddenline/screen_scene.hpp"
#include "modules/module_params.hpp"
#include "platform/machine_registry.hpp"
#include "platform/machines/machine_run.hpp"
#include "platform/machines/machine_support.hpp"
#include "platform/machines/mesh_params.hpp"
#include "platform/machines/ullner_hidden_line/hidden_line_pipe.hpp"
#include "platform/machines/ullner_hidden_line/pipe_host.hpp"

namespace rtsim::platform {

class UllnerHiddenLine final : public Machine {
 public:
  using Machine::Machine;
  void declare_params(params::ParamRegistry& registry) const override;
  FunctionalTwin make_twin(scenes::Scene& scene,
                           const params::ParamRegistry& registry) const override;
  RunResult run(scenes::Scene& scene, FunctionalTwin& twin, const params::ParamRegistry& registry,
                const RunOptions& opts) const override;
};

namespace {

using namespace ullner_hidden_line;

/// The most triangles a scene may tessellate into before it is put on the screen (the estimate,
/// against a mesh without bound): a pipe of more than kMaxPlaneProcessors planes is refused
/// after it, and this keeps the refusal quick.
constexpr double kMaxTriangles = 100000;
/// The most point-polygon tests `check.points` may ask for (about half a minute).
constexpr double kMaxCheckTests = 1e9;
/// Bins of processors the statistics give the pipe's utilisation in, first to last.
constexpr std::size_t kPipeBins = 20;

const modules::CountParam kCheckPoints(
    {.name = "check.points",
     .default_value = "0",
     .min = "0",
     .max = "1000",
     .unit = "points a segment",
     .description = "points the run samples along every segment after the frame, each tested "
                    "against every polygon by an independent 2-D inside test and depth (no "
                    "boundary plane), and compared with the pieces the pipe drew: "
                    "hidden_line.check in stats.json; 0, no check (it costs segments x points "
                    "x polygons)",
     .source = "study setting: the validation rows' check that the results are exact "
               "(seed 000 L1681)"});

/// The scene on the screen (seed 000 §3.4's input): its polygons' planes and its edges.
struct HiddenLineFrame {
  hiddenline::ScreenScene screen;
  std::vector<std::vector<hiddenline::Plane>> planes;  ///< a hiding polygon's, in order
  std::size_t plane_count = 0;
};

HiddenLineFrame load_frame(const scenes::Scene& scene, const raster::MeshSettings& mesh_settings,
                           int width, int height) {
  const double estimate = raster::estimated_triangles(scene, mesh_settings);
  if (estimate > kMaxTriangles)
    throw InputError(scene.name, 0,
                     "ullner-hidden-line: the scene makes about " +
                         std::to_string(static_cast<long long>(estimate)) +
                         " polygons, a cleanup processor and a plane processor an edge each; at "
                         "most " +
                         std::to_string(static_cast<long long>(kMaxTriangles)) +
                         " (lower mesh.* for a tessellated scene)");
  const raster::RasterMesh mesh = raster::build_raster_mesh(scene, mesh_settings);
  HiddenLineFrame f;
  f.screen = hiddenline::to_screen(
      scene, mesh, raster::ViewTransform::camera(scene.camera, width, height, mesh.bounds));
  for (const auto& poly : f.screen.polygons) {
    std::vector<hiddenline::Plane> planes = hiddenline::boundary_planes(poly);
    if (planes.empty()) continue;  // seen edge-on: it hides nothing
    f.plane_count += planes.size();
    f.planes.push_back(std::move(planes));
  }
  if (f.plane_count > HiddenLinePipe::kMaxPlaneProcessors)
    throw InputError(scene.name, 0,
                     "ullner-hidden-line: the scene's polygons have " +
                         std::to_string(f.plane_count) +
                         " boundary planes, a plane processor "
                         "each; a pipe has at most " +
                         std::to_string(HiddenLinePipe::kMaxPlaneProcessors) +
                         " (a smaller scene, or lower mesh.*)");
  return f;
}

void check_samples(int spp) {
  if (spp > 1)
    throw InputError("render.spp", 0,
                     "ullner-hidden-line draws lines, one sample a pixel (seed 000 §3.4 "
                     "computes visible segments, not pixels); use 1");
}

/// The drawing: black where a visible line passes, white paper elsewhere.
void paint(const std::vector<hiddenline::VisiblePiece>& pieces, const hiddenline::ScreenScene& s,
           functional::FrameState& frame) {
  const std::vector<std::uint8_t> ink =
      hiddenline::ink_pixels(pieces, s, frame.width(), frame.height());
  for (std::size_t i = 0; i < ink.size(); ++i)
    frame.fb().add(static_cast<std::uint32_t>(i), ink[i] ? Color(0.0) : Color(1.0));
}

}  // namespace

void UllnerHiddenLine::declare_params(params::ParamRegistry& r) const {
  // The twin reads view.* and mesh.*: it traces no rays and shades nothing.
  declare_common_params(r, {.accel = false,
                            .shells = false,
                            .polygon_kernel = false,
                            .bezier = false,
                            .ray_tree = false});
  const modules::ParamDecls machine(r, "", /*per_instance=*/false);
  declare_mesh_params(machine.affecting_image());
  machine.add(kCheckPoints);
  HiddenLinePipe::declare_params(machine);
}

FunctionalTwin UllnerHiddenLine::make_twin(scenes::Scene& scene,
                                           const params::ParamRegistry& r) const {
  auto settings = functional::read_render_settings(r);
  settings.accel = functional::AccelKind::None;
  check_samples(settings.spp);
  FunctionalTwin twin = make_functional_twin(scene, settings);
  const raster::MeshSettings mesh = read_mesh_params(r);
  const std::size_t trailing = HiddenLinePipe::trailing_cleanups(r);
  // Checked now: a scene the machine cannot hold is bad input before anything runs.
  (void)raster::estimated_triangles(scene, mesh);
  // The same anti-clipping in plain C++: every processor of the chain in turn over the whole
  // stream, then the divider (firmware/hiddenline/pipe.hpp).
  twin.render = [mesh, trailing](const scenes::Scene& s, const Tracer&,
                                 const functional::RenderOptions& opts) {
    const auto start = std::chrono::steady_clock::now();
    const int w = opts.width > 0 ? opts.width : s.camera.width;
    const int h = opts.height > 0 ? opts.height : s.camera.height;
    const HiddenLineFrame frame = load_frame(s, mesh, w, h);
    auto chain = hiddenline::build_chain(frame.planes, static_cast<int>(trailing));
    const auto pieces = hiddenline::divide(
        hiddenline::run_chain(chain, hiddenline::segment_stream(frame.screen.segments)));
    functional::FrameState state(w, h, 1, opts.aov_id, opts.aov_depth);
    paint(pieces, frame.screen, state);
    functional::RenderResult result = state.finish(
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    result.drawing_svg = hiddenline::svg_drawing(pieces, frame.screen, w, h);
    return result;
  };
  return twin;
}

RunResult UllnerHiddenLine::run(scenes::Scene& scene, FunctionalTwin& twin,
                                const params::ParamRegistry& r, const RunOptions& opts) const {
  if (opts.sample_every > 0) throw InputError("--sample", 0, "ullner-hidden-line does not sample");
  check_samples(twin.settings.spp);
  MachineRun run(name(), scene, twin, r, opts, /*rows_sampled=*/false);
  const HiddenLineFrame frame = load_frame(scene, read_mesh_params(r), run.width(), run.height());
  const std::size_t wanted = HiddenLinePipe::plane_processors(r);
  if (wanted > 0 && wanted < frame.plane_count)
    throw InputError("pipe.plane_processors", 0,
                     "ullner-hidden-line: the scene's polygons have " +
                         std::to_string(frame.plane_count) +
                         " boundary planes, a plane processor each, and the pipe has " +
                         std::to_string(wanted) + "; at least " +
                         std::to_string(frame.plane_count) + " (or 0, as many as the scene needs)");
  // -p check.points: refused before the run if the check would take too long.
  const std::size_t check_points = modules::ModuleParams(r, "").get(kCheckPoints);
  {
    const hiddenline::ScreenScene& screen = frame.screen;
    const double tests = static_cast<double>(check_points) *
                         static_cast<double>(screen.segments.size()) *
                         static_cast<double>(screen.polygons.size());
    if (tests > kMaxCheckTests)
      throw InputError("check.points", 0,
                       "ullner-hidden-line: " + std::to_string(check_points) +
                           " points on each of " + std::to_string(screen.segments.size()) +
                           " segments against " + std::to_string(screen.polygons.size()) +
                           " polygons is more than the " +
                           std::to_string(static_cast<long long>(kMaxCheckTests)) +
                           " point-polygon tests a check makes; fewer points");
  }
  PipeLayout layout{.polygons = hiddenline::build_chain(frame.planes, 0),
                    .idle_plane_processors = wanted > 0 ? wanted - frame.plane_count : 0,
                    .trailing_cleanups = HiddenLinePipe::trailing_cleanups(r)};

  // In-flight faults on the last link's intersections; the machine has no memory at rest.
  std::vector<MemoryFault> at_rest = opts.faults;
  std::vector<IntersectionFault> faults;
  for (const auto& f :
       take_faults(at_rest, [](const std::string& n) { return n == HiddenLinePipe::kFaultPoint; }))
    faults.push_back({f.word, f.xor_mask, false});
  inject_faults(name(), at_rest, {}, {HiddenLinePipe::kFaultPoint});

  const std::size_t idle = layout.idle_plane_processors;
  HiddenLinePipe pipe(HiddenLinePipe::kName, run, std::move(layout), std::move(faults));
  PipeHost host(PipeHost::kName, run, pipe, hiddenline::segment_stream(frame.screen.segments),
                frame.plane_count);
  // --latency-probe follows every segment from the host to the divider (a segment found
  // hidden whole on the way is not counted).
  modules::LatencyProbe& probe = run.probe();
  std::vector<modules::LatencyProbe::Journey> journeys;
  if (probe.enabled()) {
    probe.describe("segment",
                   "a segment, from the host handing it to its link to its arrival at the "
                   "divider at the pipe's end");
    const int host_link = probe.stage("host.link");
    const int pp = probe.stage("pipe.pp*");
    const int pp_link = probe.stage("pipe.pp*.link");
    const int cp = probe.stage("pipe.cp*");
    const int cp_link = probe.stage("pipe.cp*.link");
    for (std::size_t e = 0; e < frame.screen.segments.size(); ++e)
      journeys.push_back(probe.begin(sc_core::SC_ZERO_TIME));
    host.follow(&journeys, host_link);
    pipe.follow(&journeys, pp, pp_link, cp, cp_link);
  }
  run.simulate();
  const DividerNode& divider = pipe.divider();
  if (!divider.ended())
    throw std::logic_error("ullner-hidden-line: the stream's end did not reach the divider");
  pipe.end_journeys();
  pipe.account();
  const sc_core::sc_time end = host.frame_end();
  run.stats_over(sc_core::SC_ZERO_TIME, end);
  for (const IntersectionFault& f : pipe.faults())
    if (!f.applied)
      throw InputError("--fault intersection:" + std::to_string(f.index), 0,
                       "the last link carried fewer intersections than that to the divider "
                       "(" +
                           std::to_string(divider.received().size()) +
                           " messages in all); give a smaller index");

  // What the divider received, divided: the visible pieces, drawn.
  std::uint64_t divisions = 0;
  const auto pieces = hiddenline::divide(divider.received(), &divisions);
  paint(pieces, frame.screen, run.frame());

  // Segment latency, host to divider (L1914: "the delay necessary for a segment description to
  // pass all the way through the pipeline").
  const auto& handed = host.handed();
  double latency_sum = 0, latency_max = 0, first_latency = 0;
  std::size_t arrived = 0;
  for (const auto& [edge, at] : divider.segment_arrivals()) {
    if (edge >= handed.size()) continue;
    const double l = (at - handed[edge]).to_seconds();
    if (arrived == 0) first_latency = l;
    latency_sum += l;
    latency_max = std::max(latency_max, l);
    ++arrived;
  }
  // Utilisation along the pipe (L1914: messages created and eliminated "tend to close" each
  // other's gaps): the processors in kPipeBins runs, first to last.
  const auto& stages = pipe.stages();
  const double frame_s = end.to_seconds();
  nlohmann::ordered_json along = nlohmann::ordered_json::array();
  const std::size_t bins = std::min(kPipeBins, stages.size());
  for (std::size_t b = 0; b < bins; ++b) {
    const std::size_t lo = b * stages.size() / bins, hi = (b + 1) * stages.size() / bins;
    double link = 0, compute = 0, inputs = 0, segments = 0;
    for (std::size_t k = lo; k < hi; ++k) {
      const StageState& st = stages[k]->state();
      link += st.link_busy.to_seconds();
      compute += st.compute_busy.to_seconds();
      inputs += static_cast<double>(st.inputs);
      segments += static_cast<double>(st.segments_in);
    }
    const double n = static_cast<double>(hi - lo);
    along.push_back({{"first", lo},
                     {"last", hi - 1},
                     {"link_utilization", frame_s > 0 ? link / n / frame_s : 0.0},
                     {"compute_utilization", frame_s > 0 ? compute / n / frame_s : 0.0},
                     {"messages_mean", inputs / n},
                     {"segments_mean", segments / n}});
  }
  double visible = 0;
  for (const auto& p : pieces) visible += p.t1 - p.t0;
  const std::uint64_t word_bits = HiddenLinePipe::word_bits(r);
  const modules::Link& link = pipe.link_out();
  const auto message_s = [&](std::uint64_t bit_times) {
    return modules::times(link.bit_time(), bit_times).to_seconds();
  };

  nlohmann::ordered_json& res = run.machine_stats();
  auto& hl = res["hidden_line"];
  const hiddenline::ScreenScene& screen = frame.screen;
  hl["polygons"] = frame.planes.size();
  hl["polygons_split"] = screen.concave_split;
  hl["polygons_clipped"] = screen.clipped;
  hl["polygons_culled"] = screen.culled;
  hl["segments"] = screen.segments.size();
  hl["planes"] = frame.plane_count;
  hl["plane_processors"] = pipe.plane_processors();
  hl["idle_plane_processors"] = idle;
  hl["cleanup_processors"] = pipe.cleanup_processors();
  hl["frame_time_s"] = frame_s;
  hl["plane_load_s"] = host.planes_loaded().to_seconds();
  hl["message_time_s"] = {{"segment", message_s(bit_times(6, 0, link.lanes(), word_bits))},
                          {"intersection", message_s(bit_times(2, 3, link.lanes(), word_bits))},
                          {"plane", message_s(plane_bit_times(link.lanes(), word_bits))}};
  hl["segment_latency_s"] = {
      {"first", first_latency},
      {"mean", arrived > 0 ? latency_sum / static_cast<double>(arrived) : 0.0},
      {"max", latency_max}};
  hl["segments_out"] = arrived;
  hl["visible_pieces"] = pieces.size();
  hl["visible_share"] =
      screen.segments.empty() ? 0.0 : visible / static_cast<double>(screen.segments.size());
  hl["divisions"] = divisions;
  if (check_points > 0) {
    const hiddenline::PieceCheck c = hiddenline::check_pieces(
        screen.polygons, screen.segments, pieces, static_cast<int>(check_points));
    hl["check"] = {{"points", c.samples},
                   {"hidden", c.hidden},
                   {"missed", c.missed},
                   {"drawn_hidden", c.drawn_hidden}};
  }
  hl["along_pipe"] = std::move(along);
  for (const auto& f : pipe.faults())
    hl["faults_in_flight"].push_back({{"at", HiddenLinePipe::kFaultPoint},
                                      {"word", f.index},
                                      {"xor_mask", f.xor_mask},
                                      {"applied", f.applied}});
  using modules::StatUnit;
  run.machine_units() = {{"hidden_line.*_s", StatUnit::seconds},
                         {"hidden_line.*_s.*", StatUnit::seconds},
                         {"hidden_line.visible_share", StatUnit::fraction},
                         {"hidden_line.along_pipe.*_utilization", StatUnit::fraction},
                         {"hidden_line.*", StatUnit::count}};
  RunResult result = run.finish(modules::LatencyRecorder{}, {});
  result.image.drawing_svg = hiddenline::svg_drawing(pieces, screen, run.width(), run.height());
  return result;
}

namespace {

const RegisterMachine<UllnerHiddenLine> kRegistered(
    {.name = "ullner-hidden-line",
     .description = "Ullner's hidden-line elimination pipeline: a plane processor a polygon's "
                    "boundary plane anti-clipping the scene's edges exactly, cleanup processors "
                    "and a divider, on 500 ns bit-serial links (seed 000 §3.4)",
     .sample_scene = "builtin:ullner-cubes",
     .test_runs = {"--scene builtin:ullner-random-100",
                   "--scene builtin:ullner-cubes -p pipe.trailing_cleanups=0",
                   "--scene builtin:spd-teapot -p pp.multipliers=1"},
     .benchmark_runs = {"--scene builtin:ullner-random-1000", "--scene builtin:ullner-cubes",
                        "--scene builtin:spd-teapot"},
     .samples = false,
     .sampling_refusal = "its frame is one stream of segments through a pipe whose every "
                         "processor holds state from one message to the next; run the whole "
                         "frame"});

}  // namespace
}  // namespace rtsim::platform
