#pragma once
// The kit's router (DESIGN.md "The three layers": a router with pluggable topology and routing):
// a two-dimensional grid of nodes, each joined to its four neighbours, with the edges optionally
// wrapped round (a ring of columns, a torus), and dimension-order routing over it: columns first,
// then rows, each the shorter way round when the edge wraps. Deterministic, deadlock-free on a
// mesh, and every hop is between neighbours.
//
// Used by ullner-array (seed 000 §2.5: an R x C array of processors on four bidirectional links,
// wrap links for the skewed mappings, L866-L881); the token ring's and Wang's machines build other
// topologies on the same interface.
#include <array>
#include <cstdint>
#include <optional>
#include <string_view>

namespace rtsim::modules {

/// A link direction out of a node.
enum class Direction : std::uint8_t { kNorth = 0, kEast = 1, kSouth = 2, kWest = 3 };
inline constexpr std::array<Direction, 4> kDirections = {Direction::kNorth, Direction::kEast,
                                                         Direction::kSouth, Direction::kWest};
/// "n", "e", "s", "w": names of ports and links.
std::string_view direction_name(Direction d);
Direction opposite(Direction d);

struct GridNode {
  int row = 0;
  int col = 0;
  friend bool operator==(const GridNode&, const GridNode&) = default;
};

class MeshTopology {
 public:
  /// `wrap_cols`: the left and right edges are joined; `wrap_rows`: top and bottom (a torus).
  MeshTopology(int rows, int cols, bool wrap_rows, bool wrap_cols)
      : rows_(rows), cols_(cols), wrap_rows_(wrap_rows), wrap_cols_(wrap_cols) {}

  int rows() const { return rows_; }
  int cols() const { return cols_; }
  int nodes() const { return rows_ * cols_; }
  bool wrap_rows() const { return wrap_rows_; }
  bool wrap_cols() const { return wrap_cols_; }
  int index(const GridNode& n) const { return n.row * cols_ + n.col; }
  GridNode node(int index) const { return {index / cols_, index % cols_}; }

  /// The neighbour through `d`, or nothing off an unwrapped edge (an unconnected link).
  std::optional<GridNode> neighbour(const GridNode& n, Direction d) const;
  /// The direction of the first hop from `from` toward `to` (from != to): columns first.
  Direction next_hop(const GridNode& from, const GridNode& to) const;
  /// Hops on that route.
  int hops(const GridNode& from, const GridNode& to) const;
  /// The direction from `from` to its neighbour `to`, or nothing if they are not neighbours.
  std::optional<Direction> direction_to(const GridNode& from, const GridNode& to) const;

 private:
  /// Signed steps along one axis of `size` (wrapped: the shorter way, ties going up).
  static int delta(int from, int to, int size, bool wrap);
  int rows_, cols_;
  bool wrap_rows_, wrap_cols_;
};

}  // namespace rtsim::modules
