#pragma once
// Ullner's uniform grid of subvolumes (seed 000 L592-L606, Appendix B L2112-L2171).
//
// The modelling space [min, max] is cut into n_x * n_y * n_z rectangular parallelepipeds (the
// space "need not be cubic", L2118-L2122). Each subvolume holds the list of polygon addresses
// whose bounds touch it: the auxiliary processor's "local memory, which is partitioned by
// subvolume, for storing polygon addresses" (L596). A polygon is stored once in the
// intersection processor and referenced from every subvolume it touches (one level of
// indirection, L596).
//
// Layout: compressed sparse rows. offsets[c] .. offsets[c+1] index into one array of primitive
// slots, so an empty subvolume costs one 32-bit offset and nothing else, and a reference costs
// one 32-bit slot. (1,000,000 polygons with the automatic divisions need a few tens of MB.)
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "firmware/bounds.hpp"

namespace rtsim::accel {

/// Subdivisions per axis (n_x, n_y, n_z of seed 000 L2118).
struct GridDivisions {
  int x = 1;
  int y = 1;
  int z = 1;

  int operator[](int axis) const { return axis == 0 ? x : (axis == 1 ? y : z); }
  std::size_t cells() const {
    return static_cast<std::size_t>(x) * static_cast<std::size_t>(y) * static_cast<std::size_t>(z);
  }
  friend bool operator==(const GridDivisions&, const GridDivisions&) = default;
};

/// A subvolume's integer coordinates, 0-based: 0 <= x < n_x. (Ullner counts 1..n_x, L2136;
/// the DDA's as-printed variant keeps his 1-based numbering internally.)
struct CellIndex {
  int x = 0;
  int y = 0;
  int z = 0;

  int operator[](int axis) const { return axis == 0 ? x : (axis == 1 ? y : z); }
  friend bool operator==(const CellIndex&, const CellIndex&) = default;
};

/// Largest number of subvolumes a grid may have. A 32-bit offset per cell plus the slot array
/// must stay well inside the 2 GiB a run may use, and ullner-peripheral holds two grids (its
/// functional twin's and its auxiliary processor's): 2^27 = 512^3 cells is 512 MiB of offsets
/// each (at 2^28, 645^3 cells, a run took 2.6 GB). Assumption, not in the seed.
inline constexpr std::size_t kMaxGridCells = std::size_t{1} << 27;

/// A primitive whose bounds reach within this fraction of a cell width of a grid plane is also
/// stored in the subvolume on the other side of that plane. Bounds from the kernels are tight,
/// and a hit computed in floating point may land a rounding error outside them; without the
/// margin a ray crossing the plane exactly there could miss the primitive in both cells.
inline constexpr double kCellMembershipMargin = 1e-9;

/// When the scene box is flat along an axis (e.g. a single polygon in z = 0), the grid box is
/// widened to this fraction of its largest extent (or to 1 for a point-like scene) so that
/// every cell has a positive width and a = (max - min)/(d n) is never 0.
inline constexpr double kFlatAxisWidening = 1e-6;

class UniformGrid {
 public:
  /// Builds the subvolume lists. prim_bounds[i] are the bounds of primitive slot i (the
  /// "polygon address" stored in the lists). scene_box is the modelling space; primitives
  /// outside it are clipped to it, empty or non-finite bounds are not stored anywhere
  /// (skipped_count() tells how many). Throws std::invalid_argument for a division count < 1
  /// or a non-finite/empty scene box, std::length_error beyond kMaxGridCells cells or 2^32
  /// references.
  UniformGrid(std::span<const Bounds> prim_bounds, const Bounds& scene_box, GridDivisions n);

  const Bounds& box() const { return box_; }
  GridDivisions divisions() const { return n_; }
  std::size_t cell_count() const { return n_.cells(); }
  Vec3 cell_size() const { return cell_size_; }

  std::size_t linear_index(const CellIndex& c) const {
    return (static_cast<std::size_t>(c.z) * static_cast<std::size_t>(n_.y) +
            static_cast<std::size_t>(c.y)) *
               static_cast<std::size_t>(n_.x) +
           static_cast<std::size_t>(c.x);
  }
  /// The polygon addresses (primitive slots) of one subvolume, ascending.
  std::span<const std::uint32_t> cell(const CellIndex& c) const {
    const std::size_t i = linear_index(c);
    return {slots_.data() + offsets_[i], slots_.data() + offsets_[i + 1]};
  }
  /// Bounds of one subvolume (planes from seed 000 L2122).
  Bounds cell_bounds(const CellIndex& c) const;
  /// The block of subvolumes [first, last] that bounds `b` touch (the rule the lists are built
  /// by, kCellMembershipMargin included); false if none (empty, non-finite or outside).
  bool cells_touched(const Bounds& b, CellIndex& first, CellIndex& last) const;

  std::size_t primitive_count() const { return primitive_count_; }
  std::size_t skipped_count() const { return skipped_; }
  std::size_t reference_count() const { return slots_.size(); }
  std::size_t occupied_cell_count() const;  ///< n_o of seed 000 L618
  /// Bytes held by the subvolume lists (offsets + slots), the auxiliary processor's memory.
  std::size_t memory_bytes() const {
    return offsets_.capacity() * sizeof(std::uint32_t) + slots_.capacity() * sizeof(std::uint32_t);
  }

 private:
  Bounds box_;
  GridDivisions n_;
  Vec3 cell_size_{1.0};
  std::size_t primitive_count_ = 0;
  std::size_t skipped_ = 0;
  std::vector<std::uint32_t> offsets_;  ///< cell_count()+1 entries
  std::vector<std::uint32_t> slots_;    ///< primitive slots, grouped by cell
};

}  // namespace rtsim::accel
