// kit-minimal: the smallest machine the kit makes, and the example of docs/adding-a-machine.md.
// A host processor runs the ray tracer (firmware: the vision rays, the ray tree, shading) and
// sends each finished sample's pixel word over a link into the frame buffer's queue; the frame
// buffer takes the words one at a time and adds them into the image. The image is what the
// words carry, so a slower link or frame buffer changes the frame time, never the picture.
//
// It lives in the tests, linked into `rtsim-kit` (tests/CMakeLists.txt): the generic tests run
// every machine that program registers, this one included, with no edit anywhere. Its times
// are made up (it models no seed), so its parameters cite no seed but say so.
#include <array>
#include <cstdint>
#include <vector>

#include "firmware/shading/camera.hpp"
#include "firmware/shading/pixel_accumulator.hpp"
#include "firmware/tasks/ray_tree.hpp"
#include "firmware/tasks/shade_task.hpp"
#include "firmware/tasks/vision_ray_task.hpp"
#include "modules/link.hpp"
#include "modules/message_channel.hpp"
#include "modules/module_params.hpp"
#include "modules/processor.hpp"
#include "modules/sim_time.hpp"
#include "platform/machine_registry.hpp"
#include "platform/machines/machine_run.hpp"
#include "platform/machines/machine_support.hpp"

namespace rtsim::platform {
namespace {

using modules::plus;
using modules::times;

/// A sample's colour on its way to the frame buffer: the pixel and its fixed-point sums.
struct PixelWord {
  std::uint32_t pixel = 0;
  std::array<std::int64_t, 3> sums{};
  static constexpr std::uint64_t kBits = 32 + 3 * 64;
};

/// Takes pixel words from its queue and adds them into the image, `write_time` each.
class FrameBuffer : public modules::Processor {
  // Its parameters, each named once: declared by declare_params, read by the constructor.
  static inline const modules::TimeParam kWriteTime{
      {.name = "write_time",
       .default_value = "1 us",
       .description = "time to add one pixel word into the image",
       .source = "assumption: the example machine models no seed"}};
  static inline const modules::CountParam kQueueDepth{
      {.name = "queue_depth",
       .default_value = "4",
       .min = "1",
       .max = "1048576",
       .unit = "words",
       .description = "pixel words its input queue holds",
       .source = "assumption: the example machine models no seed"}};

 public:
  static void declare_params(const modules::ParamDecls& fb) {
    fb.add(kWriteTime);
    fb.add(kQueueDepth);
  }

  SC_HAS_PROCESS(FrameBuffer);
  /// Its parameters from the run's registry, under its name; it writes the run's frame.
  FrameBuffer(sc_core::sc_module_name name, MachineRun& run)
      : modules::Processor(name, run.trace()),
        params_(run.registry(), this->name()),
        in("in", params_.get(kQueueDepth)),
        frame_(run.frame()),
        write_time_(params_.get(kWriteTime)) {
    SC_THREAD(run);
  }

  sc_core::sc_time last_write() const { return last_write_; }

 private:
  modules::ModuleParams params_;  // first: the queue's depth is read from it

 public:
  modules::MessageQueue<PixelWord> in;  ///< the pixel words from the host's link

 private:
  void run() {
    for (;;) {
      const sc_core::sc_time since = clock_.now();
      modules::wait_for_item(in.fifo, clock_);
      sc_core::sc_time taken;
      const PixelWord w = in.fifo.get(clock_.now(), taken);
      clock_.catch_up(taken);
      waited_since(since, Wait::kWork);
      compute_for(write_time_, "write", {{"pixel", w.pixel}});
      frame_.fb().add_raw(w.pixel, w.sums);
      ++words_;
      last_write_ = clock_.now();
    }
  }

  functional::FrameState& frame_;
  sc_core::sc_time write_time_;
  sc_core::sc_time last_write_ = sc_core::SC_ZERO_TIME;
  modules::Counter words_{*this, "words", "pixel words written"};
};

/// Traces every ray (T_ray + T_test per intersection test) into its own accumulator and sends
/// each finished sample's pixel word to the frame buffer over its link.
class Host : public modules::Processor {
  static inline const modules::TimeParam kRayTime{
      {.name = "ray_time",
       .default_value = "20 us",
       .description = "time to spawn and shade one ray",
       .source = "assumption: the example machine models no seed"}};
  static inline const modules::TimeParam kTestTime{
      {.name = "test_time",
       .default_value = "2 us",
       .description = "time of one ray/primitive intersection test",
       .source = "assumption: the example machine models no seed"}};

 public:
  static void declare_params(const modules::ParamDecls& host) {
    host.add(kRayTime);
    host.add(kTestTime);
    modules::Link::declare_params(host.sub("link"),
                                  {.latency = "100 ns",
                                   .lanes = "8",
                                   .bit_rate = "10 Mbit/s",
                                   .source = "assumption: the example machine models no seed"});
  }

  tlm_utils::simple_initiator_socket<Host> out;

