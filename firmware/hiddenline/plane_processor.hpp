#pragma once
// A plane processor of the hidden-line pipeline (seed 000 Figs. 3-32, 3-33, L1813-L1855; with the
// modification of L1801-L1803: the processor of a polygon's last plane marks the intersections
// leaving it with h, and every processor marks the first and second intersection it sends for a
// segment with the parity p).
//
// On a segment it first sends on what it holds (its intersection, if any), then the segment, and
// intersects the segment's line with its plane: k1 = a x1 + b y1 + c z1, k2 likewise,
// t_n = k1 + d, t_d = k1 - k2 (L1749-L1763), v = (t_d > 0) (L1771). On an intersection it keeps
// the more telling of two for the same end of the line (the smaller t for the positive end, the
// larger for the negative) and sends on an intersection for the positive end before one for the
// negative (L1781). Six multiplications a segment (L1908); a comparison is a cross
// multiplication, two more (counted in `multiplications`).
//
// Two corrections to the figures, both from the text:
// - Fig. 3-32 keeps an intersection only if "t_d != 0 or t_n > 0"; the text keeps it when
//   t_n >= 0 (L1767-L1769). A segment on its own edge plane (t_d = t_n = 0) must be visible, or
//   every polygon would hide its own edges: >= it is.
// - A line parallel to the plane on its visible side (t_d = 0, t_n >= 0) is visible everywhere:
//   its intersection is the positive end's at -infinity. Fig. 3-32's t_n / 0 would compare as
//   +infinity (no information), and a segment above a square and parallel to its top edge would
//   be hidden by the square.
#include <cstdint>
#include <vector>

#include "firmware/hiddenline/messages.hpp"
#include "firmware/hiddenline/plane.hpp"

namespace rtsim::hiddenline {

class PlaneProcessor {
 public:
  explicit PlaneProcessor(const Plane& plane) : plane_(plane) {}

  /// Takes one message and appends what it sends, in order, to `out`.
  void receive(const Message& m, std::vector<Message>& out);

  const Plane& plane() const { return plane_; }
  /// Multiplications so far: six a segment, two a comparison.
  std::uint64_t multiplications() const { return multiplications_; }
  /// Intersections it dropped as redundant (L1789).
  std::uint64_t redundant() const { return redundant_; }

 private:
  void send_held(std::vector<Message>& out);
  void send(const LineParam& t, bool v, std::vector<Message>& out);

  Plane plane_;
  bool u_ = false;  ///< it holds an intersection
  LineParam t_{};
  bool v_ = false;
  bool p_ = false;  ///< the parity of the next intersection it sends for this segment
  std::uint64_t multiplications_ = 0;
  std::uint64_t redundant_ = 0;
};

}  // namespace rtsim::hiddenline
