#pragma once
// Root splitting (seed 000 §3.3.5, L1561-L1637; note 000-ch3 §2.8): the top n levels of the
// merging tree are replaced by n stages of splitting processors and merging processors. The
// 2^n subtrees left at depth n each feed a splitting processor; every stage splits each stream
// about its strip's centre into a left and a right part and merges the parts of two streams
// per side, so that after n stages each of 2^n strips of the screen has one stream and its own
// pixel conversion processor (L1596). n 2^n splitting processors and n 2^n merging processors,
// (n - 1) 2^n + 1 more than the 2^n - 1 the n levels held (L1594).
//
// A splitting processor (Fig. 3-25, L1610) splits about the centre of the screen whatever its
// position and re-scales its outputs to full-screen coordinates by single-bit shifts (L1631):
// x in [0, 2047] goes left as 2x, x in [2048, 4095] goes right as 2(x - 2048); a right end x_r
// covers up to x_r + 1 (segment.hpp), so it becomes 2 x_r + 1 and the parts cover their half of
// the steps exactly. A segment across the centre is cut at the last step of the left half and
// the first of the right (the t- and t+ = t- + epsilon of Fig. 3-25, one step apart), its z and
// colours interpolated there. The dummy goes to both outputs.
//
// Line marks: a merging processor fed by a splitting processor cannot pass a segment on until
// it holds one from each input, and an output that gets nothing for many lines (the subtree's
// polygons all on the other half there) would hold it up until the other output's queue filled
// with all of those lines' segments: the tree deadlocks, whatever the queues' depth. The seed's
// one-line bound on the queues (L1633-L1637) holds only if a merging processor learns that a
// line is over on an input that sends nothing for it. So a splitting processor that sends a
// segment of line y to one output, having sent the other nothing of line y, sends the other a
// line mark (segment.hpp): at most one a line an output. A merging processor passes a mark on
// when neither input can send anything before its line (merging.hpp), and a splitting
// processor that takes a mark passes it to each output that has not reached its line, so the
// news that a line has begun travels down every path of the split network to the strips' pixel
// conversion processors, which ignore it (as conservative simulators' null messages do). The
// seed does not describe this; it is this model's, named so.
//
// Stage s (0 first) holds 2^s strips; each strip's 2^(n-s) streams are paired in order (2j with
// 2j + 1), and the pair's left parts merge into stream j of the strip's left half, its right
// parts into stream j of its right half (Fig. 3-24: two subtrees a pair of splitters, their
// left outputs one merging processor).
#include <cstdint>
#include <optional>
#include <utility>
#include <vector>

#include "firmware/scanline/merging.hpp"
#include "firmware/scanline/segment.hpp"

namespace rtsim::scanline {

/// The deepest split the tree takes (L1594: n = 6 gives about 640 segments a line, "more than
/// can be displayed").
inline constexpr int kMaxSplitLevels = 6;

/// The x of the screen's centre in steps: the left half is [0, kSplitAt), the right the rest.
inline constexpr int kSplitAt = kWordSteps / 2;

/// What one splitting processor's input segment becomes (Fig. 3-25).
struct SplitParts {
  std::optional<Segment> left, right;
  bool broken = false;  ///< it crossed the centre and was cut
};
SplitParts split_segment(const Segment& s);

/// A splitting processor: what each segment it takes sends to each output (a part, a line
/// mark, or nothing).
class SplittingProcessor {
 public:
  struct Sent {
    std::optional<Segment> to[2];  ///< left, right
    bool broken = false;
  };
  Sent take(const Segment& s);

 private:
  int last_line_[2] = {-1, -1};  ///< the line last sent to each output
};

/// A splitting processor's work on a whole stream: its left and right output streams, each
/// ending with the dummy (line marks included); `broken` (if not null) adds the segments it
/// cut.
std::pair<std::vector<Segment>, std::vector<Segment>> split_stream(const std::vector<Segment>& in,
                                                                   std::uint64_t* broken);

/// The leaves [lo, hi) of each of the 2^levels subtrees at depth `levels` of the balanced tree
/// over `leaves` leaves (tree_frame.hpp's halving: [lo, mid) and [mid, hi)), left to right.
/// Needs leaves >= 2^levels.
std::vector<std::pair<std::size_t, std::size_t>> subtree_ranges(std::size_t leaves, int levels);

/// Processor counts of a tree split n levels (L1594).
struct SplitCounts {
  std::uint64_t splitters = 0;      ///< n 2^n
  std::uint64_t extra_merging = 0;  ///< (n - 1) 2^n + 1 (0 for n = 0)
};
SplitCounts split_counts(int levels);

/// Where a stream of the split network goes: stage `stage`'s pair `pair` of strip `strip` (the
/// network's wiring, shared by the functional evaluation and the machine).
struct SplitPair {
  std::size_t first = 0, second = 0;  ///< the two streams (indices into the stage's list)
  std::size_t left = 0, right = 0;    ///< the indices of the merged left and right streams
};
/// Stage `stage` of a network of `levels`: its 2^(levels-1) pairs. Streams are listed strip by
/// strip (2^stage strips of 2^(levels - stage) streams) before the stage and after it.
std::vector<SplitPair> split_stage(int levels, int stage);

/// The split network on the 2^levels subtree streams (left to right): one stream a strip, left
/// to right, each in its strip's own coordinates. `tally` adds the merging processors' passes,
/// `broken` the segments the splitters cut.
std::vector<std::vector<Segment>> split_network(std::vector<std::vector<Segment>> roots, int levels,
                                                MergeTally* tally, std::uint64_t* broken);

}  // namespace rtsim::scanline
