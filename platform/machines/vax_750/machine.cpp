// vax-750: the sequential baseline. One DEC VAX-11/750 with floating-point unit runs the whole
// ray tracer, with Gaudet's measured costs (seed 001 L310-L326): T_i = 429 us per ray/object
// intersection test and T_s = 710 us per ray spawned. It tests every object for every ray
// (brute force), so a frame takes T_t = R_t (T_s + T_i O) (seed 001 L326): the reference for
// "N times faster than the VAX".
#include <chrono>
#include <systemc>

#include "firmware/shading/camera.hpp"
#include "firmware/tasks/ray_tree.hpp"
#include "firmware/tasks/shade_task.hpp"
#include "firmware/tasks/vision_ray_task.hpp"
#include "modules/latency_probe.hpp"
#include "modules/module_params.hpp"
#include "modules/processor.hpp"
#include "modules/sim_time.hpp"
#include "modules/statistics.hpp"
#include "platform/functional/frame_state.hpp"
#include "platform/functional/scene_tracer.hpp"
#include "platform/machine_registry.hpp"
#include "platform/machines/machine_run.hpp"
#include "platform/machines/machine_support.hpp"
#include "platform/machines/machine_trace.hpp"

namespace rtsim::platform {

class Vax750 final : public Machine {
 public:
  using Machine::Machine;
  void declare_params(params::ParamRegistry& registry) const override;
  FunctionalTwin make_twin(scenes::Scene& scene,
                           const params::ParamRegistry& registry) const override;
  RunResult run(scenes::Scene& scene, FunctionalTwin& twin, const params::ParamRegistry& registry,
                const RunOptions& opts) const override;
};
namespace {

using modules::from_ps;
using modules::plus;
using modules::times;
using shading::TracedRay;

// The VAX's parameters (vax.*), each named once.
const modules::TimeParam kIntersectionTime(
    {.name = "intersection_time",
     .default_value = "429 us",
     .description = "T_i: average time of one ray/object intersection calculation on the "
                    "VAX-11/750 with FPU",
     .source = "seed 001 L317"});
const modules::TimeParam kRayTime(
    {.name = "ray_time",
     .default_value = "710 us",
     .description = "T_s: average time to spawn (and shade) one ray on the VAX-11/750",
     .source = "seed 001 L318"});
const modules::ChoiceParam kSearch(
    {.name = "search",
     .default_value = "brute-force",
     .allowed = {"brute-force", "shells"},
     .description = "brute-force: every ray pays T_i for every object (the cost model of seed "
                    "001 L320-L326); shells: the sequential C renderer with Gaudet's box-shell "
                    "hierarchy, paying T_i per primitive tested and vax.box_test_time per shell "
                    "box tested (the baseline of the PERT speed-ups, L964)",
     .source = "seed 001 L320-L326, L964",
     .affects_image = true});
const modules::TimeParam kBoxTestTime(
    {.name = "box_test_time",
     .default_value = "429 us",
     .description = "T_b: time of one ray/shell box test on the VAX-11/750 (vax.search = shells)",
     .source = "assumption: the thesis measured only T_i, the average intersection calculation "
               "(L317); a slab test costs about as many floating-point operations as a sphere "
               "test, so T_b = T_i"});
/// The VAX host's name, and its parameters' path.
constexpr const char* kVax = "vax";

/// The VAX running the whole ray tracer in one process: each ray costs T_s to spawn and shade
/// plus T_i for each object of the scene (brute force).
class VaxHost : public modules::Processor {
 public:
  /// Its parameters under `vax`: T_i, T_s, the search it runs and T_b.
  static void declare_params(const modules::ParamDecls& vax) {
    for (const auto* p : {&kIntersectionTime, &kRayTime, &kBoxTestTime}) vax.add(*p);
    vax.add(kSearch);
  }
  /// Whether the run's VAX searches with Gaudet's shells (else brute force).
  static bool shells(const params::ParamRegistry& registry) {
    return modules::ModuleParams(registry, kVax).get(kSearch) == "shells";
  }

  SC_HAS_PROCESS(VaxHost);
  /// The run's context; its parameters under its name.
  VaxHost(sc_core::sc_module_name name, MachineRun& run, std::uint64_t objects)
      : modules::Processor(name, run.trace()),
        scene_(run.scene()),
        tracer_(*run.twin().tracer),
        frame_(run.frame()),
        settings_(run.twin().settings),
        params_(run.registry(), this->name()),
        ray_time_(params_.get(kRayTime)),
        test_time_(params_.get(kIntersectionTime)),
        box_time_(params_.get(kBoxTestTime)),
        brute_force_(!shells(run.registry())),
        objects_(objects),
        opts_(run.options()),
        probe_(run.probe()),
        probe_vax_(probe_.stage(this->name())) {
    SC_THREAD(run);
  }

  sc_core::sc_time frame_time() const { return frame_time_; }
  sc_core::sc_time busy() const { return accounts().busy; }
  const modules::LatencyRecorder& latency() const { return latency_; }

