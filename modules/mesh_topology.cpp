#include "modules/mesh_topology.hpp"

#include <cstdlib>

namespace rtsim::modules {

std::string_view direction_name(Direction d) {
  switch (d) {
    case Direction::kNorth:
      return "n";
    case Direction::kEast:
      return "e";
    case Direction::kSouth:
      return "s";
    case Direction::kWest:
      return "w";
  }
  return "?";
}

Direction opposite(Direction d) { return static_cast<Direction>((static_cast<int>(d) + 2) % 4); }

std::optional<GridNode> MeshTopology::neighbour(const GridNode& n, Direction d) const {
  GridNode m = n;
  switch (d) {
    case Direction::kNorth:
      --m.row;
      break;
    case Direction::kSouth:
      ++m.row;
      break;
    case Direction::kEast:
      ++m.col;
      break;
    case Direction::kWest:
      --m.col;
      break;
  }
  if (m.row < 0 || m.row >= rows_) {
    if (!wrap_rows_ || rows_ < 2) return std::nullopt;
    m.row = (m.row + rows_) % rows_;
  }
  if (m.col < 0 || m.col >= cols_) {
    if (!wrap_cols_ || cols_ < 2) return std::nullopt;
    m.col = (m.col + cols_) % cols_;
  }
  return m;
}

int MeshTopology::delta(int from, int to, int size, bool wrap) {
  int d = to - from;
  if (wrap && size > 1) {
    d = ((d % size) + size) % size;  // 0 .. size-1 going up
    if (d > size - d) d -= size;     // the shorter way; a tie goes up
  }
  return d;
}

Direction MeshTopology::next_hop(const GridNode& from, const GridNode& to) const {
  const int dc = delta(from.col, to.col, cols_, wrap_cols_);
  if (dc != 0) return dc > 0 ? Direction::kEast : Direction::kWest;
  const int dr = delta(from.row, to.row, rows_, wrap_rows_);
  return dr > 0 ? Direction::kSouth : Direction::kNorth;
}

int MeshTopology::hops(const GridNode& from, const GridNode& to) const {
  return std::abs(delta(from.col, to.col, cols_, wrap_cols_)) +
         std::abs(delta(from.row, to.row, rows_, wrap_rows_));
}

std::optional<Direction> MeshTopology::direction_to(const GridNode& from,
                                                    const GridNode& to) const {
  for (const Direction d : kDirections)
    if (const auto m = neighbour(from, d); m && *m == to) return d;
  return std::nullopt;
}

}  // namespace rtsim::modules
