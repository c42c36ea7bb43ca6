#pragma once
// The "direct memory" baseline of Gaudet's comparisons (seed 001 L806, L1011, L1103): the
// processor holds the whole data set in its own memory module, so a packet is there as soon as
// it is asked for — after the memory's first-access latency; the words then stream at one
// cycle each (L863), which the processor charges as it reads them. No registers to run out of,
// no buffers to fill: the floor that broadcasting is measured against.
#include <algorithm>
#include <span>
#include <utility>
#include <vector>

#include "platform/machines/gaudet_pert/packet_port.hpp"

namespace rtsim::platform::gaudet {

class LocalDataSet final : public PacketPort {
 public:
  /// `memory`: the data set as a Broadcast Processor's memory holds it (an ID list of `ids`
  /// entries of `entry_words` words, {ID, address, size}, then the packets); one image serves
  /// every processor (each holds the same copy) and must outlive this port.
  LocalDataSet(sc_core::sc_time first_access, std::span<const std::uint32_t> memory,
               std::size_t ids, std::uint32_t entry_words)
      : first_access_(first_access), memory_(memory) {
    for (std::size_t i = 0; i < ids; ++i) {
      const std::uint32_t id = memory[i * entry_words];
      if (id >= packets_.size()) packets_.resize(std::size_t{id} + 1);
      packets_[id] = {memory[i * entry_words + 1], memory[i * entry_words + 2]};
    }
  }

  bool request(std::uint32_t id, const sc_core::sc_time& t) override {
    if (pending(id)) return true;
    ReceivedPacket p{id, t + first_access_, t, static_cast<int>(ready_.size())};
    if (id < packets_.size()) {
      const auto [address, size] = packets_[id];
      const std::size_t first = std::min<std::size_t>(address, memory_.size());
      p.words = memory_.subspan(first, std::min<std::size_t>(size, memory_.size() - first));
    }
    ready_.push_back(p);
    tell_changed(changed_);
    return true;
  }
  void cancel(std::uint32_t id, const sc_core::sc_time&) override {
    std::erase_if(ready_, [id](const ReceivedPacket& p) { return p.id == id; });
  }
  bool pending(std::uint32_t id) const override {
    return std::any_of(ready_.begin(), ready_.end(),
                       [id](const ReceivedPacket& p) { return p.id == id; });
  }
  bool register_free(const sc_core::sc_time&) const override { return true; }
  std::optional<sc_core::sc_time> next_arrival(
      std::optional<std::uint32_t> id = std::nullopt) const override {
    std::optional<sc_core::sc_time> best;
    for (const auto& p : ready_)
      if ((!id || p.id == *id) && (!best || p.arrival < *best)) best = p.arrival;
    return best;
  }
  std::optional<ReceivedPacket> take(const sc_core::sc_time& t,
                                     std::optional<std::uint32_t> id = std::nullopt) override {
    auto best = ready_.end();
    for (auto it = ready_.begin(); it != ready_.end(); ++it)
      if ((!id || it->id == *id) && it->arrival <= t &&
          (best == ready_.end() || it->arrival < best->arrival))
        best = it;
    if (best == ready_.end()) return std::nullopt;
    ReceivedPacket p = *best;
    ready_.erase(best);
    return p;
  }
  void release(const ReceivedPacket&, const sc_core::sc_time&) override {}
  const sc_core::sc_event& changed_event() const override { return changed_; }

 private:
  sc_core::sc_time first_access_;
  std::span<const std::uint32_t> memory_;
  std::vector<std::pair<std::uint32_t, std::uint32_t>> packets_;  ///< by ID: address, size
  std::vector<ReceivedPacket> ready_;
  sc_core::sc_event changed_;
};

}  // namespace rtsim::platform::gaudet
