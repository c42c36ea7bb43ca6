#include "platform/machines/ullner_scanline_tree/merging_node.hpp"

#include "platform/machines/machine_run.hpp"

namespace rtsim::platform::ullner_scanline_tree {

namespace {
const modules::TimeParam kStageTime(
    {.name = "stage_time",
     .default_value = "3 us",
     .description = "time of one of Fig. 3-22's five stages (a pass takes 1, 2 or 5 of them)",
     .source = "seed 000 L1519: \"about three microseconds per stage\" (Lyon's serial circuits "
               "at 12 MHz, slower dividers)"});
const modules::CountParam kQueueDepth(
    {.name = "queue_depth",
     .default_value = "2",
     .min = "1",
     .max = "4096",
     .unit = "segments",
     .description = "segments each input queue holds (the one being merged not counted)",
     .source = "assumption: \"short queues on the inputs and outputs of merging processors can "
               "help to smooth over these irregularities\" (seed 000 L1519); two"});
constexpr const char* kLink = "link";

std::vector<std::string> case_names() {
  std::vector<std::string> names;
  for (const auto n : scanline::kMergeCaseNames) names.emplace_back(n);
  return names;
}
}  // namespace

void MergingNode::declare_params(const modules::ParamDecls& mp) {
  mp.add(kStageTime);
  mp.add(kQueueDepth);
  modules::Link::declare_params(
      mp.sub(kLink), {.latency = "0 s",
                      .lanes = "11",
                      .bit_time = "150 ns",
                      .source = "assumption: the scan converters' links (seed 000 L1348), bit-"
                                "serial between all the tree's processors (L1459)"});
}

std::size_t MergingNode::queue_depth(const params::ParamRegistry& registry) {
  return modules::ModuleParams(registry, kClass).get(kQueueDepth);
}

MergingNode::MergingNode(sc_core::sc_module_name name, MachineRun& run,
                         const modules::TimedFifo<SegmentMessage>& parent,
                         const ProbeStages& stages)
    : modules::Processor(name, run.trace()),
      in0("in0", queue_depth(run.registry())),
      in1("in1", queue_depth(run.registry())),
      out("out"),
      link(std::string(this->name()) + "." + kLink,
           modules::ModuleParams(run.registry(), kClass).sub(kLink)),
      params_(run.registry(), kClass),
      parent_(parent),
      stage_time_(params_.get(kStageTime)),
      probe_(run.probe()),
      stages_(stages),
      passes_(*this, "passes", case_names(), "passes of the six-step algorithm by case") {
  SC_THREAD(run);
}

void MergingNode::run() {
  modules::MessageQueue<SegmentMessage>* in[2] = {&in0, &in1};
  // A frame's streams end with the dummies; the next frame's follow.
  for (;;) {
    if (mp_.finished()) {
      clock_.sync();
      mp_ = scanline::MergingProcessor{};
    }
    for (int k = 0; k < 2; ++k) {
      if (!mp_.needs(k)) continue;
      auto& fifo = in[k]->fifo;
      const sc_core::sc_time since = clock_.now();
      modules::wait_for_item(fifo, clock_);
      sc_core::sc_time taken;
      const SegmentMessage m = fifo.get(clock_.now(), taken);
      clock_.catch_up(taken);
      waited_since(since, Wait::kData);
      probe_.add(m.segment.journey, stages_.mp_in, modules::LatencyPart::kQueueing,
                 clock_.now() - m.arrived);
      taken_at_[k] = clock_.now();
      mp_.give(k, m.segment);
    }
    scanline::MergingProcessor::Pass p = mp_.pass();
    const auto kind = static_cast<std::size_t>(p.kind);
    passes_.add(kind);
    compute_for(stage_time_ * static_cast<double>(scanline::kMergeStages[kind]),
                scanline::kMergeCaseNames[kind]);
    if (p.dropped) probe_.drop(*p.dropped);
    if (!p.out) continue;
    // The part it keeps of the segment it sends follows a journey of its own from here.
    if (p.shares >= 0) mp_.set_journey(p.shares, probe_.fork(p.out->journey));
    // From being taken to leaving: held for its partner and merged (the processor's time).
    probe_.add(p.out->journey, stages_.mp, modules::LatencyPart::kService,
               clock_.now() - taken_at_[p.from]);
    const sc_core::sc_time ready = clock_.now();
    wait_for_room(parent_);
    probe_.add(p.out->journey, stages_.mp, modules::LatencyPart::kQueueing, clock_.now() - ready);
    const sc_core::sc_time arrived = link.transfer(kSegmentBits, clock_.now());
    probe_.add(p.out->journey, stages_.mp_link, modules::LatencyPart::kTransfer,
               arrived - clock_.now());
    SegmentMessage msg{*p.out, arrived};
    modules::send_message(out, msg, arrived, kSegmentBits);
    if (!p.out->dummy() && !p.out->mark) ++segments_;
  }
}

}  // namespace rtsim::platform::ullner_scanline_tree
