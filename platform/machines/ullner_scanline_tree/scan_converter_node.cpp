#include "platform/machines/ullner_scanline_tree/scan_converter_node.hpp"

#include "firmware/scanline/scan_converter.hpp"
#include "platform/machines/machine_run.hpp"

namespace rtsim::platform::ullner_scanline_tree {

namespace {
const modules::TimeParam kSegmentTime(
    {.name = "segment_time",
     .default_value = "0 s",
     .description = "time to step the trackers to the next line and form a segment (its adders "
                    "work while the previous segment is sent)",
     .source = "assumption: \"the computation performed within the scan conversion processor is "
               "so minimal that the communication time is dominant\" (seed 000 L1348)"});
constexpr const char* kLink = "link";
}  // namespace

void ScanConverterNode::declare_params(const modules::ParamDecls& scp) {
  scp.add(kSegmentTime);
  modules::Link::declare_params(
      scp.sub(kLink), {.latency = "0 s",
                       .lanes = "11",
                       .bit_time = "150 ns",
                       .source = "seed 000 L1348: bit-serial, one wire a word (11 words of 12 "
                                 "bits), about 150 ns a bit: a segment in 1.8 us"});
}

ScanConverterNode::ScanConverterNode(sc_core::sc_module_name name, MachineRun& run,
                                     std::uint32_t polygon, int lines,
                                     const modules::TimedFifo<SegmentMessage>& parent,
                                     const ProbeStages& stages)
    : modules::Processor(name, run.trace()),
      in("in", 1),
      out("out"),
      link(std::string(this->name()) + "." + kLink,
           modules::ModuleParams(run.registry(), kClass).sub(kLink)),
      params_(run.registry(), kClass),
      polygon_(polygon),
      lines_(lines),
      parent_(parent),
      segment_time_(params_.get(kSegmentTime)),
      probe_(run.probe()),
      stages_(stages) {
  SC_THREAD(run);
}

void ScanConverterNode::run() {
  // A frame at a time: the edge lists the frame sequencer hands over (a new version, or the
  // one it scanned last, L1352), a segment a line, then the dummy.
  for (;;) {
    const sc_core::sc_time since = clock_.now();
    modules::wait_for_item(in.fifo, clock_);
    sc_core::sc_time taken;
    const ChainsMessage m = in.fifo.get(clock_.now(), taken);
    clock_.catch_up(taken);
    waited_since(since, Wait::kData);
    for (scanline::Segment s : scanline::scan_convert(m.chains, lines_, polygon_)) {
      const sc_core::sc_time formed = clock_.now();
      if (!s.dummy()) s.journey = probe_.begin(formed);
      if (segment_time_ > sc_core::SC_ZERO_TIME)
        compute_for(segment_time_, "segment", {{"y", s.y}});
      probe_.add(s.journey, stages_.scp, modules::LatencyPart::kService, clock_.now() - formed);
      const sc_core::sc_time ready = clock_.now();
      wait_for_room(parent_);
      probe_.add(s.journey, stages_.scp, modules::LatencyPart::kQueueing, clock_.now() - ready);
      const sc_core::sc_time arrived = link.transfer(kSegmentBits, clock_.now());
      probe_.add(s.journey, stages_.scp_link, modules::LatencyPart::kTransfer,
                 arrived - clock_.now());
      SegmentMessage msg{s, arrived};
      modules::send_message(out, msg, arrived, kSegmentBits);
      if (!s.dummy()) ++segments_;
    }
    clock_.sync();
  }
}

}  // namespace rtsim::platform::ullner_scanline_tree
