#include "platform/machines/gaudet_pert/broadcast_processor.hpp"

#include <algorithm>
#include <span>
#include <stdexcept>

#include "common/input_error.hpp"
#include "modules/activations.hpp"
#include "modules/sim_time.hpp"
#include "modules/wiring.hpp"

namespace rtsim::platform::gaudet {

namespace {

// A broadcast bus's parameters (broadcast.*, per bus), each named once.
const modules::TimeParam kIdTime(
    {.name = "id_time",
     .default_value = "1000 ns",
     .description = "Broadcast Processor: time to broadcast an ID and sample the hit line",
     .source = "seed 001 L959"});
const modules::TimeParam kPacketOverhead(
    {.name = "packet_overhead",
     .default_value = "800 ns",
     .description = "Broadcast Processor: overhead of sending a packet",
     .source = "seed 001 L960"});
const modules::TimeParam kWordTime(
    {.name = "word_time",
     .default_value = "400 ns",
     .description = "Broadcast bus: time of one 32-bit packet word (2 BP cycles)",
     .source = "seed 001 L883, L961"});
const modules::TimeParam kLoopReset(
    {.name = "loop_reset",
     .default_value = "400 ns",
     .description = "Broadcast Processor: time to reset the loop at the end of the ID list",
     .source = "seed 001 L962"});

const modules::ChoiceParam kWakes(
    {.name = "wakes",
     .default_value = "needed",
     .allowed = {"needed", "every_change"},
     .description =
         "When the Broadcast Processor's loop wakes to plan its next strobe: only at the strobe "
         "it planned, which a request for a sooner slot moves (needed), or at every request, "
         "every freed buffer and every packet's end as well (every_change: the reference). The "
         "statistics and the image are the same either way (tests/gaudet_sync_test.cpp); the "
         "first wakes a bus a half to a third as often. A bus that sends every packet "
         "(broadcast.mode = non-adaptive) wakes at every change either way",
     .source = "simulator setting, not of the machine"});

}  // namespace

void BroadcastProcessor::declare_params(const modules::ParamDecls& bus) {
  for (const auto* p : {&kIdTime, &kPacketOverhead, &kWordTime, &kLoopReset}) bus.add(*p);
  bus.add(kWakes);
}

BroadcastProcessor::BroadcastProcessor(sc_core::sc_module_name name,
                                       const modules::ModuleParams& params,
                                       std::size_t memory_words, sc_core::sc_time load_word_time,
                                       bool adaptive, bool on_queue)
    : sc_core::sc_module(name),
      modules::StatGroup(sc_core::sc_module::name()),
      // The BP streams its memory (L875): the loop's timings already include the reads, so a
      // read costs no extra time here.
      memory("memory", memory_words, 1, load_word_time, sc_core::SC_ZERO_TIME),
      timing_{.id_slot = params.get(kIdTime),
              .packet_overhead = params.get(kPacketOverhead),
              .word_time = params.get(kWordTime),
              .loop_reset = params.get(kLoopReset)},
      adaptive_(adaptive),
      // A bus that sends every packet records its busy time between wakes a cycle at a time
      // (skip_to), its utilisation windows depending on where its wakes fall: it wakes at every
      // change whatever broadcast.wakes says.
      wake_at_every_change_(params.get(kWakes) == "every_change" || !adaptive) {
  // A pass through the ID list that sends nothing must take time, or the loop never gets past
  // a moment (it ran for ever before this check).
  const bool sends_take_time =
      timing_.packet_overhead > sc_core::SC_ZERO_TIME || timing_.word_time > sc_core::SC_ZERO_TIME;
  if (timing_.id_slot == sc_core::SC_ZERO_TIME && timing_.loop_reset == sc_core::SC_ZERO_TIME &&
      (adaptive_ || !sends_take_time)) {
    std::string names = params.path_of(kIdTime.name());
    names += " and ";
    names += params.path_of(kLoopReset.name());
    throw InputError(names, 0,
                     "both are 0 s: a cycle through the ID list with nothing to send would take "
                     "no time, and the Broadcast Processor would never get past its first moment; "
                     "give either a time (defaults " +
                         kIdTime.spec().default_value + " and " + kLoopReset.spec().default_value +
                         ", seed 001 L959 and L962)");
  }
  process_.start(program());
  if (!on_queue) SC_METHOD(run);
}

void BroadcastProcessor::join(modules::WakeQueue& queue) { process_.join(queue, *this, *this); }

void BroadcastProcessor::run() { process_.resume_in_method(); }

void BroadcastProcessor::woken() { process_.resume_from_queue(); }

void BroadcastProcessor::attach(BusInterface& bic) {
  modules::connect(name(), bic.name(), "broadcast");
  bic.bus_ = this;
  bic.bus_place_ = static_cast<std::uint32_t>(bics_.size());
  bics_.push_back(&bic);
}

void BroadcastProcessor::start(const sc_core::sc_time& t, std::size_t ids,
                               std::uint32_t entry_words) {
  // Read the ID list the control processor loaded: {ID, address, size} per entry (L877).
  const std::span<const std::uint32_t> mem = memory.contents();
  auto word = [&](std::size_t k) {
    if (k >= mem.size())
      throw std::out_of_range(std::string(name()) + ": an ID list past its memory");
    return mem[k];
  };
  slots_.clear();
  for (std::size_t i = 0; i < ids; ++i) {
    const std::size_t at = i * entry_words;
    slots_.push_back(Slot{word(at), word(at + 2), word(at + 1)});
  }
  // Keys for the listed IDs. The control processor numbers packets from 0, so a table by ID
  // holds them; an ID far beyond the list's length (only a corrupted word) goes in a map.
  constexpr std::size_t kDenseIdsPerSlot = 4;
  key_by_id_.assign(
      std::min<std::size_t>(kDenseIdsPerSlot * slots_.size() + 1024, std::size_t{0xFFFFFFFFu}),
      kUnlisted);
  key_by_large_id_.clear();
  id_of_key_.clear();
  positions_.clear();
  demand_.clear();
  demanded_.clear();
  withdrawn_.clear();
  total_demand_ = 0;
  for (std::size_t i = 0; i < slots_.size(); ++i) {
    const std::uint32_t id = slots_[i].id;
    std::uint32_t key = key_of(id);
    if (key == kUnlisted) {
      key = static_cast<std::uint32_t>(id_of_key_.size());
      if (id < key_by_id_.size())
        key_by_id_[id] = key;
      else
        key_by_large_id_.emplace(id, key);
      id_of_key_.push_back(id);
      positions_.emplace_back();
    }
    positions_[key].push_back(static_cast<std::uint32_t>(i));
  }
  demand_.assign(id_of_key_.size(), 0);
  // Registers that hold IDs already (none at a frame's start, as the BICs are made).
  holders_.assign(id_of_key_.size(), {});
  for (const BusInterface* b : bics_)
    for (const auto& r : b->registers_) {
      if (r.valid) held(r.id, b->bus_place_);
      if (r.withdrawn) held(r.withdrawn_id, b->bus_place_);
    }
  idle_cycle_packets_ = idle_cycle_words_ = 0;
  offset_.assign(1, sc_core::SC_ZERO_TIME);
  for (const Slot& s : slots_) {
    sc_core::sc_time next = offset_.back() + timing_.id_slot;
    if (!adaptive_) {
      next += packet_time(s);
      ++idle_cycle_packets_;
      idle_cycle_words_ += s.words;
    }
    offset_.push_back(next);
  }
  idle_cycle_ = offset_.back() + timing_.loop_reset;
  cursor_ = Cursor{0, t};
  start_.notify(t > modules::sim_now() ? t - modules::sim_now() : sc_core::SC_ZERO_TIME);
}

sc_core::sc_time BroadcastProcessor::minimum_cycle() const {
  return modules::times(timing_.id_slot, slots_.size()) + timing_.loop_reset;
}

void BroadcastProcessor::run_to(const sc_core::sc_time& end) {
  if (slots_.empty() || sleep_ == Sleep::kBusy) return;  // not started, or past `end` already
  if (sleep_ == Sleep::kAnyChange) count_missed_strobes(end);
  record_until_ = end;
  skip_to(end);
}

void BroadcastProcessor::demand(std::uint32_t id, int delta) {
  // An ID the ID list does not hold (only with a corrupted memory) is never broadcast: its
  // requester waits for ever, and the loop must not spin through cycles looking for it.
  const std::uint32_t key = key_of(id);
  if (key == kUnlisted) return;
  const bool was = demand_[key] > 0;
  demand_[key] += delta;
  total_demand_ += delta;
  const bool is = demand_[key] > 0;
  if (is && !was) demanded_.push_back(key);
  if (was && !is) {
    const auto at = std::find(demanded_.begin(), demanded_.end(), key);
    *at = demanded_.back();
    demanded_.pop_back();
  }
}

void BroadcastProcessor::held(std::uint32_t id, std::uint32_t place) {
  if (const std::uint32_t key = key_of(id); key != kUnlisted) add_holder(key, place);
}

void BroadcastProcessor::add_holder(std::uint32_t key, std::uint32_t place) {
  std::vector<std::uint32_t>& h = holders_[key];
  const auto at = std::lower_bound(h.begin(), h.end(), place);
  if (at == h.end() || *at != place) h.insert(at, place);
}

void BroadcastProcessor::requested(std::uint32_t id, const sc_core::sc_time& t) {
  if (sleep_ == Sleep::kBusy) return;  // it plans again once the slot ends
  if (sleep_ == Sleep::kUntil && !wake_at_every_change_) {
    const std::uint32_t key = key_of(id);
    if (key == kUnlisted) return;
    // Its slot comes round only after the strobe (or look) the loop sleeps for: the loop meets
    // it then, as it would have had it woken now, planned again and slept till the same time.
    const sc_core::sc_time at = first_strobe_after(key, t);
    if (at >= planned_) return;
    // Sooner: the loop sleeps till its slot instead, and plans again then (it finds the slot
    // wanted at once), rather than waking now only to plan the same sleep.
    ring_at(at);
    return;
  }
  ring_at(modules::sim_now());
}

void BroadcastProcessor::ring_at(const sc_core::sc_time& t) {
  planned_ = t;
  if (process_.on_queue()) {
    // Moved, sooner or later, as an event notified again; a time passed is now, as below.
    process_.cancel();
    process_.run_at(std::max(t, modules::sim_now()));
    return;
  }
  // A delay handed to SystemC counts from SystemC's own time (modules/sim_time.hpp).
  const sc_core::sc_time now = modules::systemc_now();
  alarm_.cancel();  // a pending notification stays if later than a new one's: cancel it first
  alarm_.notify(t > now ? t - now : sc_core::SC_ZERO_TIME);
}

sc_core::sc_time BroadcastProcessor::first_strobe_after(std::uint32_t key,
                                                        const sc_core::sc_time& t) const {
  // A cycle with nothing sent that takes no time (no IDs' time, no reset, empty packets sent
  // in direct mode) has no next slot to speak of: wake, as for any request.
  if (idle_cycle_ == sc_core::SC_ZERO_TIME) return sc_core::SC_ZERO_TIME;
  const std::size_t n = slots_.size();
  sc_core::sc_time first = sc_core::sc_max_time();
  for (const std::uint32_t p : positions_[key]) {
    sc_core::sc_time at = after(cursor_, (p + n - cursor_.pos) % n).t;
    if (at <= t)  // a strobe at t cannot match a register valid from t (bus_interface.hpp)
      at += modules::times(idle_cycle_, (t - at).value() / idle_cycle_.value() + 1);
    first = std::min(first, at);
  }
  return first;
}

modules::Resumable BroadcastProcessor::sleep(std::optional<sc_core::sc_time> until, Sleep why) {
  sleep_ = why;
  if (until) {
    ring_at(*until);
  } else {
    planned_ = sc_core::sc_max_time();
    if (process_.on_queue())
      process_.cancel();
    else
      alarm_.cancel();
  }
  if (!process_.on_queue()) process_.run_on(alarm_);
  co_await process_.suspend();
  sleep_ = Sleep::kBusy;
}

void BroadcastProcessor::withdrawn(std::uint32_t id, const sc_core::sc_time& t) {
  const std::uint32_t key = key_of(id);
  if (key != kUnlisted) withdrawn_.emplace_back(key, t);
}

bool BroadcastProcessor::withdrawals_pending() {
  const sc_core::sc_time now = modules::sim_now();
  std::erase_if(withdrawn_, [&now](const auto& w) { return w.second < now; });
  return !withdrawn_.empty();
}

sc_core::sc_time BroadcastProcessor::packet_time(const Slot& s) const {
  return timing_.packet_overhead + modules::times(timing_.word_time, s.words);
}

void BroadcastProcessor::pass(Cursor& c, bool sent, bool account) {
  const Slot& s = slots_[c.pos];
  c.t += timing_.id_slot;
  if (account) {
    ++ids_;
    if (sent) {
      ++packets_;
      packet_words_ += s.words;
      // Up to the frame's end only, once the loop runs on to it (run_to).
      if (c.t < record_until_) busy_.record(c.t, std::min(packet_time(s), record_until_ - c.t));
    }
  }
  if (sent) c.t += packet_time(s);
  if (++c.pos == slots_.size()) {
    c.pos = 0;
    c.t += timing_.loop_reset;
    if (account) ++cycles_;
  }
}

BroadcastProcessor::Cursor BroadcastProcessor::after(const Cursor& c, std::size_t d) const {
  const std::size_t n = slots_.size();
  if (c.pos + d < n) return Cursor{c.pos + d, c.t + (offset_[c.pos + d] - offset_[c.pos])};
  return Cursor{c.pos + d - n, c.t + (idle_cycle_ - offset_[c.pos]) + offset_[c.pos + d - n]};
}

std::size_t BroadcastProcessor::next_wanted() {
  // The first slot in the loop's order from the cursor whose ID is wanted by its time: the
  // demanded IDs' slots, nearest first (the slots' times grow with their distance), until one
  // is wanted by then (a register valid before its strobe).
  const std::size_t n = slots_.size();
  candidates_.clear();
  for (const std::uint32_t key : demanded_)
    for (const std::uint32_t p : positions_[key])
      candidates_.emplace_back((p + n - cursor_.pos) % n, key);
  for (const auto& [key, at] : withdrawn_)
    for (const std::uint32_t p : positions_[key])
      candidates_.emplace_back((p + n - cursor_.pos) % n, key);
  std::sort(candidates_.begin(), candidates_.end());
  for (const auto& [d, key] : candidates_)
    if (wanted(key, after(cursor_, d).t)) return d;
  return n;
}

void BroadcastProcessor::skip_to(const sc_core::sc_time& t) {
  if (adaptive_) {
    // Nothing is sent on the way: only IDs and cycles to count, so the slots' starts are
    // worked out, not passed one by one.
    if (cursor_.t >= t) return;
    const std::size_t n = slots_.size();
    const sc_core::sc_time cycle_start = cursor_.t - offset_[cursor_.pos];
    // The first slot starting at or after t, counted in slots from this cycle's slot 0.
    const std::uint64_t into = (t - cycle_start).value();
    std::uint64_t cycles = into / idle_cycle_.value();
    const sc_core::sc_time rest = sc_core::sc_time::from_value(into % idle_cycle_.value());
    std::size_t k = static_cast<std::size_t>(
        std::lower_bound(offset_.begin(), offset_.begin() + static_cast<std::ptrdiff_t>(n), rest) -
        offset_.begin());
    if (k == n) {  // past the last slot's start: slot 0 of the next cycle
      k = 0;
      ++cycles;
    }
    ids_ += cycles * n + k - cursor_.pos;
    cycles_ += cycles;
    cursor_.pos = k;
    cursor_.t = cycle_start + modules::times(idle_cycle_, cycles) + offset_[k];
    return;
  }
  // Slot by slot to the start of a cycle, whole idle cycles at once (each the same length),
  // then slot by slot.
  while (cursor_.t < t && cursor_.pos != 0) pass(cursor_, !adaptive_, true);
  if (cursor_.t < t && idle_cycle_ > sc_core::SC_ZERO_TIME) {
    const std::uint64_t k = (t - cursor_.t).value() / idle_cycle_.value();
    // Non-adaptive idle cycles still send every packet: one interval a cycle is exact enough
    // for utilisation windows (a window spans many cycles).
    const sc_core::sc_time sent_per_cycle = idle_cycle_ - minimum_cycle();
    if (sent_per_cycle > sc_core::SC_ZERO_TIME)
      for (std::uint64_t i = 0; i < k; ++i)
        busy_.record(cursor_.t + modules::times(idle_cycle_, i), sent_per_cycle);
    cursor_.t += modules::times(idle_cycle_, k);
    cycles_ += k;
    ids_ += k * slots_.size();
    packets_ += k * idle_cycle_packets_;
    packet_words_ += k * idle_cycle_words_;
  }
  while (cursor_.t < t) pass(cursor_, !adaptive_, true);
}

bool BroadcastProcessor::wanted(std::uint32_t key, const sc_core::sc_time& t) const {
  if (demand_[key] <= 0 && std::none_of(withdrawn_.begin(), withdrawn_.end(), [&](const auto& w) {
        return w.first == key && t <= w.second;
      }))
    return false;
  const std::uint32_t id = id_of_key_[key];
  return std::any_of(holders_[key].begin(), holders_[key].end(),
                     [&](std::uint32_t place) { return bics_[place]->requested(id, t); });
}

std::optional<sc_core::sc_time> BroadcastProcessor::first_request_time() const {
  std::optional<sc_core::sc_time> first;
  for (const BusInterface* b : bics_)
    for (const auto& r : b->registers_)
      if (r.valid && (!first || r.from < *first))
        if (const std::uint32_t key = key_of(r.id); key != kUnlisted && demand_[key] > 0)
          first = r.from;
  return first;
}

bool BroadcastProcessor::every_strobe_misses(const sc_core::sc_time& t) const {
  for (const BusInterface* b : bics_) {
    if (b->free_buffer(t) < 0) continue;
    for (const auto& r : b->registers_)
      if (r.valid && r.from < t)
        if (const std::uint32_t key = key_of(r.id); key != kUnlisted && demand_[key] > 0)
          return false;  // it would capture its packet
  }
  return true;
}

std::optional<sc_core::sc_time> BroadcastProcessor::next_change(const sc_core::sc_time& t) const {
  std::optional<sc_core::sc_time> first;
  const auto consider = [&first](const sc_core::sc_time& at) {
    if (!first || at < *first) first = at;
  };
  for (const BusInterface* b : bics_) {
    for (const auto& buffer : b->buffers_)
      if (buffer.state == BusInterface::BufferState::kFree && buffer.at >= t) consider(buffer.at);
    for (const auto& r : b->registers_)
      if (r.valid && r.from >= t) consider(r.from);
  }
  return first;
}

void BroadcastProcessor::plan_missed_strobes() {
  miss_plan_.clear();
  for (const std::uint32_t key : demanded_) {
    std::vector<BusInterface*> requesters;
    for (const std::uint32_t place : holders_[key])
      if (bics_[place]->requested(id_of_key_[key], cursor_.t)) requesters.push_back(bics_[place]);
    if (!requesters.empty()) miss_plan_.emplace_back(key, std::move(requesters));
  }
}

void BroadcastProcessor::count_missed_strobes(const sc_core::sc_time& end) {
  // The slots' starts repeat every idle cycle (nothing is captured, so nothing is sent but what
  // the mode sends anyway): each planned ID's slots are strobed once a cycle, each strobe a miss
  // in every BIC that requests the ID.
  const std::size_t n = slots_.size();
  const std::uint64_t cycle = idle_cycle_.value();
  for (const auto& [key, requesters] : miss_plan_)
    for (const std::uint32_t p : positions_[key]) {
      const sc_core::sc_time first = after(cursor_, (p + n - cursor_.pos) % n).t;
      if (first >= end) continue;
      const std::uint64_t strobes =
          (end - first).value() / cycle + ((end - first).value() % cycle != 0 ? 1 : 0);
      for (BusInterface* b : requesters) b->missed_ += strobes;
    }
}

modules::Resumable BroadcastProcessor::program() {
  // On the queue it runs first at the frame's start.
  if (!process_.on_queue()) {
    process_.run_on(start_);
    co_await process_.suspend();
  }
  if (slots_.empty()) co_return;
  for (;;) {
    // A request withdrawn now is still met by a strobe now (bus_interface.hpp).
    const bool withdrawals = withdrawals_pending();
    if (total_demand_ <= 0 && !withdrawals) {
      co_await sleep(std::nullopt, Sleep::kUntil);
      skip_to(modules::sim_now());
      continue;
    }
    // The next slot whose ID some BIC holds in a register valid by then (at most one cycle
    // ahead). A register is valid from its processor's local time, which may lie ahead of
    // simulated time (a quantum > 0): a strobe before then could not match it.
    const std::size_t n = next_wanted();
    // While a packet is on the bus the loop plans from the packet's end (the cursor).
    const sc_core::sc_time now = std::max(modules::sim_now(), packet_end_);
    if (n == slots_.size() && total_demand_ <= 0) {
      // Only withdrawn requests, which no strobe can meet any more: as with none.
      co_await sleep(std::nullopt, Sleep::kUntil);
      skip_to(modules::sim_now());
      continue;
    }
    if (n == slots_.size()) {
      // Every request is valid only from beyond this cycle: sleep until the first of them (or
      // a new request), instead of strobing a cycle of slots no comparator can match yet.
      const auto first = first_request_time();
      co_await sleep(now + (first && *first > now ? *first - now : minimum_cycle()), Sleep::kUntil);
      skip_to(modules::sim_now());
      continue;
    }
    const Cursor c = after(cursor_, n);
    if (c.t > modules::sim_now()) {
      co_await sleep(c.t, Sleep::kUntil);
      // Woken early, at the slot of a request made since: nothing was wanted before now, and
      // the plan from here finds that slot at once.
      if (modules::sim_now() < c.t) {
        skip_to(modules::sim_now());
        continue;
      }
    }
    skip_to(c.t);  // to the wanted slot, counting the ones before it
    // The sync strobe: every BIC compares the ID with its registers (L920).
    const Slot& s = slots_[cursor_.pos];
    const sc_core::sc_time strobe = cursor_.t;
    hitters_.clear();
    std::vector<std::uint32_t>& holders = holders_[key_of(s.id)];
    for (const std::uint32_t place : holders)
      if (bics_[place]->hit(s.id, strobe)) hitters_.push_back(bics_[place]);
    const bool sent = !hitters_.empty() || !adaptive_;
    if (!hitters_.empty()) {
      const sc_core::sc_time start = strobe + timing_.id_slot;
      const sc_core::sc_time arrival = start + packet_time(s);
      // The packet's words as the memory holds them (an entry pointing past the end sends
      // what there is).
      const std::span<const std::uint32_t> mem(memory.contents());
      const std::size_t first = std::min<std::size_t>(s.address, mem.size());
      const auto words = mem.subspan(first, std::min<std::size_t>(s.words, mem.size() - first));
      for (BusInterface* b : hitters_)
        b->capture(s.id, start, arrival, start + timing_.packet_overhead, timing_.word_time, words);
      ++hit_packets_;
      captures_ += hitters_.size();
      hit_packet_time_ += packet_time(s);
      if (on_packet) on_packet(s.id, start, packet_time(s), hitters_.size());
    }
    // The BICs that captured it, or whose withdrawn request it met, hold its ID no more.
    std::erase_if(holders, [&](std::uint32_t place) { return !bics_[place]->holds(s.id); });
    pass(cursor_, sent, true);
    if (!hitters_.empty() && !wake_at_every_change_) {
      // A packet on the bus: the loop plans its next strobe now, from the packet's end (the
      // cursor), rather than waking at the end only to plan. A request made during the packet
      // moves its alarm sooner if its slot comes first after the packet, as any request does.
      packet_end_ = cursor_.t;
      continue;
    }
    // The loop is busy until the slot ends (a packet no one listens to, in the modes that send
    // them all; the ID alone; or, waking at every change, any packet).
    if (cursor_.t > modules::sim_now()) {
      process_.run_at(cursor_.t);
      co_await process_.suspend();
    }
    // A wanted ID missed: every BIC that wants one may be full until its processor frees a
    // buffer. While that holds, every strobe misses alike, and strobing slot by slot costs
    // events without end when a processor is slow (a 1 Hz shell clock: 2,400 strobes a
    // simulated second). Sleep until a wake or the next change the BICs already hold, and
    // count the strobes slept through as the misses they were.
    if (hitters_.empty()) {
      const sc_core::sc_time now = modules::sim_now();
      if (total_demand_ > 0 && every_strobe_misses(now)) {
        const auto change = next_change(now);
        if (!change || *change > now) {
          plan_missed_strobes();
          co_await sleep(change, Sleep::kAnyChange);
          count_missed_strobes(modules::sim_now());
          skip_to(modules::sim_now());
        }
      }
    }
  }
}

}  // namespace rtsim::platform::gaudet
