#include "platform/machines/gaudet_pert/bus_interface.hpp"

#include <algorithm>

#include "modules/sim_time.hpp"
#include "platform/machines/gaudet_pert/broadcast_processor.hpp"

namespace rtsim::platform::gaudet {

void BusInterface::declare_params(const modules::ParamDecls& bic, const IdRegisters& id_registers) {
  // The processor's kind, for the descriptions: "pert.shell.bic" -> "shell".
  const std::string& path = bic.path();
  const std::size_t end = path.rfind('.');
  const std::size_t begin = path.rfind('.', end - 1) + 1;
  const std::string kind = path.substr(begin, end - begin);
  bic.count(kBuffers, "2", "1", "64", "buffers",
            "FIFO packet buffers of the " + kind + " processor's BIC",
            "seed 001 L924 (double buffer)");
  bic.count(kIdRegisters, id_registers.value, "1", "4096", "registers", id_registers.description,
            id_registers.source);
}

void BusInterface::declare_stream_param(const modules::ParamDecls& bic, std::string value,
                                        std::string source) {
  bic.declare({.name = kStream,
               .kind = params::ParamKind::kBool,
               .default_value = std::move(value),
               .description = "The processor reads a packet's records as they stream into the "
                              "BIC's FIFO buffer (record k once its words are in), not only "
                              "after the whole packet",
               .source = std::move(source)});
}

BusInterface::BusInterface(const modules::ModuleParams& params, std::uint32_t stream_unit_words)
    : modules::StatGroup(params.path()),
      registers_(std::max<std::size_t>(params.get_count(kIdRegisters), 1)),
      buffers_(std::max<std::size_t>(params.get_count(kBuffers), 1)),
      stream_unit_words_(stream_unit_words > 0 && params.get_bool(kStream) ? stream_unit_words
                                                                           : 0) {}

bool BusInterface::request(std::uint32_t id, const sc_core::sc_time& t) {
  if (pending(id)) return true;  // the comparator matches it once for everyone who wants it
  // The processor searches the registers serially for a free one (L910).
  for (Register& r : registers_) {
    if (r.valid || r.from > t) continue;
    r = Register{id, true, t};
    ++requests_;
    const auto used = static_cast<std::size_t>(std::count_if(
        registers_.begin(), registers_.end(), [](const Register& x) { return x.valid; }));
    peak_registers_.note(used);
    if (bus_) {
      bus_->demand(id, +1);
      bus_->held(id, bus_place_);
      bus_->requested(id, t);
    }
    return true;
  }
  ++register_full_;
  return false;
}

void BusInterface::cancel(std::uint32_t id, const sc_core::sc_time& t) {
  for (Register& r : registers_) {
    if (!r.valid || r.id != id) continue;
    // A strobe at t still matches it (bus_interface.hpp): the bus keeps it in mind until then.
    r.withdrawn = true;
    r.withdrawn_id = id;
    r.withdrawn_from = r.from;
    r.withdrawn_at = t;
    r.valid = false;
    r.from = std::max(t, r.from);
    if (bus_) {
      bus_->demand(id, -1);
      bus_->withdrawn(id, t);
    }
  }
  for (Buffer& b : buffers_) {
    if (b.state != BufferState::kFilled || b.id != id) continue;
    b.state = BufferState::kFree;
    b.at = std::max(t, b.at);
    if (bus_) bus_->buffer_freed();
  }
}

bool BusInterface::pending(std::uint32_t id) const {
  return std::any_of(registers_.begin(), registers_.end(),
                     [id](const Register& r) { return r.valid && r.id == id; });
}

bool BusInterface::register_free(const sc_core::sc_time& t) const {
  return std::any_of(registers_.begin(), registers_.end(),
                     [&t](const Register& r) { return !r.valid && r.from <= t; });
}

std::optional<sc_core::sc_time> BusInterface::next_arrival(std::optional<std::uint32_t> id) const {
  std::optional<sc_core::sc_time> best;
  for (const Buffer& b : buffers_) {
    if (b.state != BufferState::kFilled || (id && b.id != *id)) continue;
    if (!best || b.ready < *best) best = b.ready;
  }
  return best;
}

std::optional<ReceivedPacket> BusInterface::take(const sc_core::sc_time& t,
                                                 std::optional<std::uint32_t> id) {
  int pick = -1;
  for (std::size_t i = 0; i < buffers_.size(); ++i) {
    const Buffer& b = buffers_[i];
    if (b.state != BufferState::kFilled || b.ready > t || (id && b.id != *id)) continue;
    if (pick < 0 || b.ready < buffers_[static_cast<std::size_t>(pick)].ready)
      pick = static_cast<int>(i);
  }
  if (pick < 0) return std::nullopt;
  Buffer& b = buffers_[static_cast<std::size_t>(pick)];
  b.state = BufferState::kInUse;
  return ReceivedPacket{.id = b.id,
                        .arrival = b.at,
                        .transfer_start = b.start,
                        .buffer = pick,
                        .words = b.words,
                        .streamed = stream_unit_words_ > 0,
                        .first_word = b.first_word,
                        .word_time = b.word_time};
}

void BusInterface::release(const ReceivedPacket& p, const sc_core::sc_time& t) {
  Buffer& b = buffers_.at(static_cast<std::size_t>(p.buffer));
  b.state = BufferState::kFree;
  b.at = std::max(t, b.at);  // a streamed packet's FIFO fills until its arrival
  // A free buffer can turn a waiting match into a hit: the bus must look again.
  if (bus_) bus_->buffer_freed();
}

int BusInterface::free_buffer(const sc_core::sc_time& t) const {
  for (std::size_t i = 0; i < buffers_.size(); ++i)
    if (buffers_[i].state == BufferState::kFree && buffers_[i].at < t)  // freed before t
      return static_cast<int>(i);
  return -1;
}

bool BusInterface::requested(std::uint32_t id, const sc_core::sc_time& t) const {
  return std::any_of(registers_.begin(), registers_.end(), [&](const Register& r) {
    // Valid before the strobe at t, not at it, and not withdrawn before it (bus_interface.hpp
    // says why).
    return (r.valid && r.id == id && r.from < t) || r.withdrawn_match(id, t);
  });
}

bool BusInterface::holds(std::uint32_t id) const {
  return std::any_of(registers_.begin(), registers_.end(), [id](const Register& r) {
    return (r.valid && r.id == id) || (r.withdrawn && r.withdrawn_id == id);
  });
}

bool BusInterface::hit(std::uint32_t id, const sc_core::sc_time& t) {
  if (!requested(id, t)) return false;
  if (free_buffer(t) < 0) {
    ++missed_;  // a match without a free buffer does not raise the hit line (L920)
    return false;
  }
  return true;
}

void BusInterface::capture(std::uint32_t id, const sc_core::sc_time& start,
                           const sc_core::sc_time& arrival, const sc_core::sc_time& first_word,
                           const sc_core::sc_time& word_time,
                           std::span<const std::uint32_t> words) {
  const int i = free_buffer(modules::sim_now());
  if (i < 0) return;  // hit() said otherwise: cannot happen
  Buffer& b = buffers_[static_cast<std::size_t>(i)];
  b.state = BufferState::kFilled;
  b.id = id;
  b.at = arrival;
  b.start = start;
  b.first_word = first_word;
  b.word_time = word_time;
  // Streamed: taken once its first record is in (L920, L924).
  b.ready = stream_unit_words_ > 0
                ? std::min(arrival, first_word + modules::times(word_time, stream_unit_words_))
                : arrival;
  b.words.assign(words.begin(), words.end());
  ++received_;
  const sc_core::sc_time strobe = modules::sim_now();
  bool wanted = false;
  for (Register& r : registers_) {
    if (!r.valid || r.id != id) continue;
    r.valid = false;
    r.from = arrival;  // freed when the packet has been received (L912)
    wanted = true;
    if (bus_) bus_->demand(id, -1);
  }
  // A request withdrawn at the strobe's very time was matched: its register is freed on
  // receipt as any other's, and the packet is dropped as the withdrawal drops a packet in.
  for (Register& r : registers_) {
    if (!r.withdrawn_match(id, strobe)) continue;
    r.withdrawn = false;
    if (!r.valid) r.from = std::max(r.from, arrival);
    if (!wanted) {
      b.state = BufferState::kFree;
      b.at = std::max(r.withdrawn_at, b.at);
      wanted = true;  // one buffer, dropped once
    }
  }
  tell_changed(changed_);
}

}  // namespace rtsim::platform::gaudet
