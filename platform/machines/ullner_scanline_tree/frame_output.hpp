#pragma once
// The tree's pixels as a run delivers them, the same for the machine's pixel conversion processor
// and for its functional twin: the colours into the frame buffer (one sample a pixel), the id
// image as the scene primitive of the polygon painted there, the depth image as the distance
// along the pixel's ray that the segment's 12-bit z stands for (z = f (e - n) / ((f - n) e) after
// the perspective division, L987-L999, so e = n f / (f - z (f - n))).
#include <cstdint>
#include <vector>

#include "firmware/raster/view_transform.hpp"
#include "firmware/scanline/pixel_converter.hpp"
#include "platform/functional/frame_state.hpp"

namespace rtsim::platform::ullner_scanline_tree {

void deliver_rows(const std::vector<scanline::PixelRow>& rows, const raster::ViewTransform& view,
                  const std::vector<std::uint32_t>& primitive_of_polygon,
                  functional::FrameState& frame);

}  // namespace rtsim::platform::ullner_scanline_tree
