#pragma once
// The memory module of one Broadcast Processor (seed 001 §5.3.1, L875-L879; Fig. 5-5 is lost,
// the prose survives): "The first structure occupying successive memory locations is the ID
// list. With each ID the size and address of its packet are also stored. ... The contents of
// each packet are also stored in successive memory locations" so the memory can stream them.
// A packet is everything for one array index (a sibling-shell list, the primitives of one leaf
// shell, one surface's characteristics); its ID is that index (L877).
//
// Layout (word addresses, 32-bit words, the width of the broadcast bus, L867):
//   0 .. N*E-1      ID list: entry i = [ID_i, address_i, size_i, 0 ...] (E words per entry)
//   N*E ..          packet 0 contents, packet 1 contents, ... in ID order
// E = id_list_entry_words (3 by default: the three fields the thesis names). Sizes are in
// words; the BP microcode says "number of bytes in packet" (Fig. 5-6, L893) — 4 x words.
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace rtsim::accel {

/// One ID list entry: {ID, packet address, packet size} (L877).
struct IdListEntry {
  std::uint32_t id = 0;
  std::uint32_t address = 0;     ///< word address of the packet in the BP memory
  std::uint32_t size_words = 0;  ///< packet length in 32-bit words
};

/// Words per ID list entry: ID, address, size (L877). Assumption: one word each.
inline constexpr std::uint32_t kIdListEntryWords = 3;

class BroadcastImage {
 public:
  BroadcastImage() = default;

  std::size_t packet_count() const { return id_list_.size(); }
  std::span<const IdListEntry> id_list() const { return id_list_; }
  /// The contents of packet `id` (a view into memory()).
  std::span<const std::uint32_t> packet(std::uint32_t id) const {
    const IdListEntry& e = id_list_[id];
    return {memory_.data() + e.address, e.size_words};
  }
  /// The whole memory module: ID list, then the packets.
  std::span<const std::uint32_t> memory() const { return memory_; }
  std::uint32_t id_list_entry_words() const { return entry_words_; }
  std::uint64_t id_list_words() const {
    return static_cast<std::uint64_t>(entry_words_) * id_list_.size();
  }
  std::uint64_t packet_words() const { return memory_.size() - id_list_words(); }
  std::uint32_t largest_packet_words() const;

 private:
  friend class BroadcastImageBuilder;
  std::vector<IdListEntry> id_list_;
  std::vector<std::uint32_t> memory_;
  std::uint32_t entry_words_ = kIdListEntryWords;
};

/// Collects packets in ID order, then lays out the image.
class BroadcastImageBuilder {
 public:
  /// Starts the next packet (its ID is the number of packets begun before it).
  void begin_packet() { starts_.push_back(words_.size()); }
  /// Words appended go to the packet begun last.
  std::vector<std::uint32_t>& words() { return words_; }
  /// Throws std::invalid_argument if id_list_entry_words < 3, std::length_error past 2^32 words.
  BroadcastImage finish(std::uint32_t id_list_entry_words = kIdListEntryWords) &&;

 private:
  std::vector<std::size_t> starts_;
  std::vector<std::uint32_t> words_;
};

}  // namespace rtsim::accel
