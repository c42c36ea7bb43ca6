#pragma once
// A first-in first-out buffer in one growing array: push at the back, take from the front, no
// allocation once it has grown to the most it held. std::deque allocates a block per 512 bytes,
// so a queue of messages larger than that (a ray message is about 250 bytes) allocated and freed
// a block nearly every put and take: a tenth of an array run's time went to the heap. Used by
// TimedFifo (every machine's queues).
#include <cstddef>
#include <type_traits>
#include <utility>
#include <vector>

#include "modules/prefetch.hpp"

namespace rtsim::modules {

template <class T>
class RingBuffer {
 public:
  bool empty() const { return size_ == 0; }
  std::size_t size() const { return size_; }
  T& front() { return slots_[head_]; }
  const T& front() const { return slots_[head_]; }
  /// Prefetches the front item's lines (modules/prefetch.hpp), if there is one.
  void prefetch_front() const {
    if (size_ > 0) prefetch_object(slots_[head_]);
  }

  void push_back(T item) { append() = std::move(item); }

  /// Prefetches, for writing, the slot the next append() fills (if it has room for it).
  void prefetch_back() const {
    if (size_ == slots_.size()) return;
    std::size_t at = head_ + size_;
    if (at >= slots_.size()) at -= slots_.size();
    prefetch_object<PrefetchFor::kWrite>(slots_[at]);
  }

  /// Appends a slot and returns it for the caller to fill in place (a large item is then copied
  /// once, not into a parameter and again into the slot). It holds what a slot last held.
  T& append() {
    if (size_ == slots_.size()) grow();
    std::size_t at = head_ + size_;
    if (at >= slots_.size()) at -= slots_.size();
    ++size_;
    return slots_[at];
  }

  /// Removes the front item (the buffer must not be empty).
  void pop_front() {
    // What it held (a vector, a string) is released now, as a deque would.
    if constexpr (!std::is_trivially_destructible_v<T>) slots_[head_] = T{};
    if (++head_ == slots_.size()) head_ = 0;
    --size_;
  }

 private:
  void grow() {
    std::vector<T> bigger(slots_.empty() ? 4 : 2 * slots_.size());
    for (std::size_t i = 0; i < size_; ++i) {
      std::size_t at = head_ + i;
      if (at >= slots_.size()) at -= slots_.size();
      bigger[i] = std::move(slots_[at]);
    }
    slots_ = std::move(bigger);
    head_ = 0;
  }

  std::vector<T> slots_;
  std::size_t head_ = 0;
  std::size_t size_ = 0;
};

}  // namespace rtsim::modules
