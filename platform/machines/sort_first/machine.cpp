// sort-first: Mueller's sort-first rendering architecture (seed 004 L454-L602; note 004 "Paper
// 4"): one region renderer a square screen region (Fig. 1, L503-L505), each keeping its
// primitives from frame to frame and sending on only those whose screen bounding boxes moved
// into other regions (the coherence study's setup, L560-L566), on Pixel-Planes 5's token ring
// (the study's traces came from that machine, L554) with a host and frame buffer node. A run is
// a camera path of `frames` frames, spun `camera.spin` degrees a frame about the vertical axis
// (the PLB test, L570-L572); the image is the last frame's, the scene's own view.
// firmware/sortfirst/ classifies, stores and renders; firmware/raster/ and firmware/deferred/
// scan-convert and shade.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <optional>
#include <systemc>

#include "common/input_error.hpp"
#include "firmware/sortfirst/region_store.hpp"
#include "modules/module_params.hpp"
#include "modules/ring_channel.hpp"
#include "modules/token_ring.hpp"
#include "platform/machine_registry.hpp"
#include "platform/machines/machine_run.hpp"
#include "platform/machines/machine_support.hpp"
#include "platform/machines/mesh_params.hpp"
#include "platform/machines/sort_first/frame_data.hpp"
#include "platform/machines/sort_first/frame_host.hpp"
#include "platform/machines/sort_first/interconnect.hpp"
#include "platform/machines/sort_first/mesh_channel.hpp"
#include "platform/machines/sort_first/region_renderer.hpp"