  SC_HAS_PROCESS(Host);
  /// `queue`: the frame buffer's, which it waits on for room.
  Host(sc_core::sc_module_name name, MachineRun& run, const modules::TimedFifo<PixelWord>& queue)
      : modules::Processor(name, run.trace()),
        out("out"),
        params_(run.registry(), this->name()),
        ray_time_(params_.get(kRayTime)),
        test_time_(params_.get(kTestTime)),
        link(params_.sub("link")),
        scene_(run.scene()),
        twin_(run.twin()),
        queue_(queue),
        frame_(run.frame()),
        opts_(run.options()),
        probe_(run.probe()),
        probe_host_(run.probe().stage(this->name())),
        probe_link_(run.probe().stage(link.name())) {
    SC_THREAD(run_frame);
  }

  const modules::LatencyRecorder& latency() const { return latency_; }

 private:
  void run_frame() {
    shading::PinholeCamera camera(scene_.camera, frame_.width(), frame_.height());
    tasks::VisionRayTask vision(camera, frame_.width(), frame_.height(), frame_.spp(),
                                frame_.detailed_rows());
    tasks::ShadeTask shade(scene_, twin_.settings.shade);
    shading::PixelAccumulator own(frame_.width(), frame_.height());
    std::vector<shading::TracedRay> stack, spawned;
    std::uint64_t tests_seen = 0;
    long samples = 0;
    while (!vision.done()) {
      int sample = 0;
      const shading::TracedRay primary = vision.next(sample);
      const sc_core::sc_time begun = clock_.now();
      const auto journey = probe_.begin(begun);
      bool first = true;
      tasks::trace_ray_tree(primary, *twin_.tracer, shade, own, frame_.counters(), stack, spawned,
                            [&](const shading::TracedRay& r, bool found, const Hit& hit) {
                              if (first && sample == 0) frame_.record_primary(r.pixel, found, hit);
                              first = false;
                              const std::uint64_t tests = frame_.counters().intersection_tests;
                              compute_for(plus(ray_time_, times(test_time_, tests - tests_seen)),
                                          "ray", {{"pixel", r.pixel}});
                              tests_seen = tests;
                            });
      probe_.add(journey, probe_host_, modules::LatencyPart::kService, clock_.now() - begun);
      // The sample's word leaves once the queue has room for it; the link may hold it up.
      PixelWord w{primary.pixel, own.raw(primary.pixel)};
      own.clear(primary.pixel);
      wait_for_room(queue_);
      const sc_core::sc_time arrived = link.transfer(PixelWord::kBits, clock_.now());
      probe_.add(journey, probe_link_, modules::LatencyPart::kTransfer, arrived - clock_.now());
      modules::send_message(out, w, arrived, PixelWord::kBits);
      latency_.add(arrived - begun);
      probe_.end(journey, arrived);
      if (opts_.progress && (++samples & 1023) == 0) opts_.progress(samples, samples);
    }
    clock_.sync();
  }

  modules::ModuleParams params_;
  sc_core::sc_time ray_time_, test_time_;

 public:
  modules::Link link;  ///< to the frame buffer's queue

 private:
  const scenes::Scene& scene_;
  const FunctionalTwin& twin_;
  const modules::TimedFifo<PixelWord>& queue_;
  functional::FrameState& frame_;
  const RunOptions& opts_;
  modules::LatencyProbe& probe_;
  int probe_host_, probe_link_;
  modules::LatencyRecorder latency_;
};

class KitMinimal final : public Machine {
 public:
  using Machine::Machine;

  void declare_params(params::ParamRegistry& r) const override {
    declare_common_params(r, {});  // its host runs the ordinary ray tracer
    Host::declare_params(modules::ParamDecls(r, "host"));
    FrameBuffer::declare_params(modules::ParamDecls(r, "frame_buffer"));
  }

  FunctionalTwin make_twin(scenes::Scene& scene, const params::ParamRegistry& r) const override {
    return make_functional_twin(scene, functional::read_render_settings(r));
  }

  RunResult run(scenes::Scene& scene, FunctionalTwin& twin, const params::ParamRegistry& r,
                const RunOptions& opts) const override {
    MachineRun run(name(), scene, twin, r, opts);
    // Each module takes the run (its parameters, the scene, the twin, the frame, the trace).
    FrameBuffer fb("frame_buffer", run);
    Host host("host", run, fb.in.fifo);
    host.out.bind(fb.in.socket);
    inject_faults(name(), opts.faults, {});
    run.simulate();

    // The modules report themselves: the host, its link, the frame buffer and its queue.
    run.stats_over(sc_core::SC_ZERO_TIME, fb.last_write());
    return run.finish(host.latency(), {});
  }
};

const RegisterMachine<KitMinimal> kRegistered(
    {.name = "kit-minimal",
     .description = "The kit's smallest machine: a host tracing rays, a link and a frame buffer "
                    "(the example of docs/adding-a-machine.md; built into the tests only)",
     .sample_scene = "builtin:default",
     .test_runs = {"--scene builtin:default",
                   "--scene builtin:ullner-cubes -p frame_buffer.queue_depth=1"},
     .benchmark_runs = {"--scene builtin:default"}});

}  // namespace
}  // namespace rtsim::platform
