#pragma once
// A frame of the scan-line tree evaluated functionally (seed 000 §3.3, Fig. 3-9): every T&C
// processor runs the broadcast program on its polygon, its scan conversion processor turns the
// edge chains into segments, a balanced binary tree of merging processors merges the leaves'
// streams, and the pixel conversion processor paints the root's stream. Each merging processor's
// output depends only on its two input streams, so the timed tree, whatever its waits, delivers
// exactly this stream: the machine's functional twin.
//
// Leaves: one T&C processor a polygon. Which polygon sits at which leaf is the subtree balancing
// of L1592: the scene's order shuffled (random, the default), or the scene's order.
#include <cstdint>
#include <vector>

#include "firmware/scanline/merging.hpp"
#include "firmware/scanline/pixel_converter.hpp"
#include "firmware/scanline/segment.hpp"
#include "firmware/scanline/tc_frame.hpp"

namespace rtsim::scanline {

enum class LeafOrder : std::uint8_t { Random, Scene, Subvolume };

struct LeafPlan {
  LeafOrder order = LeafOrder::Random;
  std::uint64_t seed = 1983;  ///< Random: the shuffle's seed
  int subvolumes = 8;         ///< Subvolume: the modelling space's cells a side
};

/// The polygon at each of `leaves` leaves (leaves >= polygons.size()): a permutation of
/// 0 .. leaves - 1, where an index past the last polygon is an idle leaf. Random shuffles the
/// polygons with a fixed generator (the same seed, the same tree) and puts the idle leaves
/// last; Scene keeps the scene's order; Subvolume sorts the polygons by the cell of a
/// subvolumes^3 grid over their bounds that holds their centroid, and deals that list (idle
/// leaves last) down the balanced tree, alternately to the right and the left subtree at every
/// node, so each subtree at every depth holds an even share of every subvolume.
std::vector<std::uint32_t> leaf_assignment(const std::vector<TcPolygon>& polygons,
                                           std::size_t leaves, const LeafPlan& plan);

/// The T&C processors' edge chains, polygon by polygon: `program` broadcast to a processor a
/// polygon; `executed` (if not null) adds the instructions they executed (not shut down).
std::vector<EdgeChains> transform_and_clip(const BroadcastProgram& program,
                                           const std::vector<TcPolygon>& polygons,
                                           std::uint64_t* executed);
/// The same for the frame's polygons with the program of its literals.
std::vector<EdgeChains> transform_and_clip(const TcFrame& frame);

/// The merging tree over `streams` (one a leaf, in leaf order): leaves [lo, hi) merge as
/// [lo, mid) with [mid, hi), mid = (lo + hi) / 2.
std::vector<Segment> merge_tree(const std::vector<std::vector<Segment>>& streams,
                                MergeTally* tally);

struct TreeFrame {
  /// Each strip's stream, left to right, the dummy last (one, the root's, unsplit).
  std::vector<std::vector<Segment>> strips;
  MergeTally tally;
  std::uint64_t leaf_segments = 0;  ///< segments the scan conversion processors sent
  std::uint64_t broken = 0;         ///< segments the splitting processors cut
};

/// The frame on a screen of `lines` scan lines (x is 4096 steps whatever the width), the top
/// `split_levels` levels of the tree split (needs 2^split_levels leaves).
TreeFrame evaluate_tree(const TcFrame& frame, int lines,
                        const std::vector<std::uint32_t>& leaf_polygon, int split_levels = 0);

/// The pixel conversion processors' image of the strips' streams (2^split_levels of them): rows
/// of `width`, top first, with the id and depth images if asked for.
std::vector<PixelRow> paint_frame(const std::vector<std::vector<Segment>>& strips, int width,
                                  int height, const Color& background, bool ids, bool depth);
/// Rows of background (and no id, infinite depth), for processors to paint into.
std::vector<PixelRow> blank_frame(int width, int height, const Color& background, bool ids,
                                  bool depth);

}  // namespace rtsim::scanline
