#include "platform/machines/pxpl5_raytrace/layout.hpp"

#include <algorithm>

namespace rtsim::platform::pxpl5 {

int Layout::compositor_of_lattice_row(int j) const {
  return compositor_of_row(std::min(j * rule.finest, height - 1));
}

long Layout::pixels_of_renderer(int k) const {
  const int tx = k % tiles_x(), ty = k / tiles_x();
  const int w = std::min(tile, width - tx * tile), h = std::min(tile, height - ty * tile);
  return static_cast<long>(std::max(0, w)) * std::max(0, h);
}

tasks::LatticeRange Layout::lattice_of_renderer(int k, int step) const {
  const tasks::SampleLattice grid(width, height, rule.finest * step);
  const int tx = k % tiles_x(), ty = k / tiles_x();
  const int x0 = tx * tile, y0 = ty * tile;
  const int x1 = std::min(x0 + tile, width), y1 = std::min(y0 + tile, height);
  return {grid.first_for(x0) * step, grid.first_for(y0) * step, grid.last_for(x1) * step + 1,
          grid.last_for(y1) * step + 1, 0};
}

std::vector<std::vector<int>> Layout::tiles_reading(bool rows, int step) const {
  const tasks::SampleLattice lat = lattice();
  const tasks::SampleLattice grid(width, height, rule.finest * step);
  const int n = rows ? lat.ny() : lat.nx();
  const int tiles = rows ? tiles_y() : tiles_x();
  const int extent = rows ? height : width;
  std::vector<std::vector<int>> out(static_cast<std::size_t>(n));
  for (int t = 0; t < tiles; ++t) {
    const int first = grid.first_for(t * tile),
              last = grid.last_for(std::min(t * tile + tile, extent));
    for (int i = first; i <= last && i * step < n; ++i)
      out[static_cast<std::size_t>(i * step)].push_back(t);
  }
  return out;
}

std::vector<Region> Layout::regions() const {
  const tasks::SampleLattice lat = lattice();
  const int f = rule.finest;
  std::vector<Region> out;
  if (scheme == Scheme::kRows) {
    // One lattice row each: every image row at finest 1, every f-th with the row past the last.
    for (int j = 0; j < lat.ny(); ++j) {
      const int y = j * f;
      out.push_back({0,
                     y,
                     width,
                     std::max(0, std::min(f, height - y)),
                     static_cast<int>(out.size()),
                     {0, j, lat.nx(), j + 1, 0}});
    }
    return out;
  }
  for (int y = 0; y < height; y += square)
    for (int x = 0; x < width; x += square) {
      Region g{x,
               y,
               std::min(square, width - x),
               std::min(square, height - y),
               static_cast<int>(out.size()),
               {}};
      const int i0 = x / f, j0 = y / f;
      if (rule.adaptive()) {
        // Its right and bottom edges replicated (65 x 65 for 64, L360).
        const int side = square / f;
        g.lattice = {i0, j0, std::min(i0 + side + 1, lat.nx()), std::min(j0 + side + 1, lat.ny()),
                     side};
      } else {
        g.lattice = {i0, j0, x + square >= width ? lat.nx() : (x + square) / f,
                     y + square >= height ? lat.ny() : (y + square) / f, 0};
      }
      out.push_back(g);
    }
  return out;
}

long Layout::positions_sent(const Region& g, int k, const tasks::RefinementSchedule& schedule,
                            int frame) const {
  long n = 0;
  const tasks::LatticeRange& r = g.lattice;
  const bool casts = schedule.plan(frame).cast_level >= 0;
  for (int j = r.j0; j < r.j1; ++j) {
    if (compositor_of_lattice_row(j) != k) continue;
    if (rule.adaptive()) {
      n += casts ? r.i1 - r.i0 : 0;
      continue;
    }
    for (int i = r.i0; i < r.i1; ++i) n += schedule.casts(i, j, frame);
  }
  return n;
}

}  // namespace rtsim::platform::pxpl5
