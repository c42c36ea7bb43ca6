#include "platform/machines/ullner_pipeline/chain_timing.hpp"

namespace rtsim::platform::ullner_pipeline {

using modules::plus;
using modules::times;

namespace {
/// a - b, or zero where b >= a (times are unsigned).
sc_core::sc_time minus(const sc_core::sc_time& a, const sc_core::sc_time& b) {
  return a > b ? a - b : sc_core::SC_ZERO_TIME;
}
}  // namespace

void ChainTiming::accept(const sc_core::sc_time& accepted) {
  e0_ = accepted;
  ++accepted_;
  if (engines_ == 1) {  // the first processor is the last
    el_ = accepted;
    ++el_count_;
    el_waiting_.push_back(accepted);
    return;
  }
  e0_waiting_.push_back(accepted);
  update();
}

sc_core::sc_time ChainTiming::take_first_handed() {
  const sc_core::sc_time t = handed_.front();
  handed_.pop_front();
  return t;
}

void ChainTiming::update() {
  if (engines_ == 1) return;
  while (first_starts() || second_accepts() || last_accepts()) {
  }
}

bool ChainTiming::first_starts() {
  // S_0(x) once E_1(x-1) is known: ready a hop latency after accepting; its link free; the
  // second's register free when the first bit reaches it (polygon_engine.cpp's start, the same
  // comparisons).
  const std::uint64_t x = s0_count_;
  if (x == accepted_ || (x > 0 && e1_count_ < x)) return false;
  const sc_core::sc_time ready = plus(e0_waiting_.front(), engine_.hop_latency);
  e0_waiting_.pop_front();
  const sc_core::sc_time link_free = x == 0 ? sc_core::SC_ZERO_TIME : plus(s0_, serial_);
  const sc_core::sc_time reg_allows = x == 0 ? sc_core::SC_ZERO_TIME : minus(e1_, link_latency_);
  const sc_core::sc_time handed = reg_allows > link_free ? std::max(ready, reg_allows) : ready;
  s0_ = std::max(handed, link_free);
  ++s0_count_;
  s0_waiting_.push_back(s0_);
  handed_.push_back(handed);
  return true;
}

bool ChainTiming::second_accepts() {
  // E_1(x) once S_0(x) and the far end's hold-up it needs are known (x = s0_count_ - 1 at most:
  // S_0(x + 1) needs E_1(x), so s0_ is S_0(x)). N = 2: the second is the last (last_accepts).
  if (engines_ < 3 || e1_count_ == s0_count_) return false;
  const std::uint64_t x = e1_count_;
  const std::uint64_t back = 2 * (engines_ - 2);
  sc_core::sc_time e1 = plus(plus(s0_, serial_), link_latency_);
  if (x > 0) e1 = std::max(e1, plus(e1_, spacing()));
  if (x >= back) {
    if (el_count_ <= x - back) return false;  // the hold-up from the far end is not known yet
    e1 = std::max(e1, minus(el_history_[x - back - el_base_], times(link_latency_, engines_ - 2)));
  }
  e1_ = e1;
  ++e1_count_;
  // E_{N-1} older than the next E_1 needs is no longer needed.
  while (!el_history_.empty() && el_base_ + back < e1_count_) {
    el_history_.pop_front();
    ++el_base_;
  }
  return true;
}

bool ChainTiming::last_accepts() {
  // E_{N-1}(x) once S_0(x) and S_{N-1}(x-1) are known.
  const std::uint64_t x = el_count_;
  if (x == s0_count_ || (x > 0 && sl_count_ < x)) return false;
  const sc_core::sc_time s0 = s0_waiting_.front();
  s0_waiting_.pop_front();
  sc_core::sc_time el = plus(plus(plus(s0, serial_), link_latency_), times(hop(), engines_ - 2));
  if (x > 0) el = std::max({el, plus(el_, spacing()), sl_});
  el_ = el;
  ++el_count_;
  el_waiting_.push_back(el);
  if (engines_ == 2) {
    e1_ = el;
    e1_count_ = el_count_;
  } else {
    el_history_.push_back(el);
  }
  return true;
}

std::optional<sc_core::sc_time> ChainTiming::next_leaving(const FarEnd& far_end) {
  if (sl_count_ == el_count_) return std::nullopt;
  const std::optional<sc_core::sc_time> room = far_end.slot_free(sl_count_);
  if (!room) return std::nullopt;
  const sc_core::sc_time ready = plus(el_waiting_.front(), engine_.hop_latency);
  const sc_core::sc_time link_free = sl_count_ == 0 ? sc_core::SC_ZERO_TIME : plus(sl_, serial_);
  const sc_core::sc_time unheld = std::max(ready, link_free);
  sl_ = std::max(unheld, *room);
  held_ += sl_ - unheld;
  el_waiting_.pop_front();
  ++sl_count_;
  update();
  return sl_;
}

}  // namespace rtsim::platform::ullner_pipeline
