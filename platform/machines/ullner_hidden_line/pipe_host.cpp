#include "platform/machines/ullner_hidden_line/pipe_host.hpp"

#include <algorithm>
#include <string>
#include <utility>

#include "modules/message_channel.hpp"
#include "modules/sim_time.hpp"
#include "platform/machines/machine_run.hpp"

namespace rtsim::platform::ullner_hidden_line {

PipeHost::PipeHost(sc_core::sc_module_name name, MachineRun& run, HiddenLinePipe& pipe,
                   std::vector<hiddenline::Message> stream, std::size_t planes)
    : modules::Processor(name, run.trace()),
      run_(run),
      pipe_(pipe),
      stream_(std::move(stream)),
      planes_(planes),
      link_(std::string(this->name()) + ".link",
            modules::ModuleParams(run.registry(), std::string(HiddenLinePipe::kName) + ".link")),
      plane_link_(std::string(this->name()) + ".plane_link",
                  modules::ModuleParams(run.registry(),
                                        std::string(HiddenLinePipe::kName) + ".plane_link")),
      word_bits_(HiddenLinePipe::word_bits(run.registry())) {
  link_.trace_to(run.trace());
  out.bind(pipe.first().in);
  SC_THREAD(run);
}

void PipeHost::run() {
  // The planes, one after another down the plane path: they shift from processor to
  // processor as the next arrives, so the last is in place when the host has sent them all
  // and it has shifted once more. They load while the previous scene runs (L1906): the stream
  // does not wait for them.
  const std::uint64_t plane_bits =
      plane_bit_times(plane_link_.lanes(), word_bits_) * plane_link_.lanes();
  sc_core::sc_time t = sc_core::SC_ZERO_TIME;
  for (std::size_t k = 0; k < planes_; ++k) {
    t = plane_link_.transfer(plane_bits, t);
    ++planes_sent_;
  }
  planes_loaded_ = t;

  // The stream: every segment is ready at the start; each goes when the link is free and the
  // first processor's register is (the host is blocked on its output until then).
  std::size_t segments = 0;
  for (const std::size_t total = stream_.size(); const hiddenline::Message& m : stream_) {
    const sc_core::sc_time ready = pipe_.first().register_free();
    const std::uint64_t bits = message_bit_times(m, link_.lanes(), word_bits_) * link_.lanes();
    MessageInFlight f{m, link_.transfer(bits, ready)};
    const sc_core::sc_time started = f.at - link_.latency() - link_.serialisation(bits);
    blocked_until(started);
    if (m.kind == hiddenline::Message::Kind::kSegment) {
      ++segments_;
      const std::uint32_t e = m.segment.edge;
      if (e >= handed_.size()) handed_.resize(e + 1, sc_core::SC_ZERO_TIME);
      handed_[e] = started;
      if (journeys_ && e < journeys_->size()) {
        // Waiting at the host for its link (and the first register), then on the link.
        run_.probe().add((*journeys_)[e], probe_link_, modules::LatencyPart::kQueueing, started);
        run_.probe().add((*journeys_)[e], probe_link_, modules::LatencyPart::kTransfer,
                         f.at - started);
      }
    }
    modules::send_message(out, f, f.at, bits);
    pipe_.drain();
    if (run_.options().progress && (++segments % 256 == 0 || segments == total))
      run_.options().progress(static_cast<long>(segments), static_cast<long>(total));
  }
  frame_end_ = pipe_.divider().finished();
  // Then it waits for the divider to be done with the stream; the kernel's clock goes to the
  // frame's end, for the statistics' window and the traces.
  idle_until(frame_end_, Wait::kData);
  clock_.sync();
}

}  // namespace rtsim::platform::ullner_hidden_line
