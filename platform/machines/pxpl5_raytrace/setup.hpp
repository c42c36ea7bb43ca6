#pragma once
// What every node of a pxpl5-raytrace run reads and none changes: where everyone is on the ring,
// the frames' cameras, the message sizes, a GP's timing, the by-pass code, and, with --sample, the
// regions simulated in detail. The rest of a node's context is the run's (MachineRun: frame,
// trace, probe, options, parameters, scene, twin); its own costs are its own parameters.
#include <string>
#include <vector>

#include "firmware/shading/camera.hpp"
#include "firmware/tasks/refinement_schedule.hpp"
#include "modules/processor_timing.hpp"
#include "params/registry.hpp"
#include "platform/machines/frame_sample.hpp"
#include "platform/machines/pxpl5_raytrace/layout.hpp"
#include "platform/machines/pxpl5_raytrace/ring_node.hpp"
#include "platform/machines/pxpl5_raytrace/sample_journeys.hpp"

namespace rtsim::platform::pxpl5 {

/// By-pass code (L333-L337): these nodes keep their message passing and drop their compute (a
/// by-passed caster sends samples of no radiance, so the image is black).
struct Bypass {
  std::string code = "none";  ///< the parameter's value
  bool casters = false, master = false, back_end = false;

  static void declare_params(params::ParamRegistry& r);
  static Bypass read(const params::ParamRegistry& r);
};

struct Setup {
  Layout layout;  ///< where everyone is, the regions, the sampling rule
  int frames = 1;
  /// By frame: what it casts and the level it is displayed at (refinement, partial updating).
  tasks::RefinementSchedule schedule;
  /// The frame whose image is written (display.frame; the last by default).
  int display_frame = 0;
  std::vector<shading::PinholeCamera> cameras;  ///< one per frame
  WireSizes sizes;
  modules::ProcessorTiming gp_timing;  ///< an i860 GP's (gp.*)
  Bypass bypass;
  /// --sample (one frame): the regions simulated in detail, and when each was done (a caster
  /// sent its samples); null without.
  FrameSample* sample = nullptr;
  /// With --sample, by compositor: the samples of the regions not simulated in detail, cast
  /// functionally (functional_regions.hpp), which it holds when the frame starts.
  std::vector<std::vector<Sample>> functional_samples;
  /// --latency-probe: a sample's journey from its caster beginning its region to the display of
  /// its frame, by class of stage.
  struct ProbeStages {
    int caster = -1, ring = -1, inbox = -1, compositor = -1, renderer = -1, frame_buffer = -1;
  } stages;
  /// --latency-probe: the samples' journeys between the nodes (null without the probe).
  SampleJourneys* journeys = nullptr;
};

}  // namespace rtsim::platform::pxpl5
