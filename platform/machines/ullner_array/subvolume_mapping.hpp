#pragma once
// Which processor of Ullner's ray-tracing array owns which subvolume (seed 000 §2.5, L767-L779,
// L860-L889). The modelling space is cut into n x n x n subvolumes; the array is R x C. One axis
// (the depth axis) is simulated inside the processors (Fig. 2-26); the other two, the cross
// section, are laid over the array: subvolume column a of n goes to processor column a C / n
// (several subvolumes a processor when n > C, L883-L889). Then, layer by layer along depth:
//   straight  every layer maps the same way: a processor owns a column of subvolumes (Fig. 2-26);
//   skew      layer d is shifted d processors to the right, wrapping round (Fig. 2-31): the
//             left and right edges of the array are joined (L866-L879);
//   torus     layers shift right and down in turn, never both at once, (d+1)/2 right and d/2
//             down, wrapping both ways (Fig. 2-32, L881).
// The thesis leaves the exact both-ways pattern open (note 000 §4.4: n_s layers allow only n_s - 1
// shifts): alternating is the choice here. Neighbouring subvolumes always land on the same or on
// neighbouring processors (the continuity rule, L866), which tests/ullner_array_test.cpp checks.
#include <string>

#include "firmware/accel/uniform_grid.hpp"
#include "modules/mesh_topology.hpp"

namespace rtsim::platform::ullner_array {

enum class Mapping { kStraight, kSkew, kTorus };

struct SubvolumeMapping {
  int rows = 8, cols = 8;  ///< processors
  int n = 8;               ///< subvolumes per axis
  int depth_axis = 2;      ///< simulated inside the processors
  int col_axis = 0;        ///< laid along the array's columns
  int row_axis = 1;        ///< along its rows
  bool flip_cols = false;  ///< processor column 0 holds the high end of col_axis
  bool flip_rows = false;  ///< processor row 0 holds the high end of row_axis
  Mapping mapping = Mapping::kStraight;

  bool wrap_cols() const { return mapping != Mapping::kStraight; }
  bool wrap_rows() const { return mapping == Mapping::kTorus; }

  modules::GridNode node_of(const accel::CellIndex& c) const {
    int a = c[col_axis], b = c[row_axis];
    if (flip_cols) a = n - 1 - a;
    if (flip_rows) b = n - 1 - b;
    int col = a * cols / n, row = b * rows / n;
    const int d = c[depth_axis];
    if (mapping == Mapping::kSkew) col = (col + d) % cols;
    if (mapping == Mapping::kTorus) {
      col = (col + (d + 1) / 2) % cols;
      row = (row + d / 2) % rows;
    }
    return {row, col};
  }

  /// Indices [lo, hi) along one axis (empty if lo >= hi).
  struct Range {
    int lo = 0, hi = 0;
  };
  /// The indices along col_axis whose cells of depth layer d processor column `col` owns, and
  /// along row_axis those processor row `row` owns: node_of(c) == {row, col} exactly for the
  /// cells of layer d in owned_along_cols x owned_along_rows (node_of inverted, so that a
  /// processor finds its cells in a block without testing each).
  Range owned_along_cols(int col, int d) const {
    int shift = 0;
    if (mapping == Mapping::kSkew) shift = d % cols;
    if (mapping == Mapping::kTorus) shift = ((d + 1) / 2) % cols;
    return owned(((col - shift) % cols + cols) % cols, cols, flip_cols);
  }
  Range owned_along_rows(int row, int d) const {
    const int shift = mapping == Mapping::kTorus ? (d / 2) % rows : 0;
    return owned(((row - shift) % rows + rows) % rows, rows, flip_rows);
  }

 private:
  /// The indices a with a * procs / n == u (before the flip): [ceil(u n / procs), ceil((u + 1)
  /// n / procs)); flipped, n - 1 - a.
  Range owned(int u, int procs, bool flip) const {
    const int lo = (u * n + procs - 1) / procs, hi = ((u + 1) * n + procs - 1) / procs;
    return flip ? Range{n - hi, n - lo} : Range{lo, hi};
  }
};

}  // namespace rtsim::platform::ullner_array
