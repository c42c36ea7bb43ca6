#pragma once
// What the scan-line tree's processors pass one another (seed 000 §3.3): a polygon's edge chains
// from its T&C processor to its scan conversion processor (Fig. 3-15's entries, 11 numbers each),
// and segments (11 words of 12 bits, 132 bits, L1340, L1348) from scan converters and merging
// processors up the tree to the pixel conversion processor.
#include <cstdint>
#include <systemc>

#include "firmware/scanline/segment.hpp"
#include "firmware/scanline/tc_program.hpp"

namespace rtsim::platform::ullner_scanline_tree {

struct ChainsMessage {
  scanline::EdgeChains chains;
  /// Its size: 12 bits a number (L1344: the scan converter's edge-list memory).
  std::uint64_t bits() const {
    return static_cast<std::uint64_t>(chains.left.size() + chains.right.size()) *
           scanline::kEdgeEntryWords * scanline::kWordBits;
  }
};

struct SegmentMessage {
  scanline::Segment segment;
  sc_core::sc_time arrived;  ///< when its last bit reached the queue
};

/// The latency probe's stages (--latency-probe follows segments from the scan converter that
/// formed them to the pixels they became), in the order a segment meets them.
struct ProbeStages {
  int scp = -1, scp_link = -1, mp_in = -1, mp = -1, mp_link = -1, pcp_in = -1, pcp = -1;
  /// A split root's splitting processors: its input, the test and break, its output queues and
  /// their links.
  int sp_in = -1, sp = -1, sp_out = -1, sp_link = -1;
};
inline constexpr std::uint64_t kSegmentBits = scanline::kSegmentBits;

}  // namespace rtsim::platform::ullner_scanline_tree
