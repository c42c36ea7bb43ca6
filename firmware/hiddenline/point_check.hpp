#pragma once
// An independent check of the hidden-line pipeline's answers (no boundary plane involved):
// points sampled along each segment, each tested against every polygon by a 2-D inside test
// (the point's distance inside each edge) and the depth of the polygon's plane at it, both in
// doubles. Within `kMargin` screen units of a polygon's edge or plane the answer is a rounding's
// and the check says nothing. Used by the tests and the validation rows (seed 000 L1681: the
// results are "exact to the numeric precision").
#include <cstddef>
#include <vector>

#include "firmware/hiddenline/messages.hpp"
#include "firmware/hiddenline/pipe.hpp"

namespace rtsim::hiddenline {

enum class Seen { kVisible, kHidden, kUnsure };

inline constexpr double kMargin = 1e-6;

/// Whether the point (x, y, z) of the screen is hidden by one of `polygons` (convex), leaving
/// out those whose indices `exclude` lists (sorted): a point on a polygon's own edge is on its
/// boundary, where the check cannot decide, and no polygon hides its own edges.
Seen point_seen(const std::vector<std::vector<ScreenPoint>>& polygons, double x, double y, double z,
                const std::vector<std::size_t>& exclude = {});

struct PieceCheck {
  std::size_t samples = 0;       ///< points the check could decide
  std::size_t hidden = 0;        ///< of them, hidden
  std::size_t missed = 0;        ///< visible, but on no piece
  std::size_t drawn_hidden = 0;  ///< hidden, but on a piece
};

/// `per_segment` points along each segment (at (j + 1/2) / per_segment), skipping those within
/// 1e-6 of a piece's end, against the pieces the pipe drew for it. The polygons that have the
/// segment as an edge (both its ends among their vertices) are left out of its points' tests.
PieceCheck check_pieces(const std::vector<std::vector<ScreenPoint>>& polygons,
                        const std::vector<Segment>& segments,
                        const std::vector<VisiblePiece>& pieces, int per_segment);

}  // namespace rtsim::hiddenline