 private:
  void run() {
    shading::PinholeCamera camera(scene_.camera, frame_.width(), frame_.height());
    tasks::VisionRayTask vision(camera, frame_.width(), frame_.height(), frame_.spp(),
                                frame_.detailed_rows());
    tasks::ShadeTask shade(scene_, settings_.shade);
    std::vector<TracedRay> stack, spawned;
    std::uint64_t tests_seen = 0, boxes_seen = 0;
    while (!vision.done()) {
      int sample = 0;
      bool first = true;
      tasks::trace_ray_tree(
          vision.next(sample), tracer_, shade, frame_.fb(), frame_.counters(), stack, spawned,
          [&](const TracedRay& r, bool found, const Hit& hit) {
            if (first && sample == 0) frame_.record_primary(r.pixel, found, hit);
            first = false;
            // Brute force: T_s + O T_i for this ray (seed 001 L326).
            // Shells: T_s + T_i per primitive test + T_b per box test.
            const auto& c = frame_.counters();
            const sc_core::sc_time cost =
                brute_force_
                    ? plus(ray_time_, times(test_time_, objects_))
                    : plus(plus(ray_time_, times(test_time_, c.intersection_tests - tests_seen)),
                           times(box_time_, c.box_tests - boxes_seen));
            tests_seen = c.intersection_tests;
            boxes_seen = c.box_tests;
            // The whole of a ray's latency is the VAX working on it: one process, no queue.
            const auto journey = probe_.begin(clock_.now());
            probe_.add(journey, probe_vax_, modules::LatencyPart::kService, cost);
            compute_for(cost, "ray", {{"pixel", r.pixel}, {"kind", static_cast<int>(r.kind)}});
            latency_.add(cost);
            probe_.end(journey, clock_.now());
            ++rays_;
            if (opts_.progress && (rays_.value() & 1023) == 0) {
              const auto rays = static_cast<long>(rays_.value());
              opts_.progress(rays, rays);
            }
          });
    }
    frame_time_ = clock_.now();
    clock_.sync();
  }

  const scenes::Scene& scene_;
  const Tracer& tracer_;
  functional::FrameState& frame_;
  const functional::RenderSettings& settings_;
  modules::ModuleParams params_;
  sc_core::sc_time ray_time_, test_time_, box_time_;
  bool brute_force_;
  std::uint64_t objects_;
  const RunOptions& opts_;
  modules::LatencyProbe& probe_;
  int probe_vax_;
  sc_core::sc_time frame_time_ = sc_core::SC_ZERO_TIME;
  modules::LatencyRecorder latency_;
  modules::Counter rays_{*this, "rays", "rays traced"};
};

}  // namespace

void Vax750::declare_params(params::ParamRegistry& r) const {
  // The VAX runs the ordinary software ray tracer: every render parameter is read.
  declare_common_params(r, {});
  // The VAX host, its only module, declares its own.
  VaxHost::declare_params(modules::ParamDecls(r, kVax));
}

FunctionalTwin Vax750::make_twin(scenes::Scene& scene, const params::ParamRegistry& r) const {
  // The VAX runs the ordinary software ray tracer: the functional renderer's own geometry.
  auto settings = functional::read_render_settings(r);
  // With shells, the VAX runs Gaudet's own search; brute force charges every object whatever
  // structure finds the answer (the image is the same).
  if (VaxHost::shells(r)) settings.accel = functional::AccelKind::Shells;
  return make_functional_twin(scene, settings);
}

RunResult Vax750::run(scenes::Scene& scene, FunctionalTwin& twin, const params::ParamRegistry& r,
                      const RunOptions& opts) const {
  MachineRun run(name(), scene, twin, r, opts);
  functional::FrameState& frame = run.frame();
  const std::uint64_t objects = scene.primitives.size();
  VaxHost host(kVax, run, objects);
  inject_faults(name(), opts.faults, {});  // its answers come from no memory words
  run.simulate();

  run.stats_over(sc_core::SC_ZERO_TIME, host.frame_time());
  nlohmann::ordered_json& res = run.machine_stats();
  // Brute force on the VAX: every ray is tested against every object (seed 001 L324).
  const bool brute = !VaxHost::shells(r);
  const modules::ModuleParams vax(r, kVax);
  if (brute) res["intersection_tests"] = frame.counters().total_rays() * objects;
  res["vax"] = {
      {"objects", objects},
      {"intersection_time_s", vax.get(kIntersectionTime).to_seconds()},
      {"ray_time_s", vax.get(kRayTime).to_seconds()},
      {"search", vax.get(kSearch)},
      {"intersection_tests_charged",
       brute ? static_cast<double>(frame.counters().total_rays()) * static_cast<double>(objects)
             : static_cast<double>(frame.counters().intersection_tests)},
      {"box_tests_charged", brute ? 0.0 : static_cast<double>(frame.counters().box_tests)}};
  using modules::StatUnit;
  run.machine_units() = {{"intersection_tests", StatUnit::count},
                         {"vax.*_s", StatUnit::seconds},
                         {"vax.*", StatUnit::count}};
  return run.finish(host.latency(), {});
}

namespace {

const RegisterMachine<Vax750> kRegistered(
    {.name = "vax-750",
     .description = "DEC VAX-11/750 + FPU running the sequential ray tracer: Gaudet's baseline "
                    "(429 us per intersection, 710 us per ray; seed 001 L317-L318)",
     .sample_scene = "builtin:npp-412",
     .test_runs = {"--scene builtin:npp-412", "--scene builtin:default -p vax.search=shells"},
     .benchmark_runs = {"--scene builtin:default", "--scene builtin:ullner-cubes",
                        "--scene builtin:npp-412"}});

}  // namespace
}  // namespace rtsim::platform