namespace rtsim::platform {

class SortFirst final : public Machine {
 public:
  using Machine::Machine;
  void declare_params(params::ParamRegistry& registry) const override;
  FunctionalTwin make_twin(scenes::Scene& scene,
                           const params::ParamRegistry& registry) const override;
  RunResult run(scenes::Scene& scene, FunctionalTwin& twin, const params::ParamRegistry& registry,
                const RunOptions& opts) const override;
};

namespace {

using namespace sort_first;

constexpr const char* kRing = "ring";

const modules::CountParam kRegions(
    {.name = "regions",
     .default_value = "4",
     .min = "1",
     .max = "32",
     .unit = "regions a side",
     .description = "the screen's square regions a side, one region renderer each (N x N)",
     .source = "seed 004 L562, L568: 4x4, 8x8 and 16x16 in the coherence study"});
const modules::CountParam kFrames(
    {.name = "frames",
     .default_value = "8",
     .min = "1",
     .max = "1000",
     .unit = "frames",
     .description = "frames of the camera path; the first redistributes the random initial "
                    "distribution and is left out of the migration figures (L562); the image is "
                    "the last frame's",
     .source = "seed 004 L570: the PLB test ran 80 frames; 8 keeps a default run short"});
const modules::RealParam kSpin({.name = "camera.spin",
                                .default_value = "4.5",
                                .min = "-360",
                                .max = "360",
                                .unit = "degrees",
                                .description = "turn of the view about its vertical axis through "
                                               "the point looked at, from one frame to the next",
                                .source = "seed 004 L572: PLB spun 4.5 degrees an iteration"});
const modules::ChoiceParam kPath(
    {.name = "camera.path",
     .default_value = "spin",
     .allowed = {"spin", "fly"},
     .description = "spin: the view turns camera.spin a frame about its vertical axis (the PLB "
                    "test); fly: sequences of camera.sequence frames closing in on the point "
                    "looked at by camera.dolly a frame while turning camera.spin, with an abrupt "
                    "reset between sequences (the Sierra path's shape)",
     .source = "seed 004 L570-L572 (PLB), L588-L589 (Sierra: zooms, rotations and "
               "translations with an abrupt reset between each sequence)"});
const modules::RealParam kDolly({.name = "camera.dolly",
                                 .default_value = "0.02",
                                 .min = "-0.5",
                                 .max = "0.5",
                                 .unit = "of the distance",
                                 .description = "camera.path = fly: how much nearer the point "
                                                "looked at the eye comes a frame",
                                 .source = "study setting: a zoom of 2% a frame"});
const modules::CountParam kSequence({.name = "camera.sequence",
                                     .default_value = "20",
                                     .min = "1",
                                     .max = "1000",
                                     .unit = "frames",
                                     .description = "camera.path = fly: frames between abrupt "
                                                    "resets",
                                     .source = "study setting: the Sierra path's 234 frames in "
                                               "a few sequences (L588)"});
const modules::IntParam kSeed(
    {.name = "distribution.seed",
     .default_value = "1995",
     .min = "0",
     .max = "2147483647",
     .description = "seed of the random initial distribution of primitives over the renderers",
     .source = "seed 004 L562 (random initial distribution); the seed is this model's"});

const modules::ChoiceParam kSort(
    {.name = "sort",
     .default_value = "first",
     .allowed = {"first", "middle", "last"},
     .description = "where primitives are sorted to regions: first (they migrate and stay, "
                    "L503), middle (each renderer keeps its share and sends every primitive to "
                    "its regions every frame, L509-L511), last (each renders its share over the "
                    "whole screen and the frame buffer depth-composites the partial images, L515)",
     .source = "seed 004 L483-L548: the three classes compared on the same renderers and frames"});
const modules::ChoiceParam kInterconnect(
    {.name = "interconnect",
     .default_value = "ring",
     .allowed = {"ring", "mesh"},
     .description = "ring: every node a stop on one token ring; mesh: the renderers on a 2-D "
                    "mesh of links (store-and-forward, dimension order), the host on its own bus",
     .source = "assumption: the seed gives no network (L503); the study's traces came from "
               "Pixel-Planes 5 (L554), whose ring is the default"});

/// The most renderer-frames a run simulates (each classifies everything it holds).
constexpr double kMaxRendererFrames = 1'000'000;
/// Sort-last's partial images in flight at once, at most (every renderer's whole screen of
/// 34-byte records, 278 KB a tile): a bound on memory.
constexpr double kMaxPartialBytes = 1024.0 * 1024.0 * 1024.0;

sortfirst::Sort sort_of(const std::string& s) {
  return s == "middle" ? sortfirst::Sort::Middle
         : s == "last" ? sortfirst::Sort::Last
                       : sortfirst::Sort::First;
}

void check_samples(int spp) {
  if (spp > 1)
    throw InputError("render.spp", 0,
                     "sort-first's renderers take one sample a pixel (the seed's study does not "
                     "rasterize, L568); use 1");
}

}  // namespace

void SortFirst::declare_params(params::ParamRegistry& r) const {
  declare_common_params(r, {.accel = false,
                            .shells = false,
                            .polygon_kernel = false,
                            .bezier = false,
                            .ray_tree = false});
  const modules::ParamDecls machine(r, "", /*per_instance=*/false);
  declare_mesh_params(machine.affecting_image());
  machine.add(kRegions);
  machine.add(kFrames);
  machine.add(kSpin);
  machine.add(kPath);
  machine.add(kDolly);
  machine.add(kSequence);
  machine.add(kSeed);
  machine.add(kSort);
  machine.add(kInterconnect);
  RegionRenderer::declare_params(machine.sub(RegionRenderer::kClass));
  FrameHost::declare_params(machine.sub(FrameHost::kName));
  MeshChannel::declare_params(machine);
  modules::TokenRing::declare_params(
      machine.sub(kRing),
      {.bandwidth = "5 Gbit/s",
       .bandwidth_source = "seed 004 L284 (Pixel-Planes 5's ring, the machine the study's traces "
                           "came from, L554)",
       .hop_latency = "50 ns",
       .max_packet_bytes = "1024",
       .header_bytes = "8",
       .service = "exhaustive",
       .source = "assumption: pxpl5-raytrace's ring (the seed gives only the bandwidth)"});
}

FunctionalTwin SortFirst::make_twin(scenes::Scene& scene, const params::ParamRegistry& r) const {
  auto settings = functional::read_render_settings(r);
  settings.accel = functional::AccelKind::None;
  check_samples(settings.spp);
  FunctionalTwin twin = make_functional_twin(scene, settings);
  const raster::MeshSettings mesh = read_mesh_params(r);
  // Checked now: a scene the machine cannot hold is bad input before anything runs.
  {
    FrameData probe;
    make_frame_data(probe, scene, mesh, settings.shade, 1, 1, 1);
  }
  // The twin renders the frame as one region: the partition changes no pixel (each region is
  // given every primitive whose box covers it; tests/sort_first_test.cpp), so the image does
  // not depend on `regions`.
  twin.render = [mesh](const scenes::Scene& s, const Tracer&,
                       const functional::RenderOptions& opts) {
    const auto start = std::chrono::steady_clock::now();
    const int w = opts.width > 0 ? opts.width : s.camera.width;
    const int h = opts.height > 0 ? opts.height : s.camera.height;
    FrameData data;
    make_frame_data(data, s, mesh, opts.shade, 1, w, h);
    functional::FrameState state(w, h, 1, opts.aov_id, opts.aov_depth);
    render_frame(data, frame_view(s, data.mesh, w, h, 0, 1, CameraPath{}), state);
    return state.finish(
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  };
  return twin;
}

RunResult SortFirst::run(scenes::Scene& scene, FunctionalTwin& twin, const params::ParamRegistry& r,
                         const RunOptions& opts) const {
  if (opts.sample_every > 0) throw InputError("--sample", 0, "sort-first does not sample");
  check_samples(twin.settings.spp);
  MachineRun run(name(), scene, twin, r, opts, /*rows_sampled=*/false);
  const modules::ModuleParams top(r, "");
  const int side = static_cast<int>(top.get(kRegions));
  const int regions = side * side;
  const int frames = static_cast<int>(top.get(kFrames));
  const CameraPath path{.fly = top.get(kPath) == "fly",
                        .spin = top.get(kSpin),
                        .dolly = top.get(kDolly),
                        .sequence = static_cast<int>(top.get(kSequence))};
  // A fly path's eye stays on its side of the point it looks at: at the start of the longest
  // sequence it is 1 + dolly (frames before its end) times as far as the scene's eye.
  const int longest = std::min(path.sequence, frames) - 1;
  if (path.fly && 1.0 + path.dolly * longest < 0.01) {
    char why[200];
    std::snprintf(why, sizeof why,
                  "sort-first: camera.dolly %g over a sequence of %d frames brings the eye onto "
                  "(or past) the point it looks at; a dolly above %.4g, or shorter sequences",
                  path.dolly, longest + 1, -0.99 / longest);
    throw InputError("camera.dolly", 0, why);
  }
  const sortfirst::Sort sort = sort_of(top.get(kSort));
  const bool mesh = top.get(kInterconnect) == "mesh";
  FrameData data;
  make_frame_data(data, scene, read_mesh_params(r), twin.settings.shade, side, run.width(),
                  run.height());
  if (static_cast<double>(regions) * frames > kMaxRendererFrames)
    throw InputError("frames", 0,
                     "sort-first: " + std::to_string(regions) + " renderers x " +
                         std::to_string(frames) + " frames is more than the " +
                         std::to_string(static_cast<long long>(kMaxRendererFrames)) +
                         " renderer-frames a run simulates; fewer frames or regions");
  if (sort == sortfirst::Sort::Last) {
    const double tiles = raster::RegionGrid{run.width(), run.height()}.count();
    const double bytes = regions * tiles * raster::kRegionPixels * raster::kAppearanceBytes;
    if (bytes > kMaxPartialBytes)
      throw InputError(
          "sort", 0,
          "sort-first: sort = last holds every renderer's partial image of the "
          "whole screen at once, " +
              std::to_string(static_cast<long long>(bytes / (1024 * 1024))) +
              " MiB here, more than the " +
              std::to_string(static_cast<long long>(kMaxPartialBytes / (1024 * 1024))) +
              " MiB allowed; fewer regions or a smaller image");
  }
  std::vector<raster::ViewTransform> views;
  for (int f = 0; f < frames; ++f)
    views.push_back(frame_view(scene, data.mesh, run.width(), run.height(), f, frames, path));
  const std::vector<int> initial = sortfirst::random_distribution(
      data.mesh.triangles.size(), regions, static_cast<std::uint64_t>(top.get(kSeed)));
  // Each renderer's share of it, the primitives' database indices.
  std::vector<std::vector<std::uint32_t>> shares(static_cast<std::size_t>(regions));
  for (std::uint32_t i = 0; i < initial.size(); ++i)
    shares[static_cast<std::size_t>(initial[i])].push_back(i);

  // In-flight faults on migrating records; the machine has no memory at rest to corrupt.
  std::vector<MemoryFault> at_rest = opts.faults;
  MigrationFaults faults;
  for (const auto& f :
       take_faults(at_rest, [](const std::string& n) { return n == MigrationFaults::kFaultPoint; }))
    faults.faults.push_back({f.word, f.xor_mask, false});
  inject_faults(name(), at_rest, {}, {MigrationFaults::kFaultPoint});

  // --latency-probe follows each region's frame from its view to its pixels.
  modules::LatencyProbe& probe = run.probe();
  probe.describe("region-frame",
                 "a region's frame, from the host handing its view to the interconnect to the "
                 "host taking the region's finished pixels");
  const ProbeStages stages{.net = probe.stage(mesh ? "mesh" : kRing),
                           .renderer_in = probe.stage("renderer*.inbox"),
                           .renderer = probe.stage("renderer*"),
                           .host_in = probe.stage("host.inbox")};
  // Both interconnects' parameters are read (a bad value is an error whichever is chosen); the
  // one chosen is built and carries the messages.
  const modules::TokenRing::Config ring_config =
      modules::TokenRing::read_config(modules::ModuleParams(r, kRing));
  MeshChannel::check_params(r);
  std::optional<modules::TokenRing> ring;
  std::optional<modules::RingChannel<Message>> ring_channel;
  std::optional<MeshChannel> mesh_channel;
  std::optional<Interconnect> net;
  if (mesh) {
    mesh_channel.emplace("mesh", side, r);
    net.emplace(*mesh_channel);
  } else {
    ring.emplace(kRing, ring_config, static_cast<std::size_t>(regions + 1), kTrafficClasses);
    ring->trace_to(run.trace());
    ring_channel.emplace("ring_channel", *ring);
    net.emplace(*ring_channel);
  }
  std::vector<std::unique_ptr<RegionRenderer>> renderers;
  for (int k = 0; k < regions; ++k)
    renderers.push_back(std::make_unique<RegionRenderer>(
        (std::string(RegionRenderer::kClass) + std::to_string(k)).c_str(), run, *net, data, sort, k,
        regions, frames, shares[static_cast<std::size_t>(k)], faults, stages));
  FrameHost host(FrameHost::kName, run, *net, data, sort, regions, regions, views, stages);
  run.simulate();

  if (host.ended().size() != static_cast<std::size_t>(frames))
    throw std::runtime_error("sort-first: the frame buffer never had every region");
  for (const auto& f : faults.faults)
    if (!f.applied)
      throw InputError("--fault migration:" + std::to_string(f.word), 0,
                       "the run migrated " + std::to_string(faults.words_sent) +
                           " words of records (" + std::to_string(sortfirst::kRecordWords) +
                           " a record); give a word below that");
  const sc_core::sc_time end = host.ended().back();
  run.stats_over(sc_core::SC_ZERO_TIME, end);

  // Per frame: records migrated (as the renderers counted them sending), their share of the
  // primitives, bytes on the interconnect, the renderers' load, the frame's time.
  const double primitives = static_cast<double>(data.mesh.triangles.size());
  nlohmann::ordered_json per_frame = nlohmann::ordered_json::array();
  std::vector<double> percents;
  for (int f = 0; f < frames; ++f) {
    const auto fi = static_cast<std::size_t>(f);
    std::uint64_t sent = 0;
    double busy_max = 0, busy_sum = 0;
    for (const auto& k : renderers) {
      sent += k->sent_by_frame()[fi];
      const double b = k->busy_by_frame()[fi].to_seconds();
      busy_max = std::max(busy_max, b);
      busy_sum += b;
    }
    const double percent = primitives > 0 ? 100.0 * static_cast<double>(sent) / primitives : 0.0;
    if (f > 0) percents.push_back(percent);
    const double busy_mean = busy_sum / regions;
    // Bytes handed to the interconnect this frame, by kind (every node's).
    FrameBytes bytes{};
    const auto add_bytes = [&](const InterconnectNode& n) {
      if (const auto it = n.bytes_by_frame().find(f); it != n.bytes_by_frame().end())
        for (std::size_t c = 0; c < kMessageKinds; ++c) bytes[c] += it->second[c];
    };
    for (const auto& k : renderers) add_bytes(*k);
    add_bytes(host);
    nlohmann::ordered_json by_kind = nlohmann::ordered_json::object();
    std::uint64_t total = 0;
    for (std::size_t c = 0; c < kMessageKinds; ++c) {
      by_kind[kTrafficClasses[c]] = bytes[c];
      total += bytes[c];
    }
    per_frame.push_back({{"frame", f},
                         {"records_migrated", sent},
                         {"migrated_percent", percent},
                         {"bytes", std::move(by_kind)},
                         {"total_bytes", total},
                         {"renderer_busy_max_s", busy_max},
                         {"renderer_busy_mean_s", busy_mean},
                         {"load_imbalance", busy_mean > 0 ? busy_max / busy_mean : 0.0},
                         {"time_s", (host.ended()[fi] - host.began()[fi]).to_seconds()}});
  }
  // The study's summary over the frames after the first (L562, L568): mean, high, standard
  // deviation, 95th percentile.
  nlohmann::ordered_json summary = nlohmann::ordered_json::object();
  if (!percents.empty()) {
    double sum = 0;
    for (const double p : percents) sum += p;
    const double mean = sum / static_cast<double>(percents.size());
    double var = 0;
    for (const double p : percents) var += (p - mean) * (p - mean);
    std::vector<double> sorted = percents;
    std::sort(sorted.begin(), sorted.end());
    // The 95th percentile: the smallest value at least 95% of the frames do not exceed.
    const std::size_t at =
        static_cast<std::size_t>(std::ceil(0.95 * static_cast<double>(sorted.size()))) - 1;
    summary = {{"frames", percents.size()},
               {"mean", mean},
               {"high", sorted.back()},
               {"std_dev", std::sqrt(var / static_cast<double>(percents.size()))},
               {"p95", sorted[std::min(at, sorted.size() - 1)]}};
  }
  nlohmann::ordered_json& res = run.machine_stats();
  auto& sf = res["sort_first"];
  sf["sort"] = top.get(kSort);
  sf["interconnect"] = top.get(kInterconnect);
  sf["regions"] = regions;
  sf["region_grid"] = std::to_string(side) + "x" + std::to_string(side);
  sf["frames"] = frames;
  sf["primitives"] = data.mesh.triangles.size();
  sf["migrated_percent"] = std::move(summary);
  sf["per_frame"] = std::move(per_frame);
  for (const auto& f : faults.faults)
    sf["faults_in_flight"].push_back({{"at", MigrationFaults::kFaultPoint},
                                      {"word", f.word},
                                      {"xor_mask", f.xor_mask},
                                      {"applied", f.applied}});
  using modules::StatUnit;
  run.machine_units() = {{"sort_first.per_frame.*_s", StatUnit::seconds},
                         {"sort_first.per_frame.bytes.*", StatUnit::bytes},
                         {"sort_first.per_frame.total_bytes", StatUnit::bytes},
                         {"sort_first.migrated_percent.frames", StatUnit::count},
                         {"sort_first.migrated_percent.*", StatUnit::ratio},
                         {"sort_first.per_frame.migrated_percent", StatUnit::ratio},
                         {"sort_first.per_frame.load_imbalance", StatUnit::ratio},
                         {"sort_first.*", StatUnit::count}};
  return run.finish(modules::LatencyRecorder{}, {});
}

namespace {

const RegisterMachine<SortFirst> kRegistered(
    {.name = "sort-first",
     .description = "Mueller's sort-first architecture: a region renderer a square screen "
                    "region keeping its primitives from frame to frame, migrating those that "
                    "cross regions, on a token ring with a host and frame buffer (seed 004, "
                    "Mueller 1995)",
     .sample_scene = "builtin:spd-teapot",
     .test_runs = {"--scene builtin:spd-teapot", "--scene builtin:default -p regions=2 -p frames=3",
                   "--scene builtin:ullner-cubes -p regions=8 -p frames=2 -p camera.spin=30"},
     .benchmark_runs = {"--scene builtin:spd-teapot", "--scene builtin:ullner-cubes",
                        "--scene builtin:bowling"},
     .report_plots = {{.object = "sort_first",
                       .key = "per_frame",
                       .script = "sort_first_frames.py",
                       .title = "Sort-first's frames",
                       .caption = "The primitives migrated in each frame (the first, the random "
                                  "distribution's, hollow), the bytes each frame handed to the "
                                  "interconnect by kind, and each frame's time and load "
                                  "imbalance (stats.json sort_first.per_frame; "
                                  "analysis/sort_first_frames.py)"}},
     .samples = false,
     .sampling_refusal = "its frames are a camera path whose every frame redistributes what the "
                         "renderers hold; run the whole path"});

}  // namespace
}  // namespace rtsim::platform
