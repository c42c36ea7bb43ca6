#include "platform/machines/wang_bezier/bezier_host.hpp"

#include <array>
#include <bit>

#include "platform/functional/scene_tracer.hpp"

namespace rtsim::platform::wang_bezier {

namespace {
/// The slab test of a ray against a patch's box: 6 subtractions, 6 multiplications by the
/// inverse direction, 10 comparisons.
constexpr Cost kCullCost{.fp_add = 6 + 10, .fp_mul = 6, .mem_words = 6, .instructions = 4};
/// Formatting a job: its words written, a few instructions.
constexpr Cost kJobCost{.mem_words = PatchJob::kWireBits / 32, .instructions = 8};
/// Taking an answer: its words read.
constexpr Cost kAnswerCost{.mem_words = JobResult::kWireBits / 32, .instructions = 4};
/// Words of one control net: 16 points x 3 singles.
constexpr std::size_t kNetWords = 48;

std::size_t count_patches(const functional::SceneGeometry& g) {
  std::size_t n = 0;
  for (const auto& s : g.shapes) n += std::holds_alternative<functional::PatchShape>(s.shape);
  return n;
}
}  // namespace

namespace {
const modules::CountParam kRaysInFlight(
    {.name = "rays_in_flight",
     .default_value = "4096",
     .min = "1",
     .max = "1000000",
     .unit = "rays",
     .description = "Rays the host keeps in flight (their jobs in the pipeline or waiting for it)",
     .source = "assumption: enough to keep the pipeline's 56 jobs in flight busy"});
}  // namespace

void BezierHost::declare_params(const modules::ParamDecls& host) {
  modules::declare_processor_params(
      host, {.clock = "350 MHz",
             .fp_add = 1,
             .fp_mul = 1,
             .fp_div = 20,
             .fp_sqrt = 30,
             .mem_word = 1,
             .instruction = 1,
             .source = "assumption: the paper gives no host (note 002 §4); the 350 MHz "
                       "Pentium II on which it timed the blocks (seed 002 L274)"});
  host.add(kRaysInFlight);
}

BezierHost::BezierHost(sc_core::sc_module_name name, MachineRun& run,
                       const modules::TimedFifo<PatchJob>& pipeline_input, ReferenceCheck* check)
    : modules::Processor(name, run.trace()),
      job_out("job_out"),
      results("result_queue", modules::TimedFifo<JobResult>::kUnbounded),
      patch_memory("patch_memory",
                   std::max<std::size_t>(1, count_patches(*run.twin().geometry)) * kNetWords,
                   kNetWords, sc_core::SC_ZERO_TIME, sc_core::SC_ZERO_TIME),
      scene_(run.scene()),
      frame_(run.frame()),
      pipeline_input_(pipeline_input),
      geometry_(*run.twin().geometry),
      opts_(run.options()),
      probe_(run.probe()),
      // Named in the order a ray meets them.
      probe_host_(probe_.stage(this->name())),
      probe_input_(probe_.stage(pipeline_input.name())),
      probe_pipeline_(
          probe_.stage(pipeline_input.name().substr(0, pipeline_input.name().rfind('.')))),
      probe_results_(probe_.stage(results.name())),
      check_(check),
      shade_(run.scene(), run.twin().settings.shade),
      window_(modules::ModuleParams(run.registry(), this->name()).get(kRaysInFlight)),
      memory_port_("memory_port") {
  memory_port_.bind(patch_memory.socket);
  set_timing(modules::read_processor_timing(modules::ModuleParams(run.registry(), this->name())));
  for (std::uint32_t s = 0; s < geometry_.shapes.size(); ++s)
    if (std::holds_alternative<functional::PatchShape>(geometry_.shapes[s].shape))
      patch_slots_.push_back(s);
  SC_THREAD(run);
}

void BezierHost::load_patches() {
  std::array<std::uint32_t, kNetWords> words{};
  sc_core::sc_time unused = sc_core::SC_ZERO_TIME;
  for (std::size_t k = 0; k < patch_slots_.size(); ++k) {
    const auto& net =
        std::get<functional::PatchShape>(geometry_.shapes[patch_slots_[k]].shape).kernel->net();
    for (int a = 0; a < 4; ++a)
      for (int b = 0; b < 4; ++b)
        for (int c = 0; c < 3; ++c)
          words[static_cast<std::size_t>((a * 4 + b) * 3 + c)] =
              std::bit_cast<std::uint32_t>(net.p[a][b][c]);
    modules::write_words(memory_port_, k * kNetWords, words.data(), kNetWords, unused);
  }
}

const kernels::ControlNet<float>& BezierHost::net_of(std::size_t k) {
  if (patch_memory.words_written() != decoded_after_) {
    const auto& words = patch_memory.contents();
    nets_.resize(patch_slots_.size());
    for (std::size_t i = 0; i < patch_slots_.size(); ++i)
      for (int a = 0; a < 4; ++a)
        for (int b = 0; b < 4; ++b)
          for (int c = 0; c < 3; ++c)
            nets_[i].p[a][b][c] = std::bit_cast<float>(
                words[i * kNetWords + static_cast<std::size_t>((a * 4 + b) * 3 + c)]);
    decoded_after_ = patch_memory.words_written();
  }
  return nets_[k];
}

void BezierHost::start(const shading::TracedRay& r, bool first_sample) {
  const std::uint64_t id = next_id_++;
  RayState& st = rays_[id];
  st.ray = r;
  st.first_sample = first_sample;
  st.started = clock_.now();
  in_flight_peak_.note(rays_.size());
  const double t_min = shade_.t_min(r);
  Cost cost;
  for (std::size_t k = 0; k < patch_slots_.size(); ++k) {
    const std::uint32_t slot = patch_slots_[k];
    const auto& kernel = *std::get<functional::PatchShape>(geometry_.shapes[slot].shape).kernel;
    cost += kCullCost;
    const auto entry = kernel.entry(r.ray, t_min, r.t_max);
    if (!entry) {
      ++culled_;
      continue;
    }
    PatchJob job;
    job.ray = id;
    job.slot = slot;
    job.o = *entry;
    job.d = Vec3T<float>(r.ray.direction);
    job.net = net_of(k);  // the control points as the host's memory holds them
    pending_.push_back(job);
    ++st.outstanding;
  }
  hop("ray", id);
  compute(cost, "cull", {{"ray", id}});
  st.culled = clock_.now();
  if (st.outstanding == 0) answer(id);
}

void BezierHost::answer(std::uint64_t id) {
  RayState st = std::move(rays_.at(id));
  rays_.erase(id);
  const shading::TracedRay& r = st.ray;
  const double t_min = shade_.t_min(r);
  const bool shadow = r.kind == RayKind::Shadow;
  if (check_) check_->ray(r.ray, t_min, r.t_max, st.first_sample, st.answers);
  TraceCounters& counters = frame_.counters();
  Cost cost;  // the host's own tests of the other primitives, then the shading
  // In slot order, each shape with the nearest found so far as its limit: the twin's search.
  double best = r.t_max;
  bool found = false;
  Hit hit;
  SurfaceHit s;
  for (std::uint32_t slot = 0; slot < geometry_.shapes.size() && !(shadow && found); ++slot) {
    bool here = false;
    if (const auto* p = std::get_if<functional::PatchShape>(&geometry_.shapes[slot].shape)) {
      const auto a = st.answers.find(slot);
      if (a != st.answers.end()) {
        ++counters.intersection_tests;
        here = p->kernel->finish(a->second, r.ray, t_min, best, s);
      }
    } else {
      cost += std::visit([](const auto& k) { return std::decay_t<decltype(k)>::kTestCost; },
                         geometry_.shapes[slot].shape);
      here = functional::test_shape(geometry_, slot, r.ray, t_min, best, s, counters);
    }
    if (!here) continue;
    found = true;
    best = s.t;
    functional::fill_hit(geometry_, slot, s, hit);
  }
  counters.count_ray(r.kind);
  if (found && !shadow) ++counters.hits;
  if (st.first_sample) frame_.record_primary(r.pixel, found, hit);
  const Cost shading = shade_.on_result(r, found, hit, frame_.fb(), spawned_);
  counters.cost += shading;
  cost += shading;
  hop("ray", id);
  compute(cost, "answer", {{"ray", id}, {"spawned", spawned_.size()}});
  latency_.add(clock_.now() - st.started);
  probe_ray(st);
  for (const auto& sp : spawned_) backlog_.push_back(sp);
}

void BezierHost::probe_ray(const RayState& st) {
  if (!probe_.enabled()) return;
  using modules::LatencyPart;
  const sc_core::sc_time now = clock_.now();
  const auto j = probe_.begin(st.started);
  if (st.answers.empty()) {  // every pair culled: the host alone
    probe_.add(j, probe_host_, LatencyPart::kService, now - st.started);
  } else {
    // The host culls, then its last job waits among the others for the pipeline's input,
    // until the host spends kJobCost issuing it.
    const sc_core::sc_time issue = timing().time_for(kJobCost);
    probe_.add(j, probe_host_, LatencyPart::kService, st.culled - st.started);
    probe_.add(j, probe_host_, LatencyPart::kQueueing, st.last.sent - issue - st.culled);
    probe_.add(j, probe_host_, LatencyPart::kService, issue);
    probe_.add(j, probe_input_, LatencyPart::kQueueing, st.last.accepted - st.last.sent);
    probe_.add(j, probe_pipeline_, LatencyPart::kService, st.last.left - st.last.accepted);
    probe_.add(j, probe_results_, LatencyPart::kQueueing, st.last_taken - st.last.left);
    probe_.add(j, probe_host_, LatencyPart::kService, now - st.last_taken);
  }
  probe_.end(j, now);
}

void BezierHost::run() {
  load_patches();
  const shading::PinholeCamera camera(scene_.camera, frame_.width(), frame_.height());
  tasks::VisionRayTask vision(camera, frame_.width(), frame_.height(), frame_.spp(),
                              frame_.detailed_rows());
  const std::uint64_t total = vision.remaining();
  std::uint64_t started = 0;
  for (;;) {
    const sc_core::sc_time now = clock_.now();
    if (results.fifo.has_item_by(now)) {
      sc_core::sc_time taken;
      JobResult res = results.fifo.get(now, taken);
      clock_.catch_up(taken);
      compute(kAnswerCost, "take");
      job_latency_.add(taken - res.sent);
      RayState& st = rays_.at(res.ray);
      st.answers[res.slot] = res.result;
      st.last = res;
      st.last_taken = taken;
      if (--st.outstanding == 0) answer(res.ray);
      continue;
    }
    if (!pending_.empty() && pipeline_input_.has_room_by(now)) {
      PatchJob job = pending_.front();
      pending_.pop_front();
      hop("ray", job.ray);
      compute(kJobCost, "job", {{"ray", job.ray}});
      job.sent = clock_.now();
      job.arrived = job.sent;
      ++jobs_;
      modules::send_message(job_out, job, job.arrived, PatchJob::kWireBits);
      continue;
    }
    if (pending_.empty() && rays_.size() < window_) {
      if (!backlog_.empty()) {
        const shading::TracedRay r = backlog_.front();
        backlog_.pop_front();
        start(r, false);
        continue;
      }
      if (!vision.done()) {
        int sample = 0;
        const shading::TracedRay r = vision.next(sample);
        compute(tasks::VisionRayTask::kCost, "vision ray", {{"pixel", r.pixel}});
        start(r, sample == 0);
        if (opts_.progress && (++started & 1023) == 0)
          opts_.progress(static_cast<long>(started), static_cast<long>(total));
        continue;
      }
    }
    if (rays_.empty() && backlog_.empty() && vision.done() && pending_.empty()) break;
    // Wait for an answer, or for room in the pipeline's input when a job is waiting.
    await_answer_or_room(results.fifo, pipeline_input_, !pending_.empty());
  }
  frame_time_ = clock_.now();
  clock_.sync();
  if (opts_.progress) opts_.progress(static_cast<long>(started), static_cast<long>(total));
}

}  // namespace rtsim::platform::wang_bezier
