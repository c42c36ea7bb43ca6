#pragma once
// A cleanup processor of the hidden-line pipeline (seed 000 Fig. 3-34, L1791-L1805, L1859-L1902):
// it turns the pairs of marked intersections (h) of a polygon into the segment's hidden parts,
// drops those that hide nothing of [0, 1], suppresses a segment hidden whole, and merges
// overlapping parts. It holds the segment and two hidden parts (four intersections, "fewer than
// three hundred bits", L1910); holding a third, it sends one on, after the segment: the
// cleanup processors between them sort the parts by a partial bubble sort (L1795-L1799), and a
// segment sent on before it proved hidden is caught by a later one ("debris", L1799).
//
// A hidden part is the positive end's intersection (v = 0, the part's upper end: the line is
// visible beyond it) and the negative end's (v = 1, its lower end). A part whose ends were sent
// singly by the plane processors is completed with the missing end at -infinity or +infinity,
// told by the parity p (L1803).
//
// One line the figure leaves out is here: a segment with no hidden part is sent on when the
// processor finishes with it (flush), as it must be before an unmarked intersection that follows
// it, or a visible segment would be lost.
#include <array>
#include <cstdint>
#include <vector>

#include "firmware/hiddenline/messages.hpp"

namespace rtsim::hiddenline {

class CleanupProcessor {
 public:
  void receive(const Message& m, std::vector<Message>& out);

  /// Segments it suppressed as hidden whole, hidden parts it merged or dropped.
  std::uint64_t suppressed() const { return suppressed_; }
  std::uint64_t merged() const { return merged_; }
  std::uint64_t dropped() const { return dropped_; }
  /// Cross multiplications (two multiplications each).
  std::uint64_t comparisons() const { return comparisons_; }

 private:
  void insert(const Intersection& i, std::vector<Message>& out);
  void sort_merge();
  void make_space(std::vector<Message>& out);
  void flush(std::vector<Message>& out);
  bool less(const LineParam& a, const LineParam& b) {
    ++comparisons_;
    return a < b;
  }

  bool have_segment_ = false;
  Segment segment_{};
  bool sent_ = false, suppress_ = false, p_ = true;
  int n_ = 0;
  std::array<Intersection, 4> part_{};  ///< int1 .. int4 of the figure
  std::uint64_t suppressed_ = 0, merged_ = 0, dropped_ = 0, comparisons_ = 0;
};

}  // namespace rtsim::hiddenline
