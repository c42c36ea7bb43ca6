#pragma once
// The merging processor (seed 000 §3.3.3, L1354-L1519): two streams of segments in raster order,
// each without overlaps, into one with the same properties holding every visible part of both.
// It holds one segment from each input and repeats the six-step algorithm (L1367-L1397):
//
//   1. classify: the visible segment V is the one the raster scan meets first — by line, then x,
//      then nearer z (L1367's concatenated key; the text orders x before z, as here);
//   2. apart: V ends before the other segment O begins: output V, fetch its successor;
//   3. V disappears: O's left end is in front of V's line: output V up to O, keep the rest of V,
//      and swap the roles;
//   4. intersect: O's right end is in front of V's line and of the line from O's left end to V's
//      right end: break both at the crossing, output V's left part, drop O's, swap (both right
//      parts start at the crossing's step, which O's keeps: with whole steps the seed's epsilon
//      after it would leave a one-step hole);
//   5. O protrudes: O ends after V: clip O to after V, output V, fetch V's successor;
//   6. O is hidden: drop it, fetch its successor.
//
// After a fetch the next pass classifies again; after a swap it goes on as classified (L1391).
// A line mark (splitting.hpp) is not a segment: the other input's segment goes out if it is on
// an earlier line (nothing from the mark's input can come before it); otherwise nothing from
// either input can come before the mark's line, and the mark goes on to the output — unless the
// output has reached that line already — so that the processors after it learn it too: one
// stage, stage 1's comparison.
// The arithmetic is integer, on the 12-bit words; the epsilon of L1421-L1427 is one step of x.
// What each pass needs of the five stages of Fig. 3-22 (L1457) times it: step 2 the first stage
// only, steps 3, 5 and 6 the first and the fifth (the segments overlap), step 4 all five.
// Where the seed's intersection coefficients disagree in sign (b_o = x_OR - x_OL against
// b_v = x_VL - x_VR, L1429-L1439), the lines are written one way.
#include <array>
#include <cstdint>
#include <optional>
#include <string_view>
#include <vector>

#include "firmware/scanline/segment.hpp"

namespace rtsim::scanline {

enum class MergeCase : std::uint8_t { Apart, Disappears, Intersects, Protrudes, Hidden, Mark };
inline constexpr int kMergeCases = 6;
inline constexpr std::array<std::string_view, kMergeCases> kMergeCaseNames = {
    "apart", "disappears", "intersects", "protrudes", "hidden", "mark"};
/// Fig. 3-22's stages a case needs (L1457, L1519: 3 us non-overlapping, 6 overlapping, 15
/// intersecting; a line mark dropped, stage 1).
inline constexpr std::array<int, kMergeCases> kMergeStages = {1, 2, 5, 2, 2, 1};

/// The passes of each case a processor (or a tree) made.
struct MergeTally {
  std::array<std::uint64_t, kMergeCases> passes{};
  MergeTally& operator+=(const MergeTally& o);
  std::uint64_t total() const;
};

class MergingProcessor {
 public:
  /// Whether it waits for a segment from input k (0 or 1) before its next pass.
  bool needs(int k) const { return !held_[static_cast<std::size_t>(k)].has_value(); }
  /// Hands it the next segment of input k.
  void give(int k, const Segment& s);
  /// Both dummies have met: its stream is over (the dummy was its last output).
  bool finished() const { return finished_; }

  struct Pass {
    MergeCase kind = MergeCase::Apart;
    std::optional<Segment> out;
    /// The input whose segment `out` is (a part of).
    int from = 0;
    /// The input that still holds another part of the same segment (-1: none): its journey
    /// forks (Segment::journey).
    int shares = -1;
    /// A segment dropped whole (hidden, or the second dummy): its journey ends unfinished.
    std::optional<std::uint32_t> dropped;
  };
  /// One pass of the algorithm; both inputs held and not finished.
  Pass pass();
  /// Gives the segment input k holds another journey (a fork's).
  void set_journey(int k, std::uint32_t journey) {
    if (held_[static_cast<std::size_t>(k)]) held_[static_cast<std::size_t>(k)]->journey = journey;
  }

 private:
  std::array<std::optional<Segment>, 2> held_;
  int visible_ = 0;
  bool classified_ = false;
  bool finished_ = false;
  Pass step();
  /// The line of its last output (segment or mark); -1 before the first.
  int last_line_ = -1;
  /// Passes since the last fetch: a bound that no pair of 12-bit segments reaches (each swap
  /// moves a break a step right), kept so that corrupted words cannot hold a processor forever.
  int since_fetch_ = 0;
};

/// The part of `s` from step a to step b (a <= b), ends interpolated.
Segment cut(const Segment& s, int a, int b);

/// Merges two whole streams (each ending with the dummy) as one processor would.
std::vector<Segment> merge_streams(const std::vector<Segment>& a, const std::vector<Segment>& b,
                                   MergeTally* tally);

}  // namespace rtsim::scanline
