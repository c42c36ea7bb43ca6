#include "platform/machines/ullner_hidden_line/pipe_stage.hpp"

#include <algorithm>
#include <utility>
#include <variant>

#include "modules/message_channel.hpp"
#include "modules/sim_time.hpp"

namespace rtsim::platform::ullner_hidden_line {

using hiddenline::Message;
using modules::plus;

MessageInFlight* carried(tlm::tlm_generic_payload& gp) {
  auto* ext = gp.get_extension<modules::MessageExtension<MessageInFlight>>();
  return ext ? ext->message() : nullptr;
}

PipeStage::PipeStage(const sc_core::sc_module_name& name, std::size_t index, StageState& state,
                     const StageTiming& timing, LinkWatch& watch)
    : modules::ChainHop(name), index_(index), state_(state), timing_(timing), watch_(watch) {
  state_.plane =
      !state_.firmware || std::holds_alternative<hiddenline::PlaneProcessor>(*state_.firmware);
}

void PipeStage::b_transport(tlm::tlm_generic_payload& gp, sc_core::sc_time& delay) {
  (void)delay;  // the time travels in the message (MessageInFlight::at)
  const MessageInFlight* f = carried(gp);
  if (!f) {
    gp.set_response_status(tlm::TLM_GENERIC_ERROR_RESPONSE);
    return;
  }
  StageState& s = state_;
  // It holds one input: accepted once it is done with the one before.
  const sc_core::sc_time accepted = std::max(f->at, s.done);
  s.accepted = accepted;
  ++s.inputs;
  const Message& m = f->message;
  if (m.kind == Message::Kind::kSegment) ++s.segments_in;
  watch_.accepted(index_, m, f->at, accepted);

  out_.clear();
  // Its multiplications for this input (a cleanup processor's comparisons are two each).
  std::uint64_t multiplications = 0;
  if (!s.firmware) {
    out_.push_back(m);  // an idle plane processor passes everything on
  } else if (auto* pp = std::get_if<hiddenline::PlaneProcessor>(&*s.firmware)) {
    const std::uint64_t before = pp->multiplications();
    pp->receive(m, out_);
    multiplications = pp->multiplications() - before;
  } else {
    auto& cp = std::get<hiddenline::CleanupProcessor>(*s.firmware);
    const std::uint64_t before = cp.comparisons();
    cp.receive(m, out_);
    multiplications = 2 * (cp.comparisons() - before);
  }
  // Its arithmetic: the multiplications over its multipliers, in rounds (L1908, L1912).
  const std::uint64_t rounds = (multiplications + timing_.multipliers - 1) / timing_.multipliers;
  const sc_core::sc_time compute = modules::times(timing_.multiplication_time, rounds);
  s.compute_busy = plus(s.compute_busy, compute);
  s.done = plus(accepted, compute);
  // A plane processor forwards a segment first, and the intersection it held before it: they
  // are ready as it accepts the segment; the rest once its arithmetic is done.
  const bool forwarded = s.plane && m.kind != Message::Kind::kIntersection;
  s.pending.clear();
  s.head = 0;
  for (const Message& o : out_) s.pending.push_back({o, forwarded ? accepted : s.done});
  gp.set_response_status(tlm::TLM_OK_RESPONSE);
}

void PipeStage::send_next() {
  StageState& s = state_;
  const StageState::Pending& p = s.pending[s.head++];
  // Its link starts when the message is ready, the link has carried the one before and the
  // next register is free.
  const sc_core::sc_time start =
      std::max({p.ready, s.link_free, next_free_ ? *next_free_ : p.ready});
  s.waited = plus(s.waited, start - p.ready);
  const std::uint64_t bit_times = message_bit_times(p.message, timing_.lanes, timing_.word_bits);
  const sc_core::sc_time serial = modules::times(timing_.bit_time, bit_times);
  s.link_free = plus(start, serial);
  s.link_busy = plus(s.link_busy, serial);
  s.done = std::max(s.done, start);
  if (p.message.kind == Message::Kind::kIntersection) ++s.intersections_out;
  flight_.message = p.message;
  flight_.at = plus(s.link_free, timing_.link_latency);
  watch_.handed(index_, flight_, p.ready, start);
  modules::send_message(out, flight_, flight_.at, bit_times * timing_.lanes);
}

}  // namespace rtsim::platform::ullner_hidden_line
