#pragma once
// The bookkeeping of Gaudet's three tasks on a PERT (seed 001 §4.5, L716-L800), in the
// machine-neutral units of firmware/cost.hpp. The thesis gives no operation counts (they were
// microcoded in [CHIL85], L951): these are what the pseudo-code does, counted by us. The
// arithmetic of the tests themselves is the kernels' own (accel::kShellBoxTestCost, the sphere
// and triangle kTestCost); reading a packet out of a BIC buffer costs one word per word (L924).
#include <cmath>
#include <cstdint>

#include "firmware/cost.hpp"

namespace rtsim::tasks {

/// Taking a packet from a buffer and finding the rays that asked for it.
inline constexpr Cost kPacketBookkeepingCost{.instructions = 6};
/// ShellTask: appending {child_index, t-value} to the LeafShellList (Fig. 4-10).
inline constexpr Cost kLeafShellAppendCost{.mem_words = 2, .instructions = 2};
/// ShellTask: writing a child packet's ID into a free BIC register, found by serial search
/// (L910), or onto the overflow stack.
inline constexpr Cost kAskPacketCost{.mem_words = 1, .instructions = 4};
/// PrimTask: the stop test after a packet, t_p < t_s of the next leaf shell (L646-L648).
inline constexpr Cost kStopTestCost{.fp_add = 1, .instructions = 2};
/// PrimTask "compute info" (Fig. 4-12): the point o + t d and the surface normal.
inline constexpr Cost kHitInfoCost{
    .fp_add = 6, .fp_mul = 6, .fp_div = 1, .mem_words = 6, .instructions = 4};

/// PrimTask's ray/sphere test as a PERT microcodes it (the thesis gives no intersection
/// algorithm, note 001 §5): the classic geometric test with the ray direction of unit length,
///   oc = c - o (3 add); b = d.oc (3 mul, 2 add); c2 = oc.oc - r^2 (3 mul, 3 add);
///   disc = b^2 - c2 (1 mul, 1 add); disc < 0? (1 compare); t = b - sqrt(disc) (1 sqrt, 1 add);
///   t in (t_min, t_max)? (2 compares) — 13 additions/compares, 7 multiplications, 1 root.
/// The SPHERE record's words are charged as the packet is read. (The functional kernel does
/// more, for accuracy in double; the PERT's timing is its own firmware's.)
inline constexpr Cost kPertSphereTestCost{
    .fp_add = 13, .fp_mul = 7, .fp_sqrt = 1, .instructions = 4};
/// PrimTask's ray/triangle test (a polygon of 3 vertices): the plane, then the inside test,
///   e1, e2 (6 sub), n = e1 x e2 (6 mul, 3 add) (the PRIM record holds vertices only),
///   n.d and the plane distance (6 mul, 5 add), t = num / den (1 div), range (2 compares),
///   point (3 mul, 3 add) and three edge tests on the dominant-axis projection (6 mul, 9 add).
inline constexpr Cost kPertTriangleTestCost{
    .fp_add = 6 + 3 + 5 + 2 + 3 + 9, .fp_mul = 6 + 6 + 3 + 6, .fp_div = 1, .instructions = 8};

/// Sorting n LeafShellList entries on t (L734): about n log2 n compare-and-move steps.
inline Cost leaf_shell_sort_cost(std::uint64_t n) {
  if (n < 2) return {};
  const auto steps = static_cast<std::uint64_t>(
      std::ceil(static_cast<double>(n) * std::log2(static_cast<double>(n))));
  return Cost{.fp_add = steps, .mem_words = 2 * steps, .instructions = steps};
}

/// Reading or writing a message or packet of `words` 32-bit words.
inline constexpr Cost words_cost(std::uint64_t words) { return Cost{.mem_words = words}; }

}  // namespace rtsim::tasks
