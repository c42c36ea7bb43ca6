#pragma once
// Ullner's host (seed 000 L474-L476): one processor running two tasks. Task 2 processes
// results (shading, spawning secondary rays) whenever one is waiting; task 1 generates vision
// rays "whenever the host would otherwise be idle". Rays go to the peripheral's ray queue; rays
// that find it full wait in host memory (so the host never blocks on the peripheral and the
// two queues cannot deadlock).
#include <tlm_utils/simple_initiator_socket.h>

#include <deque>
#include <systemc>

#include "firmware/tasks/shade_task.hpp"
#include "modules/latency_probe.hpp"
#include "modules/link.hpp"
#include "modules/message_channel.hpp"
#include "modules/pipelined_unit.hpp"
#include "modules/processor.hpp"
#include "modules/processor_timing.hpp"
#include "modules/stats_registry.hpp"
#include "platform/functional/frame_state.hpp"
#include "platform/functional/scene_geometry.hpp"
#include "platform/machine.hpp"
#include "platform/machines/machine_trace.hpp"
#include "platform/machines/ullner/messages.hpp"
#include "platform/machines/ullner/peripheral_settings.hpp"

namespace rtsim::platform::ullner {

class Host : public modules::Processor {
 public:
  tlm_utils::simple_initiator_socket<Host> ray_out;   ///< to the peripheral's ray queue
  tlm_utils::simple_initiator_socket<Host> load_out;  ///< to the parameter memories' load port
  modules::MessageQueue<RayResult> results;           ///< the result queue

  /// Its parameters under `host`: its processor's clock and cycles, its result queue.
  static void declare_params(const modules::ParamDecls& host);

  SC_HAS_PROCESS(Host);
  /// Reads its own parameters under its name; `peripheral`: the peripheral's settings (the
  /// lighting devices it computes on).
  Host(sc_core::sc_module_name name, const params::ParamRegistry& registry,
       const scenes::Scene& scene, const shading::ShadeParams& shade, functional::FrameState& frame,
       const modules::TimedFifo<RayRequest>& ray_queue, const PeripheralSettings& peripheral,
       const RunOptions& opts, MachineTrace& trace, const functional::SceneGeometry& geometry,
       modules::LatencyProbe& probe);

  /// From the end of the scene load to the host having the last answer.
  sc_core::sc_time frame_time() const { return frame_time_; }
  sc_core::sc_time load_time() const { return frame_start_; }
  sc_core::sc_time busy() const { return accounts().busy; }
  const modules::LatencyRecorder& latency() const { return latency_; }
  const modules::PipelinedUnit& lighting_unit() const { return lighting_; }
  const modules::Link& ray_link() const { return ray_link_; }
  std::uint64_t vision_rays() const { return vision_rays_; }
  std::uint64_t results_processed() const { return results_processed_; }
  std::uint64_t backlog_peak() const { return backlog_peak_; }

 private:
  void run();
  void load_scene();
  void send(RayRequest req);
  sc_core::sc_time result_time(const Cost& shade_cost);

  const scenes::Scene& scene_;
  shading::ShadeParams shade_params_;
  functional::FrameState& frame_;
  const modules::TimedFifo<RayRequest>& ray_queue_;
  PeripheralSettings peripheral_;
  const RunOptions& opts_;
  const functional::SceneGeometry& geometry_;
  sc_core::sc_time frame_start_ = sc_core::SC_ZERO_TIME;
  modules::LatencyProbe& probe_;
  int probe_result_queue_;  ///< host.result_queue
  modules::Link ray_link_;  ///< host -> the peripheral's ray queue
  int probe_ray_link_;

  modules::PipelinedUnit lighting_;  ///< the inner-product unit of the lighting extension
  std::deque<RayRequest> backlog_;
  std::uint64_t next_id_ = 0;
  std::uint64_t outstanding_ = 0;
  std::uint64_t vision_rays_ = 0;
  std::uint64_t results_processed_ = 0;
  std::uint64_t backlog_peak_ = 0;
  sc_core::sc_time frame_time_ = sc_core::SC_ZERO_TIME;
  modules::LatencyRecorder latency_;
};

}  // namespace rtsim::platform::ullner
