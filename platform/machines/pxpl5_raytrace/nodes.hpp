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
// Each node takes the run (MachineRun) and the run's Setup, and declares and reads its own costs
// (the seed gives none: each parameter's source says why its default).
#include <deque>
#include <map>
#include <memory>
#include <vector>

#include "firmware/tasks/shade_task.hpp"
#include "modules/statistics.hpp"
#include "params/registry.hpp"
#include "platform/machines/machine_run.hpp"
#include "platform/machines/pxpl5_raytrace/ring_node.hpp"
#include "platform/machines/pxpl5_raytrace/samples_fault.hpp"
#include "platform/machines/pxpl5_raytrace/setup.hpp"

namespace rtsim::platform::pxpl5 {

class Host : public RingNode {
 public:
  SC_HAS_PROCESS(Host);
  /// pipeline.frames_in_flight.
  static void declare_params(params::ParamRegistry& r);
  Host(sc_core::sc_module_name name, MachineRun& run, modules::RingChannel<Message>& ring,
       const Setup& setup);
  /// When each frame started (its view read, L288) and when the host heard it was displayed.
  const std::vector<sc_core::sc_time>& started() const { return started_; }
  const std::vector<sc_core::sc_time>& done() const { return done_; }
  /// Frames the host lets into the pipeline before the first of them is displayed.
  int frames_in_flight() const { return in_flight_; }

 private:
  void run();
  void start(int f);
  MachineRun& run_;
  const Setup& setup_;
  int in_flight_;
  std::vector<sc_core::sc_time> started_, done_;
};

class MasterGp : public RingNode {
 public:
  SC_HAS_PROCESS(MasterGp);
  /// master.assign_time and assign.order.
  static void declare_params(params::ParamRegistry& r);
  MasterGp(sc_core::sc_module_name name, MachineRun& run, modules::RingChannel<Message>& ring,
           const Setup& setup);
  /// assign.order: "cost" or "screen".
  const char* order() const { return cost_order_ ? "cost" : "screen"; }

 private:
  void run();
  void assign(int caster);
  /// Frame f's regions become the ones handed out (in cost order after the first, L360).
  void begin_frame(int f);
  const Setup& setup_;
  sc_core::sc_time assign_time_;
  bool after_casting_;  ///< master.next_frame: a frame's regions wait for the last one's cast
  bool cost_order_;     ///< hands out the costliest regions of the previous frame first
  std::vector<Region> regions_;  ///< the frame's, in the order they are given out
  std::size_t next_ = 0;
  std::size_t cast_ = 0;      ///< the frame's regions reported cast
  std::vector<double> cost_;  ///< by region id: its time in the previous frame
  std::vector<int> waiting_;  ///< casters whose request waits for the next frame
  std::deque<int> starts_;    ///< frames started while the one handed out had regions left
  int frame_ = -1;
  modules::Counter assignments_{*this, "assignments", "regions handed out"};
};

class RayCaster : public RingNode {
 public:
  SC_HAS_PROCESS(RayCaster);
  RayCaster(sc_core::sc_module_name name, MachineRun& run, modules::RingChannel<Message>& ring,
            const Setup& setup, int number, SamplesFault& fault);

 private:
  void run();
  MachineRun& run_;
  const Setup& setup_;
  SamplesFault& fault_;
  tasks::ShadeTask shade_;
  modules::Counter cast_last_frame_{*this, "cast_last_frame",
                                    "rays cast on the screen in the last frame"};
  modules::Counter covered_last_frame_{
      *this, "covered_last_frame",
      "rays of the last frame whose primary ray hit something (the screen coverage's count)"};
  modules::Counter regions_{*this, "regions", "regions cast"};
  modules::Counter rays_{*this, "rays",
                         "rays cast at lattice positions (each with its spp vision rays)"};
  modules::Counter samples_{*this, "samples", "samples sent to the compositors"};
};

class Compositor : public RingNode {
 public:
  SC_HAS_PROCESS(Compositor);
  /// compositor.sample_time (compositor.band_rows is the layout's).
  static void declare_params(params::ParamRegistry& r);
  Compositor(sc_core::sc_module_name name, MachineRun& run, modules::RingChannel<Message>& ring,
             const Setup& setup, int number);

 private:
  void run();
  /// Samples the casters send this compositor in frame `frame`.
  long expected(int frame) const;
  /// --latency-probe: the journeys of the samples of `m`, composited now; they wait with the
  /// compositor until its bands have the frame.
  void probe_samples(const Message& m);
  /// --latency-probe: the frame's bands were sent now: its samples' journeys go on to the
  /// renderers of their display pixels.
  void probe_bands_sent(int frame);
  struct Held {
    SampleJourneys::Journey journey;
    int renderer;
    sc_core::sc_time composited;
  };
  std::map<int, std::vector<Held>> held_journeys_;  ///< by frame
  MachineRun& run_;
  const Setup& setup_;
  int number_;
  sc_core::sc_time sample_time_;
  modules::Counter samples_{*this, "samples", "samples composited"};
  /// By frame phase (0: the first frame, 1 + f mod period after): samples to wait for.
  std::vector<long> expected_;
};

class Renderer : public RingNode {
 public:
  SC_HAS_PROCESS(Renderer);
  /// renderer.tile_time.
  static void declare_params(params::ParamRegistry& r);
  Renderer(sc_core::sc_module_name name, MachineRun& run, modules::RingChannel<Message>& ring,
           const Setup& setup, int number);

 private:
  /// --latency-probe: the tile of `frame` was resampled from `began` to now; the journeys of the
  /// samples whose display pixels it holds go on with its pixels.
  void probe_tile(int frame, const sc_core::sc_time& began,
                  const std::map<int, sc_core::sc_time>& delivered);
  void run();
  MachineRun& run_;
  const Setup& setup_;
  int number_;
  sc_core::sc_time tile_time_;
};

class FrameBuffer : public RingNode {
 public:
  SC_HAS_PROCESS(FrameBuffer);
  /// frame_buffer.pixel_time and display.frame.
  static void declare_params(params::ParamRegistry& r);
  /// display.frame for a run of `frames` frames (-1: the last); one past the run is bad input.
  static int display_frame(const params::ParamRegistry& r, int frames);
  FrameBuffer(sc_core::sc_module_name name, MachineRun& run, modules::RingChannel<Message>& ring,
              const Setup& setup);
  /// When each frame was displayed: every pixel of it and of the frames before it written.
  const std::vector<sc_core::sc_time>& displayed() const { return displayed_; }

 private:
  /// --latency-probe: the journeys of the tile whose pixels `m` carries, written now.
  void probe_pixels(const Message& m);
  /// --latency-probe: frame `frame` is displayed now: its samples' journeys end.
  void probe_display(int frame);
  void run();
  MachineRun& run_;
  const Setup& setup_;
  sc_core::sc_time pixel_time_;
  std::vector<sc_core::sc_time> displayed_;
};

}  // namespace rtsim::platform::pxpl5
