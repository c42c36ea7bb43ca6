#include "platform/machines/ullner_hidden_line/hidden_line_pipe.hpp"

#include <algorithm>
#include <string>
#include <utility>
#include <variant>

#include "modules/wiring.hpp"
#include "platform/machines/machine_run.hpp"

namespace rtsim::platform::ullner_hidden_line {

namespace {

using hiddenline::Message;

const modules::CountParam kWordBits(
    {.name = "word_bits",
     .default_value = "16",
     .min = "4",
     .max = "64",
     .unit = "bits",
     .description = "bits of a number on the links (a segment has six, an intersection two, a "
                    "plane four): the messages' lengths. The coordinates the processors compute "
                    "with are the screen's 16-bit integers whatever this is",
     .source = "seed 000 L1906: \"if 16-bit numbers were used\""});
const modules::CountParam kPlaneProcessors(
    {.name = "plane_processors",
     .default_value = "0",
     .min = "0",
     .max = "50000",
     .unit = "processors",
     .description = "plane processors in the pipe: 0, as many as the scene's boundary planes; "
                    "more, and the rest are idle, passing every message on (a built machine "
                    "has a fixed length); fewer than the scene needs is refused",
     .source = "seed 000 L1914: 10,000 plane processors, a thousand chips of ten"});
const modules::CountParam kTrailing(
    {.name = "trailing_cleanups",
     .default_value = "4",
     .min = "0",
     .max = "1000",
     .unit = "processors",
     .description = "cleanup processors at the pipe's end after the last polygon's, catching "
                    "hidden parts and segments sent on before they were sorted or found hidden",
     .source = "assumption: the seed asks for \"a string of cleanup processors\" (L1799) and "
               "gives no number; the divider unites what debris is left, so the drawing does "
               "not depend on it"});
const modules::TimeParam kMultiplicationTime(
    {.name = "multiplication_time",
     .default_value = "4 us",
     .description = "time of one serial multiplication of two numbers",
     .source = "seed 000 L1908: \"if multiplication were twice as fast as communication\" "
               "(a message 8 us), the estimate the seed calls reasonable"});
const modules::CountParam kPlaneMultipliers(
    {.name = "multipliers",
     .default_value = "3",
     .min = "1",
     .max = "6",
     .unit = "multipliers",
     .description = "serial multipliers of a plane processor: a segment's six multiplications "
                    "take 6 / multipliers rounds, a comparison's two 2 / multipliers",
     .source = "seed 000 L1908-L1910: three multipliers"});
const modules::CountParam kCleanupMultipliers(
    {.name = "multipliers",
     .default_value = "2",
     .min = "1",
     .max = "4",
     .unit = "multipliers",
     .description = "serial multipliers of a cleanup processor: a comparison (a cross "
                    "multiplication, two multiplications) takes 2 / multipliers rounds",
     .source = "seed 000 L1912: \"two multipliers are needed to form the cross product\""});
constexpr const char* kLink = "link";
constexpr const char* kPlaneLink = "plane_link";

StageTiming class_timing(const params::ParamRegistry& r, const char* cls,
                         const modules::CountParam& multipliers, const modules::Link& link) {
  const modules::ModuleParams p(r, cls);
  return {.multiplication_time = p.get(kMultiplicationTime),
          .multipliers = p.get(multipliers),
          .bit_time = link.bit_time(),
          .lanes = link.lanes(),
          .word_bits = HiddenLinePipe::word_bits(r),
          .link_latency = link.latency()};
}

}  // namespace

void HiddenLinePipe::declare_params(const modules::ParamDecls& machine) {
  const modules::ParamDecls pipe = machine.sub(kName);
  pipe.add(kWordBits);
  pipe.add(kPlaneProcessors);
  pipe.affecting_image().add(kTrailing);
  modules::Link::declare_params(pipe.sub(kLink),
                                {.latency = "0 s",
                                 .lanes = "6",
                                 .bit_time = "500 ns",
                                 .source = "seed 000 L1906: six wires shared by the segment and "
                                           "intersection messages, 500 ns a bit"});
  modules::Link::declare_params(pipe.sub(kPlaneLink),
                                {.latency = "0 s",
                                 .lanes = "5",
                                 .bit_time = "500 ns",
                                 .source = "seed 000 L1906: five wires for the polygon (plane) "
                                           "messages, in parallel with the others"});
  const modules::ParamDecls pp = machine.sub(kPlaneClass);
  pp.add(kMultiplicationTime);
  pp.add(kPlaneMultipliers);
  const modules::ParamDecls cp = machine.sub(kCleanupClass);
  cp.add(kMultiplicationTime);
  cp.add(kCleanupMultipliers);
  DividerNode::declare_params(machine.sub(DividerNode::kName));
}

std::size_t HiddenLinePipe::plane_processors(const params::ParamRegistry& r) {
  return modules::ModuleParams(r, kName).get(kPlaneProcessors);
}

std::size_t HiddenLinePipe::trailing_cleanups(const params::ParamRegistry& r) {
  return modules::ModuleParams(r, kName).get(kTrailing);
}

std::uint64_t HiddenLinePipe::word_bits(const params::ParamRegistry& r) {
  return modules::ModuleParams(r, kName).get(kWordBits);
}

HiddenLinePipe::HiddenLinePipe(sc_core::sc_module_name name, MachineRun& run, PipeLayout layout,
                               std::vector<IntersectionFault> faults)
    : sc_core::sc_module(name),
      modules::StatGroup(this->name()),
      probe_(run.probe()),
      word_bits_(word_bits(run.registry())),
      link_out_(modules::child_name(this->name(), "link_out"),
                modules::ModuleParams(run.registry(), modules::child_name(this->name(), kLink))),
      divider_(DividerNode::kName, run.registry()),
      faults_(std::move(faults)) {
  link_out_.trace_to(run.trace());
  const StageTiming pp = class_timing(run.registry(), kPlaneClass, kPlaneMultipliers, link_out_);
  const StageTiming cp =
      class_timing(run.registry(), kCleanupClass, kCleanupMultipliers, link_out_);
  LinkWatch& watch = *this;
  // Every processor's state first, in one array that does not move, then the modules.
  states_.reserve(std::max<std::size_t>(
      layout.polygons.size() + layout.idle_plane_processors + layout.trailing_cleanups, 1));
  const auto add = [&](const char* cls, std::optional<hiddenline::Stage> firmware,
                       const StageTiming& timing) {
    const std::string n = cls + std::to_string(stages_.size());
    states_.emplace_back();
    states_.back().firmware = std::move(firmware);
    stages_.push_back(
        std::make_unique<PipeStage>(n.c_str(), stages_.size(), states_.back(), timing, watch));
  };
  for (hiddenline::Stage& stage : layout.polygons) {
    const bool plane = std::holds_alternative<hiddenline::PlaneProcessor>(stage);
    add(plane ? kPlaneClass : kCleanupClass, std::move(stage), plane ? pp : cp);
    plane_processors_ += plane ? 1 : 0;
  }
  for (std::size_t k = 0; k < layout.idle_plane_processors; ++k) {
    add(kPlaneClass, std::nullopt, pp);
    ++plane_processors_;
  }
  for (std::size_t k = 0; k < layout.trailing_cleanups; ++k)
    add(kCleanupClass, hiddenline::Stage(hiddenline::CleanupProcessor()), cp);
  if (stages_.empty()) add(kPlaneClass, std::nullopt, pp);  // a pipe of one idle processor
  for (std::size_t k = 0; k + 1 < stages_.size(); ++k) {
    stages_[k]->out.bind(stages_[k + 1]->in);
    stages_[k]->set_next(&stages_[k + 1]->register_free());
  }
  stages_.back()->out.bind(divider_.in);
  stages_.back()->set_next(&divider_.register_free());
  // `rtsim describe` draws the pipe as its classes.
  modules::connect(modules::child_name(this->name(), "pp*"),
                   modules::child_name(this->name(), "cp*"), "segments and intersections");
  modules::connect(modules::child_name(this->name(), "cp*"),
                   modules::child_name(this->name(), "pp*"), "segments and intersections");
  modules::connect(modules::child_name(this->name(), "cp*"), link_out_.name(),
                   "the pipe's output stream");
  modules::connect(link_out_.name(), divider_.name(), "the pipe's output stream");
}

void HiddenLinePipe::drain() {
  stack_.clear();
  if (stages_.front()->pending()) stack_.push_back(0);
  while (!stack_.empty()) {
    const std::size_t k = stack_.back();
    PipeStage& stage = *stages_[k];
    if (!stage.pending()) {
      stack_.pop_back();
      continue;
    }
    stage.send_next();
    if (k + 1 < stages_.size() && stages_[k + 1]->pending()) stack_.push_back(k + 1);
  }
}

void HiddenLinePipe::accepted(std::size_t index, const Message& m, const sc_core::sc_time& arrived,
                              const sc_core::sc_time& accepted) {
  if (!journeys_ || m.kind != Message::Kind::kSegment) return;
  const std::uint32_t e = m.segment.edge;
  if (e >= journeys_->size()) return;
  probe_.add((*journeys_)[e], stages_[index]->is_plane() ? probe_pp_ : probe_cp_,
             modules::LatencyPart::kQueueing, accepted - arrived);
  seg_accepted_[e] = accepted;
}

void HiddenLinePipe::handed(std::size_t index, MessageInFlight& f, const sc_core::sc_time& ready,
                            const sc_core::sc_time& start) {
  const bool last = index + 1 == stages_.size();
  if (f.message.kind == Message::Kind::kIntersection) {
    if (last) {
      for (IntersectionFault& fault : faults_)
        if (fault.index == out_intersections_) {
          f.message.intersection.t.n ^= fault.xor_mask;
          fault.applied = true;
        }
      ++out_intersections_;
    }
  }
  if (last) {
    // The last link is a kit Link: its statistics and traces are the pipe's output stream's.
    (void)link_out_.transfer(
        message_bit_times(f.message, link_out_.lanes(), word_bits_) * link_out_.lanes(), start);
  }
  if (!journeys_ || f.message.kind != Message::Kind::kSegment) return;
  const std::uint32_t e = f.message.segment.edge;
  if (e >= journeys_->size()) return;
  const bool plane = stages_[index]->is_plane();
  const modules::LatencyProbe::Journey j = (*journeys_)[e];
  // Held (a cleanup processor keeps a segment until it is done with it) and worked on, then
  // waiting for the link or the next register, then on the link.
  probe_.add(j, plane ? probe_pp_ : probe_cp_, modules::LatencyPart::kService,
             ready - seg_accepted_[e]);
  probe_.add(j, plane ? probe_pp_ : probe_cp_, modules::LatencyPart::kQueueing, start - ready);
  probe_.add(j, plane ? probe_pp_link_ : probe_cp_link_, modules::LatencyPart::kTransfer,
             f.at - start);
}

void HiddenLinePipe::follow(std::vector<modules::LatencyProbe::Journey>* journeys, int pp_stage,
                            int pp_link, int cp_stage, int cp_link) {
  journeys_ = journeys;
  seg_accepted_.assign(journeys->size(), sc_core::SC_ZERO_TIME);
  probe_pp_ = pp_stage;
  probe_pp_link_ = pp_link;
  probe_cp_ = cp_stage;
  probe_cp_link_ = cp_link;
}

void HiddenLinePipe::end_journeys() {
  if (!journeys_) return;
  std::vector<bool> arrived(journeys_->size(), false);
  for (const auto& [edge, at] : divider_.segment_arrivals()) {
    if (edge >= journeys_->size() || arrived[edge]) continue;
    arrived[edge] = true;
    probe_.end((*journeys_)[edge], at);
  }
  for (std::size_t e = 0; e < journeys_->size(); ++e)
    if (!arrived[e]) probe_.drop((*journeys_)[e]);
}

void HiddenLinePipe::account() {
  // What one processor handed on is what the next received (the last's, what the divider did).
  messages_ += divider_.received().size();
  for (const StageState& s : states_) {
    if (&s != &states_.front()) messages_ += s.inputs;
    intersections_ += s.intersections_out;
    link_busy_ += s.link_busy;
    waited_ += s.waited;
    if (!s.firmware) continue;
    if (const auto* p = std::get_if<hiddenline::PlaneProcessor>(&*s.firmware)) {
      multiplications_ += p->multiplications();
      redundant_ += p->redundant();
    } else {
      const auto& c = std::get<hiddenline::CleanupProcessor>(*s.firmware);
      comparisons_ += c.comparisons();
      suppressed_ += c.suppressed();
      merged_ += c.merged();
      dropped_ += c.dropped();
    }
  }
}

}  // namespace rtsim::platform::ullner_hidden_line
