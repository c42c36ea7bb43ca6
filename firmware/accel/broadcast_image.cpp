#include "firmware/accel/broadcast_image.hpp"

#include <algorithm>
#include <limits>
#include <stdexcept>
#include <string>

namespace rtsim::accel {

std::uint32_t BroadcastImage::largest_packet_words() const {
  std::uint32_t m = 0;
  for (const IdListEntry& e : id_list_) m = std::max(m, e.size_words);
  return m;
}

BroadcastImage BroadcastImageBuilder::finish(std::uint32_t id_list_entry_words) && {
  if (id_list_entry_words < kIdListEntryWords) {
    throw std::invalid_argument(
        "BroadcastImage: an ID list entry needs at least 3 words (ID, "
        "address, size), got " +
        std::to_string(id_list_entry_words));
  }
  const std::uint64_t list_words = static_cast<std::uint64_t>(starts_.size()) * id_list_entry_words;
  if (list_words + words_.size() > std::numeric_limits<std::uint32_t>::max()) {
    throw std::length_error("BroadcastImage: more than 2^32 words");
  }
  BroadcastImage img;
  img.entry_words_ = id_list_entry_words;
  img.memory_.assign(list_words, 0);
  img.memory_.insert(img.memory_.end(), words_.begin(), words_.end());
  img.id_list_.resize(starts_.size());
  for (std::size_t i = 0; i < starts_.size(); ++i) {
    const std::size_t end = i + 1 < starts_.size() ? starts_[i + 1] : words_.size();
    IdListEntry& e = img.id_list_[i];
    e.id = static_cast<std::uint32_t>(i);
    e.address = static_cast<std::uint32_t>(list_words + starts_[i]);
    e.size_words = static_cast<std::uint32_t>(end - starts_[i]);
    std::uint32_t* w = img.memory_.data() + i * id_list_entry_words;
    w[0] = e.id;
    w[1] = e.address;
    w[2] = e.size_words;
  }
  words_.clear();
  starts_.clear();
  return img;
}

}  // namespace rtsim::accel
