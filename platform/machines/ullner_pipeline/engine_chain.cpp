#include "platform/machines/ullner_pipeline/engine_chain.hpp"

#include <algorithm>
#include <cmath>
#include <span>

#include "common/input_error.hpp"
#include "modules/activations.hpp"
#include "modules/extension_guard.hpp"
#include "modules/sim_time.hpp"
#include "modules/wiring.hpp"
#include "platform/functional/scene_tracer.hpp"

namespace rtsim::platform::ullner_pipeline {

using modules::plus;
using modules::times;
using tasks::RayDescription;

namespace {

// The chain's parameters (pipeline.*), each named once.
const modules::CountParam kEngines(
    {.name = "engines",
     .default_value = "1000",
     .min = "1",
     .max = "1000000",
     .unit = "processors",
     .description = "Polygon processors in the chain (N): one polygon each; spare ones hold dummy "
                    "polygons. Every ray passes all of them",
     .source = "seed 000 L743 (a thousand processors); L751: ten thousand plausible, a million "
               "almost certainly infeasible",
     .affects_image = true});
const modules::TimeParam kIssueInterval(
    {.name = "issue_interval",
     .default_value = "5 us",
     .description = "Time between two ray descriptions a processor accepts: one shift-and-add "
                    "floating-point operation, each operation of the intersection having its own "
                    "unit, pipelined as the peripheral's (Fig. 2-17)",
     .source = "seed 000 L723 and L2084-L2108: about 5 us per operation (24 integer additions of "
               "100-200 ns, shifts at twice that rate, plus a pipelining allowance)"});
const modules::TimeParam kHopLatency(
    {.name = "hop_latency",
     .default_value = "200 ns",
     .description = "From a processor accepting a description to it starting to pass the "
                    "description on: one bit-serial compare-and-select of the carried and the new "
                    "fields. With the link's 4.8 us a hop is 5.0 us",
     .source = "seed 000 L2108 (an integer addition: 100-200 ns); L733, L743: a hop is \"about "
               "five microseconds\""});
const modules::TimeParam kComputeLatency(
    {.name = "compute_latency",
     .default_value = "85 us",
     .description = "From a description's ray fields arriving to the processor's own t, p_r, u, v "
                    "being ready; the result fields trail the ray fields by this along the whole "
                    "chain (each processor compares its t with the carried t, both ready this "
                    "late)",
     .source = "seed 000 L572-L588 (Fig. 2-17: 17 operations deep with one-stage additions) at 5 "
               "us an operation (L723)"});
const modules::ChoiceParam kModel(
    {.name = "model",
     .default_value = "chain",
     .allowed = {"chain", "engines"},
     .description = "How the processors are simulated: chain (each description's arrival at the "
                    "last processor by ChainTiming's formula, one step a description) or engines "
                    "(every processor a module that receives the description as a transaction, "
                    "computes on it and times itself from its own state and its neighbour's "
                    "handshake). Both give every ray the same times and the same image "
                    "(tests/ullner_pipeline_test.cpp); engines also reports fill and drain along "
                    "the chain",
     .source = "model choice (DESIGN.md \"Timing rules\": a closed form only where a test shows "
               "it identical to the structural run)"});
const modules::IntParam kDeadEngine(
    {.name = "fault.dead_engine",
     .default_value = "-1",
     .min = "-1",
     .max = "999999",
     .unit = "processor",
     .description = "A fault: this processor is dead and passes every description on unchanged "
                    "(its polygon is never found); -1 for none",
     .source = "fault model (issue: faults in flight); a dead stage of a systolic chain",
     .affects_image = true});
/// pipeline.model = engines: the longest chain it builds, a module a processor (the load alone
/// is N^2 register writes, about 0.15 us each: 60 s at this length).
constexpr std::uint64_t kMaxEngineModules = 20000;
/// pipeline.model = engines: processors whose busy time is recorded over time, at most
/// (assumption: enough rows for a picture of the chain filling and draining).
constexpr std::uint64_t kWatchedEngines = 24;
/// A processor's class and the links' class, under the chain's path.
constexpr const char* kEngine = "engine";
constexpr const char* kLinkIn = "link_in";
constexpr const char* kLink = "link";

}  // namespace

std::size_t EngineChain::engines(const modules::ModuleParams& pipeline) {
  return pipeline.get(kEngines);
}

std::string EngineChain::engines_name(const modules::ModuleParams& pipeline) {
  return pipeline.path_of(kEngines.name());
}

void EngineChain::declare_params(const modules::ParamDecls& pipeline) {
  pipeline.add(kEngines);
  pipeline.add(kModel);
  pipeline.add(kDeadEngine);
  const modules::ParamDecls engine = pipeline.sub(kEngine);
  for (const auto* p : {&kIssueInterval, &kHopLatency, &kComputeLatency}) engine.add(*p);
  const modules::Link::Defaults bit_serial{
      .latency = "0 s",
      .lanes = "13",
      .bit_rate = "",
      .bit_time = "150 ns",
      .source =
          "seed 000 L729-L733: bit-serial, one wire per value (13 each way plus "
          "handshake); \"about 150 nanoseconds per bit\" (20-200 ns by technology)"};
  // The links between processors and to the host at the far end, and the host's link into the
  // first processor (the same wires by default; apart, a what-if).
  modules::Link::declare_params(pipeline.sub(kLink), bit_serial);
  modules::Link::declare_params(pipeline.sub(kLinkIn), bit_serial);
}

EngineChain::EngineChain(sc_core::sc_module_name name, MachineRun& run)
    : sc_core::sc_module(name),
      input("input", 1),
      load("load"),
      registers(
          "polygon_registers",
          engines(modules::ModuleParams(run.registry(), this->name())) * PolygonDescription::kWords,
          PolygonDescription::kWords, sc_core::SC_ZERO_TIME, sc_core::SC_ZERO_TIME),
      result_out("result_out"),
      registers_port_("registers_port"),
      geometry_(*run.twin().geometry),
      polygons_(run.twin().geometry->shapes.size()),
      counters_(run.frame().counters()),
      probe_(run.probe()),
      inner_link_(modules::child_name(this->name(), kLink),
                  modules::ModuleParams(run.registry(), modules::child_name(this->name(), kLink))),
      link_out_(modules::child_name(this->name(), "link_out"),
                modules::ModuleParams(run.registry(), modules::child_name(this->name(), kLink))),
      timing_(
          [&] {
            const modules::ModuleParams engine(run.registry(),
                                               modules::child_name(this->name(), kEngine));
            return EngineTiming{.issue_interval = engine.get(kIssueInterval),
                                .hop_latency = engine.get(kHopLatency),
                                .compute_latency = engine.get(kComputeLatency)};
          }(),
          inner_link_.serialisation(RayDescription::kWireBits), inner_link_.latency(),
          engines(modules::ModuleParams(run.registry(), this->name()))),
      polygon_time_(inner_link_.serialisation(PolygonDescription::kWireBits)),
      overwrites_(timing_.engines(), 0),
      answers_(timing_.engines(), 0),
      engine_class_(modules::child_name(this->name(), kEngine)) {
  load.register_b_transport(this, &EngineChain::load_transport);
  inner_link_.trace_to(run.trace());
  link_out_.trace_to(run.trace());
  const modules::ModuleParams self(run.registry(), this->name());
  dead_engine_ = self.get(kDeadEngine);
  if (dead_engine_ >= static_cast<std::int64_t>(engines()))
    throw InputError(
        self.path_of(kDeadEngine.name()), 0,
        "the chain has processors 0 to " + std::to_string(engines() - 1) + " (pipeline.engines)");
  if (self.get(kModel) == "engines") {
    if (engines() > kMaxEngineModules)
      throw InputError(self.path_of(kModel.name()), 0,
                       "the engines model makes every processor a module and shifts the load "
                       "through all of them (N^2 register writes: about " +
                           std::to_string(engines() / 1000 * (engines() / 1000) * 15 / 100) +
                           " s here); it takes at most " + std::to_string(kMaxEngineModules) +
                           " processors (" + engines_name(self) +
                           "); pipeline.model=chain gives the same times for any length");
    build_engines();
  }
  registers_port_.bind(registers.socket);
  if (engine_modules_.empty()) {
    // The chain in one module: its parts in the order a ray description meets them, so that
    // `rtsim describe` draws the chain (the engines and their inner links are a class each).
    const std::string n = std::to_string(engines());
    modules::connect(modules::child_name(this->name(), kLinkIn), input.name(), "ray descriptions");
    modules::connect(input.name(), modules::child_name(this->name(), kEngine), "to processor 0");
    modules::connect(modules::child_name(this->name(), kEngine), inner_link_.name(),
                     "processor k to k+1, x " + n);
    modules::connect(inner_link_.name(), link_out_.name(),
                     "from processor " + std::to_string(engines() - 1));
  }
  // A ray meets them in this order (after the host's link in).
  probe_input_ = probe_.stage(input.name());
  probe_engines_ = probe_.stage(modules::child_name(this->name(), kEngine));
  probe_link_out_ = probe_.stage(link_out_.name());
  SC_THREAD(run);
}

std::uint64_t EngineChain::sum(const std::vector<std::uint64_t>& v, std::uint64_t first_n) {
  std::uint64_t total = 0;
  for (std::size_t k = 0; k < v.size() && k < first_n; ++k) total += v[k];
  return total;
}

void EngineChain::load_transport(tlm::tlm_generic_payload& gp, sc_core::sc_time& delay) {
  const auto* ext = gp.get_extension<modules::MessageExtension<PolygonLoad>>();
  const std::uint64_t n = engines();
  if (!ext || !ext->message() || loaded_.value() >= n) {
    gp.set_response_status(tlm::TLM_GENERIC_ERROR_RESPONSE);
    return;
  }
  PolygonLoad& msg = *ext->message();
  // The description is in the first processor's input register. It passes its current polygon
  // on (one polygon time on its link), then accepts the new one; the processor behind it does
  // the same a polygon time (and a link latency) later, and so on, so the polygon that was in
  // the last processor reaches the host N of those after this one arrived. The next
  // description can come in once this one is accepted (the register is free).
  const sc_core::sc_time arrived = modules::sim_now() + delay;
  sc_core::sc_time accepted;
  if (engine_modules_.empty()) {
    // The shortcut: each presentation's wave moves every description one processor on, so
    // after N of them the j-th rests in processor N-1-j and what leaves the chain at the j-th is
    // what processor N-1-j held before the load began. Each line is written where its
    // description comes to rest, with what the lines before it did to it on its way (a faulty
    // register word corrupts every description shifted through it), and at the end every line
    // counts as written N times, as the engines write it (tests/ullner_pipeline_test.cpp shows
    // both give the same registers, statistics and times). The returned words skip the faults
    // of the lines they pass on their way out: only their number is used.
    accepted = plus(arrived, polygon_time_);
    msg.returned_at = plus(arrived, times(plus(polygon_time_, inner_link_.latency()), n));
    const std::uint64_t line = n - 1 - loaded_.value();
    const auto& words = registers.contents();
    std::copy_n(words.begin() + static_cast<std::ptrdiff_t>(line * PolygonDescription::kWords),
                PolygonDescription::kWords, msg.returned.words.begin());
    PolygonDescription resting = msg.presented;
    for (const auto& f : registers.faults())
      if (f.word < line * PolygonDescription::kWords)
        resting.words[f.word % PolygonDescription::kWords] ^= f.xor_mask;
    exchange(line, resting);
    if (loaded_.value() + 1 == n)
      registers.account_writes(0, n * PolygonDescription::kWords, n - 1);
  } else {
    // The wave as transactions: into the first processor, from each to the next, and from the
    // last back to the host.
    LoadWave wave{.description = msg.presented, .at = arrived};
    modules::MessageExtension<LoadWave> wave_ext(&wave, PolygonDescription::kWireBits);
    tlm::tlm_generic_payload wave_gp;
    wave_gp.set_command(tlm::TLM_WRITE_COMMAND);
    wave_gp.set_address(0);
    wave_gp.set_data_ptr(reinterpret_cast<unsigned char*>(wave.description.words.data()));
    wave_gp.set_data_length(PolygonDescription::kWords * 4);
    wave_gp.set_streaming_width(PolygonDescription::kWords * 4);
    wave_gp.set_byte_enable_ptr(nullptr);
    wave_gp.set_extension(&wave_ext);
    const modules::ClearExtensionOnExit<modules::MessageExtension<LoadWave>> clear(wave_gp,
                                                                                   wave_ext);
    sc_core::sc_time none = sc_core::SC_ZERO_TIME;
    (*to_first_load_)->b_transport(wave_gp, none);
    accepted = wave.accepted;
    for (auto& engine : engine_modules_) engine->shift_on(wave_gp);
    msg.returned = wave.description;
    msg.returned_at = wave.at;
  }
  ++loaded_;
  delay = accepted - modules::sim_now();
  gp.set_response_status(tlm::TLM_OK_RESPONSE);
}

void EngineChain::exchange(std::uint64_t line, PolygonDescription& words) {
  PolygonDescription held;
  std::copy_n(
      registers.contents().begin() + static_cast<std::ptrdiff_t>(line * PolygonDescription::kWords),
      PolygonDescription::kWords, held.words.begin());
  sc_core::sc_time unused = sc_core::SC_ZERO_TIME;
  if (!modules::write_words(registers_port_, register_write_, line * PolygonDescription::kWords,
                            words.words.data(), PolygonDescription::kWords, unused))
    SC_REPORT_ERROR("rtsim/ullner-pipeline", "a polygon register write failed");
  words = held;
}

const std::vector<kernels::UllnerQuadParams<double>>& EngineChain::polygons() {
  if (registers.words_written() == decoded_after_) return decoded_;
  const auto& words = registers.contents();
  decoded_.resize(engines());
  identities_.resize(engines());
  for (std::uint64_t k = 0; k < engines(); ++k) {
    kernels::UllnerDescribedPolygon held =
        kernels::read_description(std::span<const std::uint32_t, PolygonDescription::kWords>(
            words.data() + k * PolygonDescription::kWords, PolygonDescription::kWords));
    decoded_[k] = held.params;
    identities_[k] = held.identity;
  }
  decoded_after_ = registers.words_written();
  return decoded_;
}

ullner::RayResult EngineChain::read_answer(const ullner::RayRequest& req, const RayDescription& d) {
  ullner::RayResult res;
  res.request = req;
  // A dummy's identity (or none) is no answer (L719), nor is a point that is not a number (a
  // description corrupted in flight).
  res.found = d.i < polygons_ && std::isfinite(d.t) && std::isfinite(d.u) && std::isfinite(d.v);
  if (!res.found) return res;
  const auto& quad = std::get<kernels::UllnerQuadKernel>(geometry_.shapes[d.i].shape);
  functional::fill_hit(geometry_, d.i, quad.surface_at(d.t, d.u, d.v), res.hit);
  if (req.ray.kind != RayKind::Shadow) ++counters_.hits;
  return res;
}

void EngineChain::build_engines() {
  // Every processor a module; the chain's end sockets at both ends (the host's input register
  // feeds the first, the far end takes what leaves the last).
  const std::uint64_t n = engines();
  const HeldPolygons held{
      .polygon = &decoded_, .identity = &identities_, .overwrites = &overwrites_};
  engine_modules_.reserve(n);
  for (std::uint64_t k = 0; k < n; ++k)
    engine_modules_.push_back(std::make_unique<PolygonEngine>(
        (std::string(kEngine) + std::to_string(k)).c_str(), k, timing_.engine(),
        timing_.description_time(), timing_.link_latency(), held));
  to_first_ = std::make_unique<tlm_utils::simple_initiator_socket<EngineChain>>("to_first");
  far_end_socket_ = std::make_unique<tlm_utils::simple_target_socket<EngineChain>>("far_end");
  to_first_->bind(engine_modules_.front()->in);
  for (std::uint64_t k = 0; k + 1 < n; ++k) {
    engine_modules_[k]->out.bind(engine_modules_[k + 1]->in);
    engine_modules_[k]->set_next(engine_modules_[k + 1].get());
  }
  engine_modules_.back()->out.bind(*far_end_socket_);
  // The load's wave, through the same processors.
  to_first_load_ =
      std::make_unique<tlm_utils::simple_initiator_socket<EngineChain>>("to_first_load");
  load_back_ = std::make_unique<tlm_utils::simple_target_socket<EngineChain>>("load_back");
  to_first_load_->bind(engine_modules_.front()->load_in);
  for (std::uint64_t k = 0; k + 1 < n; ++k)
    engine_modules_[k]->load_out.bind(engine_modules_[k + 1]->load_in);
  engine_modules_.back()->load_out.bind(*load_back_);
  load_back_->register_b_transport(this, &EngineChain::at_host_end);
  for (auto& engine : engine_modules_) engine->hold_registers(this, polygon_time_);
  if (dead_engine_ >= 0) engine_modules_[static_cast<std::size_t>(dead_engine_)]->set_dead(true);
  // Busy over time of a few processors along the chain (a timeline is up to 128 KiB, so not
  // of every one of 10,000): where the chain fills and drains, and where a hold stops it.
  const std::uint64_t watched = std::min<std::uint64_t>(n, kWatchedEngines);
  watched_busy_.resize(watched);
  for (std::uint64_t i = 0; i < watched; ++i) {
    watched_.push_back(watched > 1 ? i * (n - 1) / (watched - 1) : 0);
    engine_modules_[watched_.back()]->watch(&watched_busy_[i]);
  }
  far_end_socket_->register_b_transport(this, &EngineChain::at_host_end);
}

void EngineChain::at_host_end(tlm::tlm_generic_payload& gp, sc_core::sc_time& delay) {
  // What leaves the last processor: a description, whose answer the chain delivers in order
  // (leave), or during the load its previous polygon (LoadWave::at says when it is back).
  (void)delay;
  gp.set_response_status(tlm::TLM_OK_RESPONSE);
}

void EngineChain::set_faults(std::vector<DescriptionFault> faults) {
  std::stable_sort(
      faults.begin(), faults.end(),
      [](const DescriptionFault& a, const DescriptionFault& b) { return a.engine < b.engine; });
  faults_ = std::move(faults);
  for (DescriptionFault& f : faults_)
    if (!engine_modules_.empty()) engine_modules_[f.engine]->add_fault(f);
}

std::optional<sc_core::sc_time> EngineChain::ResultSlots::slot_free(std::uint64_t j) const {
  if (!results || j < results->capacity()) return sc_core::SC_ZERO_TIME;
  return results->taken_at(j - results->capacity());
}

sc_core::sc_time EngineChain::far_end_held() const {
  return engine_modules_.empty() ? timing_.far_end_held() : engine_modules_.back()->far_end_held();
}

bool EngineChain::can_accept() const {
  if (engine_modules_.empty()) return timing_.can_accept();
  // The first processor knows when it passed the last description on once that one is in the
  // second processor (or has left).
  return in_chain_.empty() || in_chain_.back().started || in_chain_.back().at >= 1;
}

void EngineChain::through_processors(DescriptionInFlight& msg) {
  // The description passes every processor in chain order, each writing the identity its
  // registers hold when it overwrites (L713, L717).
  const auto& held = polygons();
  const std::uint64_t n = engines();
  // Up to the next processor with a fault on its input, or the dead one, the description and
  // the ray's set-up are locals (no aliasing to reload) and no processor is checked.
  const auto dead = static_cast<std::uint64_t>(dead_engine_);  // -1: none
  std::uint64_t k = 0;
  std::size_t fault = 0;
  for (;;) {
    std::uint64_t stop = fault < faults_.size() ? faults_[fault].engine : n;
    if (dead >= k && dead < stop) stop = dead;
    RayDescription d = msg.description;
    const kernels::UllnerRay<double> ray = msg.ray;
    std::uint64_t last_writer = msg.last_writer;
    for (; k < stop; ++k)
      if (tasks::pass_ray_description(d, ray, held[k], identities_[k])) {
        ++overwrites_[k];
        last_writer = k;
      }
    msg.description = d;
    msg.last_writer = last_writer;
    if (k == n) break;
    // Processor k: the faults on its input; then it tests (the next run starts with it) unless
    // it is dead and passes the description on unchanged.
    for (; fault < faults_.size() && faults_[fault].engine == k; ++fault) faults_[fault].apply(msg);
    if (k == dead) ++k;
  }
}

void EngineChain::accept_next() {
  const EngineTiming& engine = timing_.engine();
  // The first processor accepts the description once it has arrived, its previous one is an
  // issue interval in and it has started passing that one on: that frees its input register
  // for the host.
  const sc_core::sc_time bound =
      engine_modules_.empty() ? timing_.accept_bound() : engine_modules_.front()->accept_bound();
  const sc_core::sc_time arrived = *input.fifo.next_item_time();
  sc_core::sc_time accepted;
  const ullner::RayRequest req = input.fifo.get(bound, accepted);
  // Was the pipe kept full (L743)? The host kept it full when the next description was waiting
  // as the processor became free; the processor waited for the chain ahead when it could not
  // take the next one an issue interval after the last.
  if (entered_ > 0) {
    if (arrived > bound) {
      host_starved_ += arrived - bound;
    } else {
      ++kept_full_;
    }
    const sc_core::sc_time issue = plus(last_entered_, engine.issue_interval);
    if (accepted > std::max(arrived, issue)) chain_held_ += accepted - std::max(arrived, issue);
  }
  last_entered_ = accepted;
  engine_busy_.record(accepted, engine.issue_interval);
  ++descriptions_;
  ++entered_;

  // The host injects (r0, r1) with t at the ray's far limit: infinity for vision rays (L704),
  // the light's distance for shadow rays, so only an occluder before the light answers.
  InChain& d = in_chain_.emplace_back();
  d.request = req;
  d.accepted = accepted;
  d.msg.description.r0 = req.ray.ray.origin;
  d.msg.description.r1_minus_r0 = req.ray.ray.direction;
  d.msg.description.t = req.ray.t_max;
  d.msg.ray = kernels::UllnerRay<double>::make(d.msg.description.r0, d.msg.description.r1_minus_r0);
  d.msg.at = accepted;
  if (engine_modules_.empty()) {
    // The data through every processor now; the times when the formulas allow (chain_timing).
    through_processors(d.msg);
    timing_.accept(accepted);
    return;
  }
  // As a transaction into the first processor's register (accepted there at `accepted`); it
  // moves on in advance().
  d.ext = modules::MessageExtension<DescriptionInFlight>(&d.msg, RayDescription::kWireBits);
  d.gp.set_command(tlm::TLM_WRITE_COMMAND);
  d.gp.set_address(0);
  d.gp.set_data_ptr(reinterpret_cast<unsigned char*>(&d.msg.description));
  d.gp.set_data_length(sizeof(d.msg.description));
  d.gp.set_streaming_width(sizeof(d.msg.description));
  d.gp.set_byte_enable_ptr(nullptr);
  d.gp.set_extension(&d.ext);
  polygons();  // the processors' registers decoded, as the load left them
  sc_core::sc_time none = sc_core::SC_ZERO_TIME;
  (*to_first_)->b_transport(d.gp, none);
}

bool EngineChain::move(std::size_t i) {
  InChain& d = in_chain_[i];
  const InChain* ahead = i > 0 ? &in_chain_[i - 1] : nullptr;
  const std::uint64_t n = engines();
  PolygonEngine& here = *engine_modules_[d.at];
  if (!d.started) {
    if (d.at + 1 == n) {
      // The last: its link starts once a slot of the host's result queue is free.
      if (ahead) return false;
      const auto room = far_end_.slot_free(entered_ - in_chain_.size() + i);
      if (!room) return false;
      here.set_far_end_room(*room);
    } else if (ahead && ahead->at < d.at + 1) {
      return false;  // the next processor has not yet accepted the one ahead: no handshake
    }
    here.start(d.gp);
    d.started = true;
    return true;
  }
  if (d.at + 1 == n) {
    here.hand_on(d.gp);  // to the far end
    leave(d.msg.at);
    return true;
  }
  // Into the next processor once it has started passing on the one ahead.
  if (ahead && (ahead->at < d.at + 1 || (ahead->at == d.at + 1 && !ahead->started))) return false;
  here.hand_on(d.gp);
  ++d.at;
  d.started = false;
  return true;
}

void EngineChain::advance() {
  if (engine_modules_.empty()) {
    while (const auto start = timing_.next_leaving(far_end_)) leave(*start);
    return;
  }
  // Oldest first, each as far as the one ahead allows; the oldest leaves when the host's end
  // has room. A description leaving or moving can let the ones behind it move.
  bool moved = true;
  while (moved) {
    moved = false;
    for (std::size_t i = 0; i < in_chain_.size();) {
      const std::size_t before = in_chain_.size();
      if (!move(i)) {
        ++i;
        continue;
      }
      moved = true;
      if (in_chain_.size() != before) i = 0;  // the oldest left
    }
  }
}

void EngineChain::leave(const sc_core::sc_time& start) {
  InChain& d = in_chain_.front();
  counters_.intersection_tests += engines();
  if (d.msg.last_writer < engines()) ++answers_[d.msg.last_writer];
  // Its ray fields leave the last processor when its link starts; its result fields trail them
  // by the compute latency (chain_timing.hpp), and the complete description crosses the last
  // link to the host.
  const sc_core::sc_time leaves = plus(start, timing_.engine().compute_latency);
  // The first inner link counts every description in order, from when the first processor
  // handed it over (the N - 1 links after it carry the same, links_ and bits_all_links_).
  if (engines() > 1) {
    const sc_core::sc_time handed =
        engine_modules_.empty() ? timing_.take_first_handed() : d.msg.first_handed;
    inner_link_.transfer(RayDescription::kWireBits, handed, handed,
                         {"description", "ray", d.request.id});
  }
  ullner::RayResult res = read_answer(d.request, d.msg.description);
  res.service_start = d.accepted;
  res.answered = leaves;
  res.arrived = link_out_.transfer(RayDescription::kWireBits, leaves, leaves,
                                   {"result", "ray", d.request.id});
  transit_total_ += leaves - d.accepted;
  using modules::LatencyPart;
  probe_.add(d.request.journey, probe_input_, LatencyPart::kQueueing,
             d.accepted - d.request.arrived);
  probe_.add(d.request.journey, probe_engines_, LatencyPart::kService, leaves - d.accepted);
  probe_.add(d.request.journey, probe_link_out_, LatencyPart::kTransfer, res.arrived - leaves);
  in_chain_.pop_front();
  // A result slot is free by now (the far end's handshake), so this never waits.
  modules::send_message(result_out, res, res.arrived, RayDescription::kWireBits);
}

void EngineChain::run() {
  for (;;) {
    advance();
    if (can_accept() && !input.fifo.empty()) {
      accept_next();
      continue;
    }
    if (in_chain_.empty()) {
      modules::wait_for_item(input.fifo, clock_);
      continue;
    }
    // Descriptions wait for the host to take answers (a slot at the far end), or the first
    // processor for the next description.
    modules::sim_wait(input.fifo.put_event() | far_end_.results->get_event());
  }
}

}  // namespace rtsim::platform::ullner_pipeline
