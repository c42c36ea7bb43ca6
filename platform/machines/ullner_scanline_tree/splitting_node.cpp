#include "platform/machines/ullner_scanline_tree/splitting_node.hpp"

#include <algorithm>
#include <utility>

#include "firmware/scanline/splitting.hpp"
#include "modules/sim_time.hpp"
#include "platform/machines/machine_run.hpp"

namespace rtsim::platform::ullner_scanline_tree {

namespace {
const modules::TimeParam kStageTime(
    {.name = "stage_time",
     .default_value = "3 us",
     .description = "time of a stage: the test takes one, a break two (the test's divisions, "
                    "then the multiplications interpolating z, r, g, b at the two new ends)",
     .source = "assumption: the seed gives no time (L1631: \"a divider and a few multipliers, "
               "as described for the merging processor\"); the merging processor's 3 us a "
               "stage (L1519)"});
const modules::CountParam kQueueDepth(
    {.name = "queue_depth",
     .default_value = "11",
     .min = "1",
     .max = "4096",
     .unit = "segments",
     .description = "segments each output queue holds: about a scan line's, as the merging "
                    "processor below delivers them",
     .source = "seed 000 L1633-L1637: 65 us a line over a segment every 6 us, eleven segments "
               "(about 1500 bits)"});
constexpr const char* kLink = "link";
}  // namespace

void SplittingNode::declare_params(const modules::ParamDecls& sp) {
  sp.add(kStageTime);
  sp.add(kQueueDepth);
  modules::Link::declare_params(
      sp.sub(kLink), {.latency = "0 s",
                      .lanes = "11",
                      .bit_time = "150 ns",
                      .source = "assumption: the tree's bit-serial links (seed 000 L1348, "
                                "L1459), one an output"});
}

std::size_t SplittingNode::queue_depth(const params::ParamRegistry& registry) {
  return modules::ModuleParams(registry, kClass).get(kQueueDepth);
}

void SplittingNode::check_params(const params::ParamRegistry& registry) {
  const modules::ModuleParams p(registry, kClass);
  (void)p.get(kStageTime);
  (void)p.get(kQueueDepth);
  modules::Link::check_params(p.sub(kLink));
}

SplittingOutput::SplittingOutput(sc_core::sc_module_name name, MachineRun& run, std::size_t depth,
                                 const modules::TimedFifo<SegmentMessage>& parent,
                                 const ProbeStages& stages)
    : modules::Processor(name, run.trace()),
      queue("queue", depth),
      out("out"),
      link(std::string(this->name()) + "." + kLink,
           modules::ModuleParams(run.registry(), SplittingNode::kClass).sub(kLink)),
      parent_(parent),
      probe_(run.probe()),
      stages_(stages) {
  SC_THREAD(run);
}

void SplittingOutput::run() {
  for (;;) {
    const sc_core::sc_time since = clock_.now();
    modules::wait_for_item(queue.fifo, clock_);
    sc_core::sc_time taken;
    SegmentMessage m = queue.fifo.get(clock_.now(), taken);
    clock_.catch_up(taken);
    waited_since(since, Wait::kData);
    probe_.add(m.segment.journey, stages_.sp_out, modules::LatencyPart::kQueueing,
               clock_.now() - m.arrived);
    const sc_core::sc_time ready = clock_.now();
    wait_for_room(parent_);
    probe_.add(m.segment.journey, stages_.sp_out, modules::LatencyPart::kQueueing,
               clock_.now() - ready);
    const sc_core::sc_time arrived = link.transfer(kSegmentBits, clock_.now());
    probe_.add(m.segment.journey, stages_.sp_link, modules::LatencyPart::kTransfer,
               arrived - clock_.now());
    m.arrived = arrived;
    modules::send_message(out, m, arrived, kSegmentBits);
    if (m.segment.dummy()) clock_.sync();
  }
}

SplittingNode::SplittingNode(sc_core::sc_module_name name, MachineRun& run,
                             const modules::TimedFifo<SegmentMessage>& left,
                             const modules::TimedFifo<SegmentMessage>& right,
                             const ProbeStages& stages)
    : modules::Processor(name, run.trace()),
      in("in", 1),
      params_(run.registry(), kClass),
      stage_time_(params_.get(kStageTime)),
      probe_(run.probe()),
      stages_(stages) {
  const std::size_t depth = params_.get(kQueueDepth);
  outputs[0] = std::make_unique<SplittingOutput>("left", run, depth, left, stages);
  outputs[1] = std::make_unique<SplittingOutput>("right", run, depth, right, stages);
  for (int k = 0; k < 2; ++k) to_output_[k].bind(outputs[k]->queue.socket);
  SC_THREAD(run);
}

int SplittingNode::max_queued() const {
  int most = 0;
  for (const auto& o : outputs)
    most = std::max(
        most, o->queue.fifo.occupancy().summarize(sc_core::SC_ZERO_TIME, modules::sim_now()).max);
  return most;
}

void SplittingNode::enqueue(int side, SegmentMessage& m) {
  const sc_core::sc_time ready = clock_.now();
  wait_for_room(outputs[static_cast<std::size_t>(side)]->queue.fifo);
  probe_.add(m.segment.journey, stages_.sp, modules::LatencyPart::kQueueing, clock_.now() - ready);
  m.arrived = clock_.now();
  modules::send_message(to_output_[static_cast<std::size_t>(side)], m, clock_.now(), 0);
}

void SplittingNode::run() {
  for (;;) {
    const sc_core::sc_time since = clock_.now();
    modules::wait_for_item(in.fifo, clock_);
    sc_core::sc_time taken;
    const SegmentMessage m = in.fifo.get(clock_.now(), taken);
    clock_.catch_up(taken);
    waited_since(since, Wait::kData);
    probe_.add(m.segment.journey, stages_.sp_in, modules::LatencyPart::kQueueing,
               clock_.now() - m.arrived);
    if (!m.segment.dummy() && !m.segment.mark) {
      if (m.segment.y != line_) {
        line_max_ = std::max(line_max_, line_count_);
        line_count_ = 0;
      }
      line_ = m.segment.y;
      ++line_count_;
    }
    const scanline::SplittingProcessor::Sent sent = sp_.take(m.segment);
    const sc_core::sc_time start = clock_.now();
    if (m.segment.mark) {
      // A mark from the merging processor below: the test alone.
      compute_for(stage_time_, "mark", {{"y", m.segment.y}});
    } else if (!m.segment.dummy()) {
      compute_for(stage_time_ * (sent.broken ? 2.0 : 1.0), sent.broken ? "break" : "test",
                  {{"y", m.segment.y}});
      ++(sent.broken ? broken_ : whole_);
    }
    probe_.add(m.segment.journey, stages_.sp, modules::LatencyPart::kService, clock_.now() - start);
    // The order it writes its outputs: a line mark first (the merging processor it tells may be
    // all that is waiting, and the other output's queue may be full), then the parts, a part
    // whose queue has room before one whose queue is full.
    int order[2] = {0, 1};
    const auto rank = [&](int k) {
      if (sent.to[k] && sent.to[k]->mark) return 0;
      return outputs[static_cast<std::size_t>(k)]->queue.fifo.full() ? 2 : 1;
    };
    if (rank(1) < rank(0)) std::swap(order[0], order[1]);
    for (const int k : order) {
      if (!sent.to[k]) continue;
      SegmentMessage out{*sent.to[k], m.arrived};
      if (out.segment.mark) {
        out.segment.journey = scanline::kNoJourney;
        ++marks_;
      } else if (k == 1 && sent.broken) {
        // The right part of a broken segment follows a journey of its own from here.
        out.segment.journey = probe_.fork(m.segment.journey);
      }
      enqueue(k, out);
    }
    if (m.segment.dummy()) {
      // The frame's stream is over; the next frame's begins afresh (its first segment closes
      // this frame's last line's count).
      sp_ = scanline::SplittingProcessor{};
      line_ = -1;
      clock_.sync();
    }
  }
}

}  // namespace rtsim::platform::ullner_scanline_tree
