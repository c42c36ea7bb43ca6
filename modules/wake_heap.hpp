#pragma once
// The WakeQueue's pending wakes (modules/wake_queue.hpp): a 4-ary min-heap of (time, sequence
// number, client), earliest time first and, at equal times, the lower sequence number first.
//
// Why not std::priority_queue: a wake is popped and another pushed for nearly every activation
// of a processor (half a million a frame on gaudet-pert, a million on a 32 x 32 array), and a
// binary heap of 24-byte entries spends that in mispredicted comparisons a level. Here an entry
// is 16 bytes, the sequence number and the client packed in one word, so that a node's four
// children take 64 bytes, and two entries compare as one 128-bit number, without a branch.
// Since every key is distinct (sequence numbers are), the order in which wakes leave is that of
// any correct priority queue: the queue's answers do not depend on the heap's shape.
#include <cstddef>
#include <cstdint>
#include <vector>

namespace rtsim::modules {

class WakeHeap {
 public:
  /// Clients are numbered below 2^kClientBits; sequence numbers below 2^(64 - kClientBits).
  static constexpr unsigned kClientBits = 24;
  static constexpr std::uint64_t kMaxClients = std::uint64_t{1} << kClientBits;
  static constexpr std::uint64_t kMaxSeq = std::uint64_t{1} << (64 - kClientBits);

  struct Entry {
    std::uint64_t t;    ///< ticks (sc_time values)
    std::uint64_t key;  ///< seq << kClientBits | client
    std::uint64_t seq() const { return key >> kClientBits; }
    std::uint32_t client() const { return static_cast<std::uint32_t>(key & (kMaxClients - 1)); }
  };

  bool empty() const { return heap_.empty(); }
  std::size_t size() const { return heap_.size(); }
  const Entry& top() const { return heap_.front(); }

  /// `client` < kMaxClients and `seq` < kMaxSeq (the caller checks).
  void push(std::uint64_t t, std::uint64_t seq, std::uint32_t client) {
    Entry e{t, seq << kClientBits | client};
    std::size_t i = heap_.size();
    heap_.push_back(e);
    while (i > 0) {
      const std::size_t parent = (i - 1) / 4;
      if (!before(e, heap_[parent])) break;
      heap_[i] = heap_[parent];
      i = parent;
    }
    heap_[i] = e;
  }

  void pop() {
    const Entry last = heap_.back();
    heap_.pop_back();
    const std::size_t n = heap_.size();
    if (n == 0) return;
    const Key last_key = key(last);
    std::size_t i = 0;
    for (;;) {
      const std::size_t first = 4 * i + 1;
      std::size_t least;
      if (first + 4 <= n) {
        // Four children: a tournament of three comparisons, each turned into arithmetic or a
        // conditional move, not a branch.
        const Entry* c = &heap_[first];
        const std::size_t a = static_cast<std::size_t>(key(c[1]) < key(c[0]));
        const std::size_t b = 2 + static_cast<std::size_t>(key(c[3]) < key(c[2]));
        least = first + (key(c[b]) < key(c[a]) ? b : a);
      } else if (first < n) {
        least = first;
        for (std::size_t k = first + 1; k < n; ++k)
          if (key(heap_[k]) < key(heap_[least])) least = k;
      } else {
        break;
      }
      if (!(key(heap_[least]) < last_key)) break;
      heap_[i] = heap_[least];
      i = least;
    }
    heap_[i] = last;
  }

 private:
  // The order as one 128-bit number (time, then key), which compares without a branch.
  __extension__ using Key = unsigned __int128;
  static Key key(const Entry& e) { return static_cast<Key>(e.t) << 64 | e.key; }
  static bool before(const Entry& a, const Entry& b) { return key(a) < key(b); }

  std::vector<Entry> heap_;
};

}  // namespace rtsim::modules
