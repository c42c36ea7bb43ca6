#pragma once
// What the hidden-line pipeline's visible pieces become on the way out: a line drawing of the
// frame (black lines on white paper) and the same lines as a vector file (SVG).
//
// The rasterization: each piece's ends go from screen units to pixels (ScreenScene::pixel_x,
// pixel_y), the piece is clipped to the image's rectangle, and n + 1 points are taken at equal
// steps along it, n the piece's length in pixels along its longer axis rounded up; the pixel
// each point falls in (x right, y down, pixel (i, j) covering [i, i + 1) x [j, j + 1)) is
// inked. A piece of zero length inks its one pixel. The same pieces always ink the same pixels.
#include <cstdint>
#include <string>
#include <vector>

#include "firmware/hiddenline/pipe.hpp"
#include "firmware/hiddenline/screen_scene.hpp"

namespace rtsim::hiddenline {

/// One flag a pixel, row by row from the top: set where a visible line passes.
std::vector<std::uint8_t> ink_pixels(const std::vector<VisiblePiece>& pieces,
                                     const ScreenScene& screen, int width, int height);

/// The pieces as an SVG drawing of `width` x `height` pixels (one <line> a piece, in pixel
/// coordinates, three decimals), white paper and black lines.
std::string svg_drawing(const std::vector<VisiblePiece>& pieces, const ScreenScene& screen,
                        int width, int height);

}  // namespace rtsim::hiddenline
