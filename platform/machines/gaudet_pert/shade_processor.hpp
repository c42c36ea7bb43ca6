#pragma once
// The ShadeProcessor of a PERT (seed 001 §4.5, Fig. 4-8, L725-L742; §5.5, L930-L938): spawns
// the initial rays of its PERT's scanlines (i, i + N, i + 2N, ... for PERT i of N, the
// "leapfrog" split of L938) and shades what comes back, writing straight into its own part of
// the frame buffer (L930).
//
// For a PRIM_TO_SHADE: a light ray that reached its light adds the light's intensity times its
// factor, a blocked one is dropped; a ray that hit nothing adds the background; a hit needs the
// surface's SHADE packet (≤ 1 ID per ray in the BIC, L910): when it arrives, the ambient,
// diffuse and specular terms are added and the light rays and the reflected ray (above the
// contribution threshold) are spawned (L730). A per-initial-ray count of rays outstanding tells
// when a pixel is finished (the thesis does not say how, note 001 §1.6); the processor keeps
// `rays_in_flight` initial rays (with all their descendants) in the ring at a time.
//
// The processor never blocks on the ring: rays it cannot send yet wait in its memory, and it
// always takes the answers coming back first, so the ring of bounded queues cannot deadlock.
#include <tlm_utils/simple_initiator_socket.h>

#include <deque>
#include <map>
#include <memory>
#include <vector>

#include "firmware/shading/camera.hpp"
#include "firmware/tasks/shade_task.hpp"
#include "firmware/tasks/vision_ray_task.hpp"
#include "modules/message_channel.hpp"
#include "modules/statistics.hpp"
#include "platform/functional/frame_state.hpp"
#include "platform/machine.hpp"
#include "platform/machines/gaudet_pert/messages.hpp"
#include "platform/machines/gaudet_pert/packet_port.hpp"
#include "platform/machines/gaudet_pert/pert_context.hpp"
#include "platform/machines/gaudet_pert/pert_processor.hpp"

namespace rtsim::platform::gaudet {

class ShadeProcessor : public PertProcessor {
 public:
  modules::MessageQueue<PrimToShade> input;
  tlm_utils::simple_initiator_socket<ShadeProcessor> out;

  /// Its parameters under `shade` ("pert.shade").
  static void declare_params(const modules::ParamDecls& shade);

  /// The ShadeProcessor of PERT number `pert`; its data set through `port`, its input queue
  /// `input_depth` messages deep.
  ShadeProcessor(sc_core::sc_module_name name, const PertContext& context, int pert,
                 PacketPort& port, std::size_t input_depth);

  void set_output_queue(const modules::TimedFifo<ShadeToShell>& q) { out_queue_ = &q; }
  /// The control processor starts the frame at `t` and is told when this PERT is done.
  void start(const sc_core::sc_event& frame_start, sc_core::sc_event& done) {
    set_frame_start(frame_start);
    done_event_ = &done;
  }
  bool finished() const { return finished_; }
  sc_core::sc_time finish_time() const { return finish_time_; }

 private:
  /// Its loop (PertProcessor::start_program).
  modules::Resumable program();
  /// Shading of one answer (its SHADE packet, if it needs one, is in).
  modules::Resumable shade(const PrimToShade& msg);
  modules::Resumable receive(PrimToShade msg);
  /// Numbers the ray, stamps its send time and puts it in the queue to the ShellProcessor, over
  /// the ring link (the send's cost, the words written since `since`, is charged by the caller,
  /// with whatever else the step costs).
  void send(RayTicket& t, const sc_core::sc_time& since);
  bool next_initial_ray(shading::TracedRay& ray, int& sample);

  int pert_, pert_count_;
  functional::FrameState& frame_;
  const shading::PinholeCamera& camera_;
  const std::vector<std::uint32_t>& packet_words_;  ///< SHADE packets
  FrameProgress& progress_;
  PacketPort& port_;
  const modules::TimedFifo<ShadeToShell>* out_queue_ = nullptr;
  sc_core::sc_event* done_event_ = nullptr;

  tasks::ShadeTask task_;
  std::unique_ptr<tasks::VisionRayTask> scanline_;
  int y_;                                   ///< current scanline
  std::vector<std::uint32_t> outstanding_;  ///< per tree slot: rays not yet answered
  std::vector<std::uint32_t> free_trees_;
  std::size_t trees_in_flight_ = 0;
  std::deque<RayTicket> backlog_;
  std::map<std::uint32_t, std::vector<PrimToShade>> awaiting_;  ///< SHADE packet -> answers
  std::vector<std::uint32_t> unasked_;                          ///< SHADE IDs not yet in a register
  std::vector<shading::TracedRay> spawned_;
  std::uint64_t next_id_ = 0;
  modules::Peak backlog_peak_{*this, "backlog_peak", "rays spawned and waiting to enter the ring"};
  bool finished_ = false;
  sc_core::sc_time finish_time_ = sc_core::SC_ZERO_TIME;
};

}  // namespace rtsim::platform::gaudet
