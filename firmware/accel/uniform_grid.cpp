#include "firmware/accel/uniform_grid.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace rtsim::accel {
namespace {

bool finite_box(const Bounds& b) { return !b.empty() && is_finite(b.lo) && is_finite(b.hi); }

/// Range of cells [first, last] along one axis touched by [lo, hi], or false if none.
bool cell_range(double lo, double hi, double box_lo, double cell, int n, int& first, int& last) {
  // Position in cell units; the plane i_x sits at f = i_x (seed 000 L2122).
  const double f_lo = (lo - box_lo) / cell - kCellMembershipMargin;
  const double f_hi = (hi - box_lo) / cell + kCellMembershipMargin;
  if (f_hi < 0.0 || f_lo > static_cast<double>(n)) return false;
  first = static_cast<int>(std::clamp(std::floor(f_lo), 0.0, static_cast<double>(n - 1)));
  last = static_cast<int>(std::clamp(std::floor(f_hi), 0.0, static_cast<double>(n - 1)));
  return true;
}

}  // namespace

UniformGrid::UniformGrid(std::span<const Bounds> prim_bounds, const Bounds& scene_box,
                         GridDivisions n)
    : box_(scene_box), n_(n), primitive_count_(prim_bounds.size()) {
  if (n.x < 1 || n.y < 1 || n.z < 1) {
    throw std::invalid_argument("UniformGrid: divisions must be >= 1 per axis, got " +
                                std::to_string(n.x) + "x" + std::to_string(n.y) + "x" +
                                std::to_string(n.z));
  }
  if (!finite_box(scene_box)) {
    throw std::invalid_argument("UniformGrid: the scene box is empty or not finite");
  }
  if (n.cells() > kMaxGridCells) {
    throw std::length_error("UniformGrid: " + std::to_string(n.cells()) +
                            " subvolumes exceed kMaxGridCells = " + std::to_string(kMaxGridCells));
  }
  if (prim_bounds.size() > std::numeric_limits<std::uint32_t>::max()) {
    throw std::length_error("UniformGrid: more than 2^32 primitives");
  }
  // Widen flat axes so every subvolume has positive width (see kFlatAxisWidening).
  const double largest = max_abs_component(box_.extent());
  for (int a = 0; a < 3; ++a) {
    if (box_.hi[a] - box_.lo[a] <= 0.0) {
      const double half = 0.5 * (largest > 0.0 ? kFlatAxisWidening * largest : 1.0);
      box_.lo[a] -= half;
      box_.hi[a] += half;
    }
    // Grid planes x = ((x_max - x_min)/n_x) i_x + x_min (seed 000 L2122).
    cell_size_[a] = (box_.hi[a] - box_.lo[a]) / n_[a];
  }

  // Two passes (count, then fill) so the only storage is the final CSR arrays.
  const std::size_t cells = n_.cells();
  offsets_.assign(cells + 1, 0);
  std::uint64_t references = 0;
  for (const Bounds& b : prim_bounds) {
    CellIndex first, last;
    if (!cells_touched(b, first, last)) {
      ++skipped_;
      continue;
    }
    for (int z = first.z; z <= last.z; ++z)
      for (int y = first.y; y <= last.y; ++y)
        for (int x = first.x; x <= last.x; ++x) {
          ++offsets_[linear_index({x, y, z}) + 1];
          ++references;
        }
  }
  if (references > std::numeric_limits<std::uint32_t>::max()) {
    throw std::length_error("UniformGrid: " + std::to_string(references) +
                            " subvolume references exceed 32-bit offsets; use fewer divisions");
  }
  for (std::size_t c = 0; c < cells; ++c) offsets_[c + 1] += offsets_[c];
  slots_.resize(references);
  // Fill: `cursor` reuses a copy of the start offsets. Slots are visited in ascending order, so
  // every list comes out sorted.
  std::vector<std::uint32_t> cursor(offsets_.begin(), offsets_.end() - 1);
  for (std::size_t slot = 0; slot < prim_bounds.size(); ++slot) {
    CellIndex first, last;
    if (!cells_touched(prim_bounds[slot], first, last)) continue;
    for (int z = first.z; z <= last.z; ++z)
      for (int y = first.y; y <= last.y; ++y)
        for (int x = first.x; x <= last.x; ++x)
          slots_[cursor[linear_index({x, y, z})]++] = static_cast<std::uint32_t>(slot);
  }
}

bool UniformGrid::cells_touched(const Bounds& b, CellIndex& first, CellIndex& last) const {
  if (!finite_box(b)) return false;
  return cell_range(b.lo.x, b.hi.x, box_.lo.x, cell_size_.x, n_.x, first.x, last.x) &&
         cell_range(b.lo.y, b.hi.y, box_.lo.y, cell_size_.y, n_.y, first.y, last.y) &&
         cell_range(b.lo.z, b.hi.z, box_.lo.z, cell_size_.z, n_.z, first.z, last.z);
}

Bounds UniformGrid::cell_bounds(const CellIndex& c) const {
  Bounds b;
  for (int a = 0; a < 3; ++a) {
    // x = ((x_max - x_min)/n_x) i_x + x_min, seed 000 L2122; the last plane is x_max exactly.
    b.lo[a] = cell_size_[a] * c[a] + box_.lo[a];
    b.hi[a] = c[a] + 1 == n_[a] ? box_.hi[a] : cell_size_[a] * (c[a] + 1) + box_.lo[a];
  }
  return b;
}

std::size_t UniformGrid::occupied_cell_count() const {
  std::size_t n = 0;
  for (std::size_t c = 0; c + 1 < offsets_.size(); ++c) n += offsets_[c + 1] != offsets_[c];
  return n;
}

}  // namespace rtsim::accel
