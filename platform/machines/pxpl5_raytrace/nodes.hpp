#pragma once
// The nodes of the Pixel-Planes 5 ray tracer (seed 004 Fig. 1, L292-L315), each a kit processor
// on the ring (ring_node.hpp):
//   Host         the Sun-4: starts each frame and hears when the frame buffer has it (L306);
//   MasterGp     hands out screen regions first-come-first-served (L352), in screen order or
//                in descending order of what each cost in the previous frame (L360);
//   RayCaster    an i860 GP with the whole scene (replicated, L310): samples its region on the
//                lattice (firmware/tasks/region_sampling.hpp: uniform, partial updating or
//                adaptive) and sends each compositor the samples in its bands;
//   Compositor   an i860 GP owning bands of rows (L310): keeps its samples from frame to frame
//                (partial updating, L379) and, when its bands have every sample of the frame,
//                sends each renderer the part of them its tile reads;
//   Renderer     a SIMD renderer owning a 128 x 128 tile (L282): resamples the lattice to
//                display pixels (at one sample a pixel, unchanged) and sends them on;
//   FrameBuffer  writes the pixels that arrive into the image and tells the host when a frame
//                is complete.
// Costs are parameters (the seed gives none: Pxpl5Raytrace::declare_params says why each).
#include <map>
#include <memory>
#include <vector>

#include "firmware/shading/camera.hpp"
#include "firmware/shading/pixel_accumulator.hpp"
#include "firmware/tasks/shade_task.hpp"
#include "firmware/tracer.hpp"
#include "modules/latency_probe.hpp"
#include "modules/processor_timing.hpp"
#include "modules/statistics.hpp"
#include "platform/functional/frame_state.hpp"
#include "platform/machine.hpp"
#include "platform/machines/frame_sample.hpp"
#include "platform/machines/pxpl5_raytrace/layout.hpp"
#include "platform/machines/pxpl5_raytrace/ring_node.hpp"

namespace rtsim::platform::pxpl5 {

/// What the nodes share.
struct Context {
  Layout layout;  ///< where everyone is, the regions, the sampling rule
  bool cost_order = true;
  int frames = 1;
  WireSizes sizes;
  modules::ProcessorTiming gp_timing;           ///< an i860 GP's (gp.*)
  std::vector<shading::PinholeCamera> cameras;  ///< one per frame
  const Tracer* tracer = nullptr;
  const scenes::Scene* scene = nullptr;
  shading::ShadeParams shade;
  functional::FrameState* frame = nullptr;  ///< the image: the last frame's pixels
  const RunOptions* opts = nullptr;
  /// By-pass code (L333-L337): these nodes keep their message passing and drop their compute
  /// (a by-passed caster sends samples of no radiance, so the image is black).
  bool bypass_casters = false, bypass_master = false, bypass_back_end = false;
  /// A fault for tests: the samples message with this number (1, 2, ..., counted over all
  /// casters) has its first sample changed on the ring (black, or white if it was black); 0 changes
  /// none.
  std::uint64_t corrupt_samples = 0;
  std::uint64_t samples_messages = 0;
  /// --sample (one frame): the regions simulated in detail, and when each was done (a caster
  /// sent its samples); null without.
  FrameSample* sample = nullptr;
  /// With --sample, by compositor: the samples of the regions not simulated in detail, cast
  /// functionally (functional_regions.hpp), which it holds when the frame starts.
  std::vector<std::vector<Sample>> functional_samples;
  /// --latency-probe: a sample's journey from its caster beginning its region to its
  /// compositor having composited it (stages by class: caster*, ring, compositor*.inbox,
  /// compositor*).
  modules::LatencyProbe* probe = nullptr;
  struct ProbeStages {
    int caster = -1, ring = -1, inbox = -1, compositor = -1;
  } stages;
};

class Host : public RingNode {
 public:
  SC_HAS_PROCESS(Host);
  Host(sc_core::sc_module_name name, MachineTrace& trace, modules::RingChannel<Message>& ring,
       Context& ctx);
  /// When each frame started and was complete in the frame buffer.
  const std::vector<sc_core::sc_time>& started() const { return started_; }
  const std::vector<sc_core::sc_time>& done() const { return done_; }

 private:
  void run();
  Context& ctx_;
  std::vector<sc_core::sc_time> started_, done_;
};

class MasterGp : public RingNode {
 public:
  SC_HAS_PROCESS(MasterGp);
  MasterGp(sc_core::sc_module_name name, MachineTrace& trace, modules::RingChannel<Message>& ring,
           Context& ctx, const sc_core::sc_time& assign_time);

 private:
  void run();
  void assign(int caster);
  Context& ctx_;
  sc_core::sc_time assign_time_;
  std::vector<Region> regions_;  ///< the frame's, in the order they are given out
  std::size_t next_ = 0;
  std::vector<double> cost_;  ///< by region id: its time in the previous frame
  std::vector<int> waiting_;  ///< casters whose request waits for the next frame
  int frame_ = -1;
  modules::Counter assignments_{*this, "assignments", "regions handed out"};
};

class RayCaster : public RingNode {
 public:
  SC_HAS_PROCESS(RayCaster);
  RayCaster(sc_core::sc_module_name name, MachineTrace& trace, modules::RingChannel<Message>& ring,
            Context& ctx, int number);
  /// Rays cast at lattice positions (each with its `spp` vision rays).
  std::uint64_t rays() const { return rays_.value(); }
  /// In the last frame: rays cast on the screen, and those whose primary ray hit something.
  std::uint64_t cast_last_frame() const { return cast_last_frame_; }
  std::uint64_t covered_last_frame() const { return covered_last_frame_; }

 private:
  void run();
  Context& ctx_;
  tasks::ShadeTask shade_;
  std::uint64_t cast_last_frame_ = 0, covered_last_frame_ = 0;
  modules::Counter regions_{*this, "regions", "regions cast"};
  modules::Counter rays_{*this, "rays",
                         "rays cast at lattice positions (each with its spp vision rays)"};
  modules::Counter samples_{*this, "samples", "samples sent to the compositors"};
};

class Compositor : public RingNode {
 public:
  SC_HAS_PROCESS(Compositor);
  Compositor(sc_core::sc_module_name name, MachineTrace& trace, modules::RingChannel<Message>& ring,
             Context& ctx, int number, const sc_core::sc_time& sample_time);

 private:
  void run();
  /// Samples the casters send this compositor in frame `frame`.
  long expected(int frame) const;
  /// --latency-probe: the journeys of the samples of `m`, composited now.
  void probe_samples(const Message& m);
  Context& ctx_;
  int number_;
  sc_core::sc_time sample_time_;
  modules::Counter samples_{*this, "samples", "samples composited"};
  /// By frame phase (0: the first frame, 1 + f mod period after): samples to wait for.
  std::vector<long> expected_;
};

class Renderer : public RingNode {
 public:
  SC_HAS_PROCESS(Renderer);
  Renderer(sc_core::sc_module_name name, MachineTrace& trace, modules::RingChannel<Message>& ring,
           Context& ctx, int number, const sc_core::sc_time& tile_time);

 private:
  void run();
  Context& ctx_;
  int number_;
  sc_core::sc_time tile_time_;
};

class FrameBuffer : public RingNode {
 public:
  SC_HAS_PROCESS(FrameBuffer);
  FrameBuffer(sc_core::sc_module_name name, MachineTrace& trace,
              modules::RingChannel<Message>& ring, Context& ctx,
              const sc_core::sc_time& pixel_time);

 private:
  void run();
  Context& ctx_;
  sc_core::sc_time pixel_time_;
};

}  // namespace rtsim::platform::pxpl5
