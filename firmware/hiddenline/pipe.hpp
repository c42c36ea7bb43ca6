#pragma once
// The hidden-line pipeline as a chain of its processors (seed 000 Fig. 3-31, L1723-L1733): for
// each polygon a plane processor a boundary plane and a cleanup processor, then a string of
// cleanup processors that catch the debris (L1799), and at the end one divider that turns the
// rationals into points (L1765). Each processor is a function of the stream it receives, so the
// chain run processor after processor (`run_chain`, the functional twin) gives the stream the
// timed machine gives, whatever its timing.
#include <cstdint>
#include <variant>
#include <vector>

#include "firmware/hiddenline/cleanup_processor.hpp"
#include "firmware/hiddenline/plane.hpp"
#include "firmware/hiddenline/plane_processor.hpp"

namespace rtsim::hiddenline {

using Stage = std::variant<PlaneProcessor, CleanupProcessor>;

/// The stages for `polygons` (each convex, in screen coordinates): every polygon's boundary
/// planes and a cleanup processor after them, then `trailing_cleanups` more. Polygons that hide
/// nothing (edge-on) get no stage.
std::vector<Stage> build_chain(const std::vector<std::vector<ScreenPoint>>& polygons,
                               int trailing_cleanups);
/// The same from each hiding polygon's boundary planes (boundary_planes, none empty).
std::vector<Stage> build_chain(const std::vector<std::vector<Plane>>& polygon_planes,
                               int trailing_cleanups);

/// The messages for `segments`, in order, and the end.
std::vector<Message> segment_stream(const std::vector<Segment>& segments);

/// `in` through every stage of `chain` in turn: the pipe's output stream.
std::vector<Message> run_chain(std::vector<Stage>& chain, std::vector<Message> in);

/// A visible piece of a segment: its end points in screen coordinates (the divider's results).
struct VisiblePiece {
  std::uint32_t edge = 0;
  double x0 = 0, y0 = 0, z0 = 0, x1 = 0, y1 = 0, z1 = 0;
  double t0 = 0, t1 = 1;  ///< where on its segment
};

/// The divider at the pipe's end: each segment that came out, less its hidden parts (clamped
/// to [0, 1] and united), as visible pieces. `divisions` counts its divisions.
std::vector<VisiblePiece> divide(const std::vector<Message>& out,
                                 std::uint64_t* divisions = nullptr);

}  // namespace rtsim::hiddenline
