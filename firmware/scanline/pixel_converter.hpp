#pragma once
// The pixel conversion processor at the tree's root (seed 000 §3.3.4, L1521-L1547): it takes the
// root's segments in raster order and turns them into pixels at video rate, interpolating the
// colour along each segment (r_i = (r_R - r_L) / (x_R - x_L), L1531-L1541) and putting the
// background colour wherever no segment covers (L1547). z is ignored.
//
// A pixel belongs to a segment if its centre lies in the steps the segment covers: pixel p of a
// row of `width` has its centre at (2p + 1) 4096 / (2 width) steps.
//
// Under root splitting (splitting.hpp) each of the 2^n strips has its own processor (L1596),
// whose segments are in the strip's coordinates: step x of strip k is step k 4096 / 2^n + x / 2^n
// of the screen. It paints the pixels whose centres lie in its strip.
#include <cstdint>
#include <vector>

#include "firmware/math.hpp"
#include "firmware/scanline/segment.hpp"

namespace rtsim::scanline {

/// A row's pixels as the processor writes them; `polygon` and `depth` (the id and depth
/// images) are filled where not null.
struct PixelRow {
  std::vector<Color> colour;
  std::vector<std::int64_t> polygon;  ///< -1: background
  std::vector<float> depth;           ///< the segment's z (0..1); infinity: background
};

/// Which strip of a split tree's screen a segment's coordinates are in (none split: the screen).
struct Strip {
  int levels = 0;  ///< the tree's split levels n: 2^n strips
  int index = 0;   ///< 0 .. 2^n - 1, left to right
};

/// The pixels of `width` whose centres `s` covers: [first, end), counted across the screen.
std::pair<int, int> covered_pixels(const Segment& s, int width, const Strip& strip = {});

/// The pixels of `width` whose centres lie in `strip`: [first, end).
std::pair<int, int> strip_pixels(int width, const Strip& strip);

/// Pixels [first, end) of `row` back to `background` (and no polygon, infinite depth, where the
/// row keeps them).
void blank_pixels(PixelRow& row, int first, int end, const Color& background);

/// Writes segment `s` into `row` (sized `width`).
void paint(const Segment& s, int width, PixelRow& row, const Strip& strip = {});

}  // namespace rtsim::scanline
