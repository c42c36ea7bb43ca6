#include "platform/machines/gaudet_pert/shade_processor.hpp"

#include <stdexcept>
#include <string>

#include "firmware/tasks/pert_task_costs.hpp"

namespace rtsim::platform::gaudet {

namespace {
const modules::CountParam kRaysInFlight(
    {.name = "rays_in_flight",
     .default_value = "4",
     .min = "1",
     .max = "100000",
     .unit = "initial rays",
     .description = "Initial rays a ShadeProcessor keeps in its PERT at a time (each with every "
                    "ray it spawns)",
     .source = "assumption: Fig. 4-8 spawns a pixel's ray when the previous pixel is finished "
               "(L738-L742) but a pipeline of three needs several in flight; see "
               "docs/machines.md"});
}  // namespace

void ShadeProcessor::declare_params(const modules::ParamDecls& shade) {
  PertProcessor::declare_params(
      shade, {.value = "4",
              .description = "ID registers of the ShadeProcessor's BIC",
              .source = "assumption: \"multiple\" (L910); Shade puts at most one ID per ray"});
  shade.add(kRaysInFlight);
}

ShadeProcessor::ShadeProcessor(sc_core::sc_module_name name, const PertContext& c, int pert,
                               PacketPort& port, std::size_t input_depth)
    : PertProcessor(name, c.run, c.on_queue),
      input("input", input_depth, ring_queue("prim_to_shade")),
      out("out"),
      pert_(pert),
      pert_count_(c.pert_count),
      frame_(c.run.frame()),
      camera_(c.camera),
      packet_words_(c.sets.shade.packet_words),
      progress_(c.progress),
      port_(port),
      task_(c.run.scene(), c.run.twin().settings.shade),
      y_(pert),
      outstanding_(std::max<std::size_t>(params_.get(kRaysInFlight), 1), 0) {
  for (std::size_t i = outstanding_.size(); i-- > 0;)
    free_trees_.push_back(static_cast<std::uint32_t>(i));
  start_program(program());
}

bool ShadeProcessor::next_initial_ray(shading::TracedRay& ray, int& sample) {
  const auto& f = frame_;
  // This PERT's scanlines: pert, pert + N, pert + 2N, ... (L938).
  while (!scanline_ || scanline_->done()) {
    if (scanline_) y_ += pert_count_;
    if (y_ >= f.height()) return false;
    const auto first = static_cast<std::uint32_t>(y_) * static_cast<std::uint32_t>(f.width());
    scanline_ = std::make_unique<tasks::VisionRayTask>(
        camera_, f.width(), f.height(), f.spp(), first,
        first + static_cast<std::uint32_t>(f.width()), f.detailed_rows());
  }
  ray = scanline_->next(sample);
  return true;
}

modules::Resumable ShadeProcessor::shade(const PrimToShade& msg) {
  const RayTicket& t = msg.ticket;
  const Cost c = task_.on_result(t.ray, msg.found, msg.hit, frame_.fb(), spawned_);
  frame_.counters().cost += c;
  co_await compute(c, "shade");
  ++rays_;
  for (const auto& s : spawned_) {
    RayTicket child;
    child.ray = s;
    child.tree = t.tree;
    child.t_min = task_.t_min(s);
    backlog_.push_back(child);
  }
  backlog_peak_.note(backlog_.size());
  std::uint32_t& left = outstanding_[t.tree];
  left += static_cast<std::uint32_t>(spawned_.size());
  if (--left == 0) {
    // Every ray of this initial ray is answered: the pixel sample is finished.
    free_trees_.push_back(t.tree);
    --trees_in_flight_;
    progress_.tree_done();
  }
}

modules::Resumable ShadeProcessor::receive(PrimToShade msg) {
  RayTicket& t = msg.ticket;
  // From the PrimProcessor's send to here the answer waited in the queue.
  probe_->to(t, Stage::kPrimToShade, RayProbe::Part::kQueueing, clock_.now());
  co_await compute_for(t, Stage::kShade, tasks::words_cost(PrimToShade::kWords), "receive");
  co_await settle();
  frame_.counters().count_ray(t.ray.kind);
  progress_.ray_back(clock_.now() - t.sent);
  probe_->end(t, clock_.now());
  if (t.first_sample) frame_.record_primary(t.ray.pixel, msg.found, msg.hit);
  if (!msg.found || t.ray.kind == RayKind::Shadow) {
    co_await shade(msg);  // no surface to look up: light reached or blocked, or the background
    co_return;
  }
  // The surface's characteristics come from the Shade bus (one ID per ray, L910).
  const auto id = static_cast<std::uint32_t>(msg.hit.material);
  auto& waiting = awaiting_[id];
  waiting.push_back(std::move(msg));
  if (waiting.size() > 1) co_return;
  co_await compute(tasks::kAskPacketCost, "ask");
  co_await settle();
  if (!port_.request(id, clock_.now())) unasked_.push_back(id);
}

void ShadeProcessor::send(RayTicket& t, const sc_core::sc_time& since) {
  t.id = next_id_++;
  t.sent = clock_.now();  // ray_latency_s and the probe's journey start here
  probe_->begin(t, t.sent);
  ShadeToShell msg{t};
  // A put into a full queue would wait for a take (TimedFifo::put): the loop looked for room
  // (has_room_by) and the send waits for nothing, so it never does.
  if (out_queue_->full()) throw std::logic_error(std::string(name()) + ": sent into a full queue");
  modules::send_message(out, msg, over_link(ShadeToShell::kWords, since, t),
                        std::uint64_t{32} * ShadeToShell::kWords);
}

modules::Resumable ShadeProcessor::program() {
  co_await begin_frame();
  // What it idles on: an answer, a SHADE packet, room in the queue to the ShellProcessor.
  constexpr unsigned idle_on = kInput | kPort | kRoom;
  bool vision_left = true;
  for (;;) {
    co_await settle();
    const sc_core::sc_time now = clock_.now();
    // Answers first: they finish pixels and free the ring.
    if (input.fifo.has_item_by(now)) {
      sc_core::sc_time taken;
      PrimToShade msg = input.fifo.get(now, taken);
      co_await catch_up(taken);
      co_await receive(std::move(msg));
      continue;
    }
    if (auto p = port_.take(now)) {
      co_await compute(tasks::words_cost(packet_words_[p->id]) + tasks::kPacketBookkeepingCost,
                       "packet");
      auto node = awaiting_.extract(p->id);
      co_await settle();
      port_.release(*p, clock_.now());
      if (!node.empty())
        for (const auto& msg : node.mapped()) co_await shade(msg);
      continue;
    }
    if (!unasked_.empty() && port_.register_free(now)) {
      co_await compute(tasks::kAskPacketCost, "ask");
      co_await settle();
      if (port_.request(unasked_.back(), clock_.now())) unasked_.pop_back();
      continue;
    }
    const bool room = out_queue_->has_room_by(now);
    // Spawned rays before new initial rays: they finish pixels.
    if (room && !backlog_.empty()) {
      RayTicket t = backlog_.front();
      backlog_.pop_front();
      const WritingAhead ahead(*this);
      const sc_core::sc_time since = clock_.now();
      co_await compute(tasks::words_cost(ShadeToShell::kWords), "send");
      send(t, since);
      continue;
    }
    if (room && vision_left && !free_trees_.empty()) {
      RayTicket t;
      int sample = 0;
      if (!next_initial_ray(t.ray, sample)) {
        vision_left = false;
        continue;
      }
      const WritingAhead ahead(*this);
      const sc_core::sc_time since = clock_.now();
      co_await compute(tasks::VisionRayTask::kCost + tasks::words_cost(ShadeToShell::kWords),
                       "spawn");
      t.tree = free_trees_.back();
      free_trees_.pop_back();
      ++trees_in_flight_;
      outstanding_[t.tree] = 1;
      t.first_sample = sample == 0;
      t.t_min = task_.t_min(t.ray);
      send(t, since);
      continue;
    }
    if (!vision_left && trees_in_flight_ == 0) break;
    // Idle until an answer, a SHADE packet or room in the queue to the ShellProcessor.
    std::optional<sc_core::sc_time> next = input.fifo.next_item_time();
    auto earliest = [&next](std::optional<sc_core::sc_time> t) {
      if (t && (!next || *t < *next)) next = t;
    };
    earliest(port_.next_arrival());
    const bool want_send = !backlog_.empty() || (vision_left && !free_trees_.empty());
    if (want_send) earliest(out_queue_->next_room_time());
    co_await idle(next, idle_on, !awaiting_.empty());
  }
  finished_ = true;
  finish_time_ = clock_.now();
  co_await settle();
  // At its local time, which the machine's queue may have run ahead of SystemC's (a delta
  // cycle later otherwise).
  if (done_event_) done_event_->notify(clock_.now() - modules::systemc_now());
}

}  // namespace rtsim::platform::gaudet
