#pragma once
// The host of Wang, Lewis & Hung's machine: it renders the scene, culls each (ray, patch) pair by
// the patch's bounding box, issues the pairs that survive to the pipeline as jobs and intersects
// any other primitives itself; when all of a ray's jobs are answered it takes the nearest hit,
// shades it and spawns the next rays. Its costs are parameters (the paper gives none, note 002:
// a host is assumed, the Pentium II of the paper's timings, L274). It keeps many rays in flight
// so the pipeline can stay full.
#include <tlm_utils/simple_initiator_socket.h>

#include <deque>
#include <map>
#include <systemc>
#include <vector>

#include "firmware/shading/camera.hpp"
#include "firmware/tasks/shade_task.hpp"
#include "firmware/tasks/vision_ray_task.hpp"
#include "modules/latency_probe.hpp"
#include "modules/memory.hpp"
#include "modules/message_channel.hpp"
#include "modules/processor.hpp"
#include "modules/processor_timing.hpp"
#include "modules/statistics.hpp"
#include "platform/functional/frame_state.hpp"
#include "platform/functional/scene_geometry.hpp"
#include "platform/machine.hpp"
#include "platform/machines/machine_run.hpp"
#include "platform/machines/machine_trace.hpp"
#include "platform/machines/wang_bezier/messages.hpp"
#include "platform/machines/wang_bezier/reference_check.hpp"

namespace rtsim::platform::wang_bezier {

class BezierHost : public modules::Processor {
 public:
  tlm_utils::simple_initiator_socket<BezierHost> job_out;  ///< to the pipeline's input
  modules::MessageQueue<JobResult> results;                ///< answers, in host memory
  /// The patches' control points as the jobs carry them (48 single-precision words a patch, in
  /// the scene's patch order): what the pipeline computes on. A --fault corrupts one.
  modules::Memory patch_memory;

  static void declare_params(const modules::ParamDecls& host);

  SC_HAS_PROCESS(BezierHost);
  BezierHost(sc_core::sc_module_name name, MachineRun& run,
             const modules::TimedFifo<PatchJob>& pipeline_input, ReferenceCheck* check = nullptr);

  sc_core::sc_time frame_time() const { return frame_time_; }
  const modules::LatencyRecorder& latency() const { return latency_; }

 private:
  struct RayState {
    shading::TracedRay ray;
    bool first_sample = false;
    std::uint32_t outstanding = 0;
    std::map<std::uint32_t, kernels::WangResult<double>> answers;  ///< by patch slot
    sc_core::sc_time started;
    sc_core::sc_time culled;  ///< its pairs culled, its jobs queued
    /// The job answered last (--latency-probe follows it: the ray waits for it), and when the
    /// host took its result.
    JobResult last;
    sc_core::sc_time last_taken;
  };
  /// --latency-probe: the ray's journey, along its last job: the host culling and queueing
  /// its jobs, the pipeline's input, the pipeline, the result queue, the host answering.
  void probe_ray(const RayState& st);
  void run();
  /// Writes every patch's control net into patch_memory (before the frame).
  void load_patches();
  /// Patch k's control net as patch_memory holds it.
  const kernels::ControlNet<float>& net_of(std::size_t k);
  /// Cull the ray's pairs, queue its jobs; answer it at once if none survived.
  void start(const shading::TracedRay& ray, bool first_sample);
  /// All its jobs are back: the nearest hit over the patches' answers and the other primitives
  /// (in slot order, as the twin searches), shading, spawned rays.
  void answer(std::uint64_t id);

  const scenes::Scene& scene_;
  functional::FrameState& frame_;
  const modules::TimedFifo<PatchJob>& pipeline_input_;
  const functional::SceneGeometry& geometry_;
  const RunOptions& opts_;
  modules::LatencyProbe& probe_;
  int probe_host_, probe_input_, probe_pipeline_, probe_results_;
  ReferenceCheck* check_;  ///< the accuracy study's, or none
  tasks::ShadeTask shade_;
  std::uint64_t window_;
  std::map<std::uint64_t, RayState> rays_;
  std::deque<PatchJob> pending_;
  std::deque<shading::TracedRay> backlog_;
  std::vector<std::uint32_t> patch_slots_;  ///< the shapes that are patches
  tlm_utils::simple_initiator_socket<BezierHost> memory_port_;
  std::vector<kernels::ControlNet<float>> nets_;  ///< patch_memory decoded
  std::uint64_t decoded_after_ = ~std::uint64_t{0};
  std::vector<shading::TracedRay> spawned_;
  std::uint64_t next_id_ = 0;
  sc_core::sc_time frame_time_ = sc_core::SC_ZERO_TIME;
  modules::LatencyRecorder latency_;
  modules::Counter jobs_{*this, "jobs_issued", "(ray, patch) jobs handed to the pipeline"};
  modules::Counter culled_{*this, "pairs_culled", "(ray, patch) pairs culled by the patch's box"};
  modules::Peak in_flight_peak_{*this, "rays_in_flight_peak", "rays with jobs outstanding"};
  modules::Distribution job_latency_{
      *this, "job_latency_s", "a job's time from entering the pipeline to its answer being read"};
};

}  // namespace rtsim::platform::wang_bezier
