#pragma once
// The scan conversion processor (seed 000 §3.3.2, L1338-L1352): two endpoint trackers walk the
// left and right edge chains the T&C processor sent (Fig. 3-15), a shared counter steps the scan
// line from the top, and a segment goes out for every line the polygon crosses, in raster order.
//
// A line's centre is at y = 1 - (2k + 1) / lines (the T&C processor's screen y, up); an edge
// covers the lines whose centre lies at or below its top and above its bottom, so a level edge
// covers none (the termination test of L1346). The ends are the chains' values there, x to 12-bit
// steps across the screen (a segment's right word is the last step it covers), z and colours to
// 12 bits. A line whose segment would cover no step gets none.
#include <cstdint>
#include <vector>

#include "firmware/scanline/segment.hpp"
#include "firmware/scanline/tc_program.hpp"

namespace rtsim::scanline {

/// The segments of one polygon on a screen of `lines` scan lines, then the dummy.
std::vector<Segment> scan_convert(const EdgeChains& chains, int lines, std::uint32_t polygon);

}  // namespace rtsim::scanline
