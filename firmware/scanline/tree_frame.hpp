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

/// The polygon at each leaf: a permutation of 0 .. polygons - 1, shuffled by `seed` if
/// `random` (a deterministic generator: the same seed, the same tree).
std::vector<std::uint32_t> leaf_assignment(std::size_t polygons, bool random, std::uint64_t seed);

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
  std::vector<Segment> root;  ///< the root's stream, the dummy last
  MergeTally tally;
  std::uint64_t leaf_segments = 0;  ///< segments the scan conversion processors sent
};

/// The frame on a screen of `lines` scan lines (x is 4096 steps whatever the width).
TreeFrame evaluate_tree(const TcFrame& frame, int lines,
                        const std::vector<std::uint32_t>& leaf_polygon);

/// The pixel conversion processor's image of a root stream: rows of `width`, top first, with
/// the id and depth images if asked for.
std::vector<PixelRow> paint_frame(const std::vector<Segment>& root, int width, int height,
                                  const Color& background, bool ids, bool depth);

}  // namespace rtsim::scanline
