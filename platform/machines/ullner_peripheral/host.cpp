#include "platform/machines/ullner_peripheral/host.hpp"

#include <cstring>

#include "firmware/kernels/ullner_quad_words.hpp"
#include "firmware/shading/camera.hpp"
#include "firmware/tasks/vision_ray_task.hpp"
#include "modules/memory.hpp"
#include "modules/sim_time.hpp"

namespace rtsim::platform::ullner {

using modules::times;

namespace {
/// Formatting one ray request into the queue: its words written, a few instructions.
Cost send_cost(std::uint64_t ray_bits) { return {.mem_words = ray_bits / 32, .instructions = 4}; }
}  // namespace

void Host::declare_processor_params(const modules::ParamDecls& host) {
  modules::declare_processor_params(
      host,
      {.clock = "5 MHz",
       .fp_add = 6,
       .fp_mul = 8,
       .fp_div = 20,
       .fp_sqrt = 60,
       .mem_word = 2,
       .instruction = 2,
       .source = "assumption: the thesis gives no host costs (seed 000 L476); a VAX-11/780-class "
                 "\"medium-sized host\" (L462) with floating-point accelerator"});
}

namespace {
const modules::CountParam kResultQueueDepth(
    {.name = "result_queue_depth",
     .default_value = "16",
     .min = "1",
     .max = "1000000",
     .unit = "results",
     .description = "Depth of the result queue from the peripheral to the host",
     .source = "assumption: queue depths are not given (seed 000 L476)"});
}  // namespace

void Host::declare_params(const modules::ParamDecls& host) {
  declare_processor_params(host);
  host.add(kResultQueueDepth);
  modules::Link::declare_params(
      host.sub(kRayLink),
      {.latency = "0 s",
       .lanes = "32",
       .bit_rate = "3 Mbit/s",
       .source = "assumption: the thesis gives no host interface (seed 000 L476); a word-wide "
                 "path at the peripheral's stage rate, one word per 1/3 us (L584)"});
}

Host::Host(sc_core::sc_module_name name, MachineRun& run, const HostAttachment& attached)
    : modules::Processor(name, run.trace()),
      ray_out("ray_out"),
      load_out("load_out"),
      // With a window, every ray in flight has a slot reserved for its answer.
      results("result_queue",
              attached.result_slots > 0 ? attached.result_slots
              : attached.max_in_flight > 0
                  ? attached.max_in_flight
                  : modules::ModuleParams(run.registry(), this->name()).get(kResultQueueDepth)),
      geometry_(*run.twin().geometry),
      scene_(run.scene()),
      shade_params_(run.twin().settings.shade),
      frame_(run.frame()),
      ray_queue_(attached.ray_queue),
      lighting_devices_(attached.lighting),
      ray_bits_(attached.ray_bits),
      max_in_flight_(attached.max_in_flight),
      answers_first_(attached.answers_first),
      opts_(run.options()),
      probe_(run.probe()),
      probe_result_queue_(probe_.stage(results.name())),
      ray_link_(attached.ray_link_name,
                modules::ModuleParams(run.registry(), attached.ray_link_params)),
      probe_ray_link_(probe_.stage(ray_link_.name())) {
  // The inner-product device: 3 multipliers then two levels of adders (seed 000 L564), at the
  // peripheral's arithmetic rate (L584).
  if (!attached.lighting.unit_name.empty())
    lighting_.emplace(attached.lighting.unit_name, attached.lighting.interval,
                      1 + 2 * attached.lighting.adder_stages, "inner_products");
  set_timing(modules::read_processor_timing(modules::ModuleParams(run.registry(), this->name())));
  ray_link_.trace_to(run.trace());
  SC_THREAD(run);
}

sc_core::sc_time Host::result_time(const Cost& c) {
  if (!lighting_devices_.enabled) return timing().time_for(c);
  // With the lighting extension the host only controls and moves data (L566); the vector
  // arithmetic runs on the inner-product device, 3 multiplies per inner product (L564), and
  // each normalisation through the reciprocal-square-root device.
  Cost control = c;
  control.fp_add = control.fp_mul = control.fp_div = control.fp_sqrt = 0;
  const sc_core::sc_time host_part = timing().time_for(control);
  const std::uint64_t inner_products = (c.fp_mul + 2) / 3;
  const sc_core::sc_time start = clock_.now() + host_part;
  auto batch = lighting_->issue(inner_products, start);
  const sc_core::sc_time done =
      batch.done + times(lighting_devices_.interval, lighting_devices_.rsqrt_stages * c.fp_sqrt);
  return done - clock_.now();
}

void Host::send(RayRequest req) {
  const sc_core::sc_time cost = timing().time_for(send_cost(ray_bits_));
  const sc_core::sc_time since = clock_.now();
  compute_for(cost, "send");
  req.id = next_id_++;
  req.sent = clock_.now();
  // The latency window opens here, as ray_latency_s's does. The words cross the ray link as the
  // host writes them; the ray is in the queue when the last one arrives (the host only sends
  // when the queue has room).
  req.journey = probe_.begin(req.sent);
  req.arrived = ray_link_.transfer(ray_bits_, since, req.sent, {"ray", "ray", req.id});
  probe_.add(req.journey, probe_ray_link_, modules::LatencyPart::kTransfer, req.arrived - req.sent);
  modules::send_message(ray_out, req, req.arrived, ray_bits_);
  ++outstanding_;
  in_flight_peak_.note(outstanding_);
}

bool Host::may_send(const sc_core::sc_time& now) const {
  return ray_queue_.has_room_by(now) && (max_in_flight_ == 0 || outstanding_ < max_in_flight_);
}

void Host::load_scene() {
  // Each polygon's 20 parameters as 32-bit words (24-bit fraction, 8-bit exponent, L582) into
  // line k of the parameter memories. One transaction per polygon, its delay annotated and
  // accumulated (loosely timed: the host synchronises once, when the load is done).
  sc_core::sc_time delay = sc_core::SC_ZERO_TIME;
  constexpr std::size_t kLine = kernels::kUllnerStoredWords;
  std::array<std::uint32_t, kLine> words{};
  for (std::size_t k = 0; k < geometry_.shapes.size(); ++k) {
    const auto* quad = std::get_if<kernels::UllnerQuadKernel>(&geometry_.shapes[k].shape);
    if (!quad) continue;
    kernels::store_words(quad->params, words);
    if (!modules::write_words(load_out, k * kLine, words.data(), kLine, delay))
      SC_REPORT_ERROR("rtsim/ullner", "parameter memory load failed");
  }
  clock_.catch_up(delay);
}

void Host::run() {
  load_scene();
  frame_start_ = clock_.now();
  shading::PinholeCamera camera(scene_.camera, frame_.width(), frame_.height());
  tasks::VisionRayTask vision(camera, frame_.width(), frame_.height(), frame_.spp(),
                              frame_.detailed_rows());
  tasks::ShadeTask shade(scene_, shade_params_);
  std::vector<shading::TracedRay> spawned;
  const std::uint64_t total_vision = vision.remaining();

  for (;;) {
    const sc_core::sc_time now = clock_.now();
    const bool room = may_send(now);
    // Task 2: a result is waiting (and, with rays first, no ray can be sent now).
    if (results.fifo.has_item_by(now) &&
        (answers_first_ || !room || (backlog_.empty() && vision.done()))) {
      sc_core::sc_time taken;
      RayResult res = results.fifo.get(now, taken);
      clock_.catch_up(taken);
      --outstanding_;
      ++results_processed_;
      latency_.add(taken - res.request.sent);
      // From the answer leaving the peripheral (waiting for room in a full result queue
      // included) until task 2 takes it: the result queue. The window closes here.
      probe_.add(res.request.journey, probe_result_queue_, modules::LatencyPart::kQueueing,
                 taken - res.arrived);
      probe_.end(res.request.journey, taken);
      const shading::TracedRay& r = res.request.ray;
      frame_.counters().count_ray(r.kind);
      if (res.request.first_sample) frame_.record_primary(r.pixel, res.found, res.hit);
      const Cost c = shade.on_result(r, res.found, res.hit, frame_.fb(), spawned);
      frame_.counters().cost += c;
      const sc_core::sc_time t = result_time(c);
      hop("ray", res.request.id);
      compute_for(t, "result", {{"ray", res.request.id}, {"spawned", spawned.size()}});
      for (const auto& s : spawned) {
        RayRequest req;
        req.ray = s;
        backlog_.push_back(req);
      }
      backlog_peak_.note(backlog_.size());
      if (opts_.progress && (results_processed_.value() & 1023) == 0)
        opts_.progress(static_cast<long>(vision_rays_.value()), static_cast<long>(total_vision));
      continue;
    }
    // Rays spawned by task 2 go first: they finish pixels.
    if (!backlog_.empty() && room) {
      RayRequest req = backlog_.front();
      backlog_.pop_front();
      send(req);
      continue;
    }
    // Task 1: generate a vision ray while otherwise idle.
    if (!vision.done() && room) {
      int sample = 0;
      RayRequest req;
      req.ray = vision.next(sample);
      req.first_sample = sample == 0;
      const sc_core::sc_time t = timing().time_for(tasks::VisionRayTask::kCost);
      compute_for(t, "vision ray", {{"pixel", req.ray.pixel}});
      ++vision_rays_;
      send(req);
      continue;
    }
    if (outstanding_ == 0 && backlog_.empty() && vision.done()) break;
    // Idle: move to the next event already known (a result stamped ahead of us, a slot the
    // peripheral frees ahead of us), else wait in global time for the peripheral. A full window
    // (every ray in flight) leaves only answers to wait for.
    const bool window_open = max_in_flight_ == 0 || outstanding_ < max_in_flight_;
    await_answer_or_room(results.fifo, ray_queue_,
                         (!backlog_.empty() || !vision.done()) && window_open);
  }
  frame_time_ = clock_.now() - frame_start_;
  clock_.sync();
  if (opts_.progress)
    opts_.progress(static_cast<long>(vision_rays_.value()), static_cast<long>(total_vision));
}

}  // namespace rtsim::platform::ullner
