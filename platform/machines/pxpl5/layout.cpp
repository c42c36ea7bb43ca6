#include "platform/machines/pxpl5/layout.hpp"

#include <algorithm>

namespace rtsim::platform::pxpl5 {

long Layout::pixels_of_compositor(int k) const {
  long rows = 0;
  for (int y = 0; y < height; ++y) rows += compositor_of_row(y) == k;
  return rows * width;
}

long Layout::pixels_of_renderer(int k) const {
  const int tx = k % tiles_x(), ty = k / tiles_x();
  const int w = std::min(tile, width - tx * tile), h = std::min(tile, height - ty * tile);
  return static_cast<long>(std::max(0, w)) * std::max(0, h);
}

std::vector<Region> Layout::regions(Scheme scheme, int square) const {
  std::vector<Region> out;
  if (scheme == Scheme::kRows) {
    for (int y = 0; y < height; ++y) out.push_back({0, y, width, 1, static_cast<int>(out.size())});
    return out;
  }
  for (int y = 0; y < height; y += square)
    for (int x = 0; x < width; x += square)
      out.push_back({x, y, std::min(square, width - x), std::min(square, height - y),
                     static_cast<int>(out.size())});
  return out;
}

}  // namespace rtsim::platform::pxpl5
