#pragma once
// Ullner's host (seed 000 L474-L476): one processor running two tasks. Task 2 processes
// results (shading, spawning secondary rays) whenever one is waiting; task 1 generates vision
// rays "whenever the host would otherwise be idle". Rays go to the ray queue of what it drives;
// rays that find it full wait in host memory (so the host never blocks on it and the two
// queues cannot deadlock).
//
// Used by both of Ullner's machines: ullner-peripheral (the ray queue, the parameter memories'
// load port, the lighting devices) and ullner-pipeline ("the same request and response as the
// peripheral, but many requests are in flight", L715: PipelineHost loads by shifting and keeps
// a window of rays in flight).
#include <tlm_utils/simple_initiator_socket.h>

#include <deque>
#include <optional>
#include <string>
#include <systemc>

#include "firmware/tasks/shade_task.hpp"
#include "modules/latency_probe.hpp"
#include "modules/link.hpp"
#include "modules/message_channel.hpp"
#include "modules/pipelined_unit.hpp"
#include "modules/processor.hpp"
#include "modules/processor_timing.hpp"
#include "modules/statistics.hpp"
#include "platform/functional/frame_state.hpp"
#include "platform/functional/scene_geometry.hpp"
#include "platform/machine.hpp"
#include "platform/machines/machine_run.hpp"
#include "platform/machines/machine_trace.hpp"
#include "platform/machines/ullner_peripheral/messages.hpp"

namespace rtsim::platform::ullner {

/// The lighting extension's devices the host computes on (seed 000 L548-L566), if it has them.
struct LightingDevices {
  /// The inner-product unit's statistics group ("peripheral.lighting"); empty: the machine has
  /// no lighting extension (then it is not enabled).
  std::string unit_name{};
  bool enabled = false;
  sc_core::sc_time interval;  ///< the arithmetic's stage time (L584)
  unsigned adder_stages = 1;  ///< Fig. 2-17
  unsigned rsqrt_stages = 2;
};

/// What the host drives: the ray queue it sends into, its link there, and how many rays it
/// may have in flight.
struct HostAttachment {
  const modules::TimedFifo<RayRequest>& ray_queue;
  /// Its ray link: the name and the parameters it reads ("host.ray_link" for the peripheral;
  /// the pipeline's first link reads the class "pipeline.link").
  std::string ray_link_name;
  std::string ray_link_params;
  std::uint64_t ray_bits = RayRequest::kWireBits;  ///< a ray on that link
  /// Rays sent and not yet answered at most (0: no limit). The result queue then holds as many:
  /// every ray has a slot reserved for its answer, so the queue never blocks what answers.
  std::uint64_t max_in_flight = 0;
  /// The result queue's slots when fewer than max_in_flight (0: as many): then what answers can
  /// find it full and must hold its answer until the host takes one (back-pressure).
  std::uint64_t result_slots = 0;
  /// Task 2 (answers) before task 1 (rays), as the thesis orders them (L474-L476); false: the
  /// host sends a ray whenever it can and takes an answer only when it cannot (a what-if).
  bool answers_first = true;
  LightingDevices lighting;
};

class Host : public modules::Processor {
 public:
  tlm_utils::simple_initiator_socket<Host> ray_out;   ///< to the peripheral's ray queue
  tlm_utils::simple_initiator_socket<Host> load_out;  ///< to the parameter memories' load port
  modules::MessageQueue<RayResult> results;           ///< the result queue

  /// Its link into the peripheral's ray queue, under its name (and its parameters' path).
  static constexpr const char* kRayLink = "ray_link";

  /// Its processor's clock and cycles (both machines' hosts: the same host, seed 000 L715).
  static void declare_processor_params(const modules::ParamDecls& host);
  /// The peripheral's host under `host`: its processor, its result queue and its ray link.
  static void declare_params(const modules::ParamDecls& host);

  SC_HAS_PROCESS(Host);
  /// Reads its own parameters under its name (its result queue's depth unless `attached`
  /// limits the rays in flight); the scene, its geometry and the shading are the run's.
  Host(sc_core::sc_module_name name, MachineRun& run, const HostAttachment& attached);

  /// From the end of the scene load to the host having the last answer.
  sc_core::sc_time frame_time() const { return frame_time_; }
  sc_core::sc_time load_time() const { return frame_start_; }
  sc_core::sc_time busy() const { return accounts().busy; }
  const modules::LatencyRecorder& latency() const { return latency_; }

 protected:
  /// Before the frame: puts the scene where the machine searches it (the peripheral: each
  /// polygon's words into the parameter memories), advancing its clock by the time it took.
  virtual void load_scene();
  modules::Link& link_to_machine() { return ray_link_; }

  const functional::SceneGeometry& geometry_;

 private:
  void run();
  void send(RayRequest req);
  /// A ray may be sent at `now`: the ray queue has room and the window is not full.
  bool may_send(const sc_core::sc_time& now) const;
  sc_core::sc_time result_time(const Cost& shade_cost);

  const scenes::Scene& scene_;
  shading::ShadeParams shade_params_;
  functional::FrameState& frame_;
  const modules::TimedFifo<RayRequest>& ray_queue_;
  LightingDevices lighting_devices_;
  std::uint64_t ray_bits_;
  std::uint64_t max_in_flight_;
  bool answers_first_;
  const RunOptions& opts_;
  sc_core::sc_time frame_start_ = sc_core::SC_ZERO_TIME;
  modules::LatencyProbe& probe_;
  int probe_result_queue_;  ///< host.result_queue
  modules::Link ray_link_;  ///< host -> the peripheral's ray queue
  int probe_ray_link_;

  /// The inner-product unit of the lighting extension, if the machine has one.
  std::optional<modules::PipelinedUnit> lighting_;
  std::deque<RayRequest> backlog_;
  std::uint64_t next_id_ = 0;
  std::uint64_t outstanding_ = 0;
  sc_core::sc_time frame_time_ = sc_core::SC_ZERO_TIME;
  modules::LatencyRecorder latency_;
  modules::Counter vision_rays_{*this, "vision_rays", "vision rays generated (task 1)"};
  modules::Counter results_processed_{*this, "results_processed", "answers taken (task 2)"};
  modules::Peak backlog_peak_{*this, "backlog_peak", "spawned rays waiting to be sent"};
  modules::Peak in_flight_peak_{*this, "in_flight_peak", "rays sent and not yet answered"};
};

}  // namespace rtsim::platform::ullner
