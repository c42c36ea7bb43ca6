#pragma once
// Gaudet's hierarchy of box shells (seed 001 §4.1-4.4, L555-L714).
//
// A shell is an orthogonal (axis-aligned) box (§4.3.2, L597-L611). Leaf shells enclose
// primitives, parent shells enclose shells, the scene is the uppermost parent shell (L559-L581);
// every primitive is inside a leaf shell (§4.3.1, L595).
//
// Storage follows the thesis's arrays (§4.4, L660-L666):
//  * SHELL_ARRAY: entry i is the list of sibling SHELLs of one parent — one SHELL packet. The
//    children of the scene (root) shell are at index 0 (L662). A parent shell's child_index is
//    the SHELL_ARRAY index of its children.
//  * PRIM_ARRAY: entry j is the list of sibling primitives of one leaf shell — one PRIM packet;
//    a leaf shell's child_index is j (L664-L666).
// Shell packets are numbered breadth-first (root's children, then the children lists of the
// shells in packet 0 in order, ...). The `next` pointer of Fig. 4-3 is implicit: siblings are
// contiguous. The root itself is not in any packet; the ray is assumed to hit it (L378, L585).
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "firmware/bounds.hpp"

namespace rtsim::accel {

/// SHELL (Fig. 4-3, seed 001 L668-L674): leaf flag, child index, the box (max, min corners).
struct Shell {
  bool leaf = false;
  std::uint32_t child_index = 0;  ///< parent: SHELL_ARRAY index; leaf: PRIM_ARRAY index
  Bounds box;
};

/// The counts of Gaudet's Fig. 6-1 (seed 001 L980-L989).
struct ShellTreeCounts {
  std::size_t shells = 0;         ///< all shells except the root (scene) shell
  std::size_t shell_packets = 0;  ///< SHELL_ARRAY entries, including the root's children
  std::size_t prims = 0;          ///< primitives stored in leaf shells
  std::size_t prim_packets = 0;   ///< PRIM_ARRAY entries = leaf shells
  friend bool operator==(const ShellTreeCounts&, const ShellTreeCounts&) = default;
};

class ShellTree {
 public:
  ShellTree() = default;

  /// Gaudet's npp scenes (seed 001 L968-L989): each cluster becomes one leaf shell, and the
  /// leaf shells are grouped `branching` at a time, consecutive clusters together, level after
  /// level, until at most `branching` shells remain: those are the root's children. With a
  /// power-of-b cluster count this is the complete b-ary tree of Fig. 6-1. (Otherwise the last
  /// group of a level is smaller, and a group of one is passed up unwrapped.)
  /// cluster_of_primitive[i] is the cluster of primitive slot i; leaf shells (= PRIM_ARRAY
  /// entries) are in increasing cluster number, primitives in a leaf in increasing slot.
  /// Primitives with empty or non-finite bounds are left out (skipped_count()).
  /// Throws std::invalid_argument if sizes differ or branching < 2.
  static ShellTree from_clusters(std::span<const Bounds> prim_bounds,
                                 std::span<const std::uint32_t> cluster_of_primitive,
                                 int branching);

  /// A generic hierarchy for any scene: top-down, each node's primitives are cut into up to
  /// `branching` groups by repeated binary splits. Each binary split is made at the median
  /// centroid ("median split") of one axis, the axis whose two halves have the smallest
  /// surface-area cost SA(left) n_left + SA(right) n_right ("SAH-lite": the surface area
  /// heuristic evaluated only at the three medians, not swept). A group of at most
  /// max_prims_per_leaf primitives becomes a leaf shell. Leaves are numbered in depth-first
  /// order (spatially coherent PRIM_ARRAY). Deterministic (ties broken by slot).
  static ShellTree build(std::span<const Bounds> prim_bounds, int branching,
                         int max_prims_per_leaf);

  /// The scene (root) shell.
  const Bounds& scene_shell() const { return scene_; }

  std::size_t shell_packet_count() const {
    return shell_offsets_.empty() ? 0 : shell_offsets_.size() - 1;
  }
  /// SHELL_ARRAY[index]: the sibling shells of one parent (index 0: the root's children).
  std::span<const Shell> shell_packet(std::size_t index) const {
    return {shells_.data() + shell_offsets_[index], shells_.data() + shell_offsets_[index + 1]};
  }
  std::size_t prim_packet_count() const {
    return prim_offsets_.empty() ? 0 : prim_offsets_.size() - 1;
  }
  /// PRIM_ARRAY[index]: the primitive slots enclosed by one leaf shell.
  std::span<const std::uint32_t> prim_packet(std::size_t index) const {
    return {prims_.data() + prim_offsets_[index], prims_.data() + prim_offsets_[index + 1]};
  }
  /// Every shell except the root, packet after packet.
  std::span<const Shell> shells() const { return shells_; }
  /// Replaces every shell's box by `stored(box)`: the box as a machine's memory holds it (a
  /// PERT's SHELL records keep it in singles rounded outward), so that a search on this tree
  /// and a search on the stored records see the same boxes.
  template <class Stored>
  void store_boxes(Stored&& stored) {
    for (Shell& s : shells_) s.box = stored(s.box);
  }

  ShellTreeCounts counts() const {
    return {shells_.size(), shell_packet_count(), prims_.size(), prim_packet_count()};
  }
  std::size_t skipped_count() const { return skipped_; }
  /// Levels of shells below the root (1: the root's children are leaves).
  int depth() const { return depth_; }

 private:
  struct Node;  // build-time tree
  static ShellTree from_nodes(const std::vector<Node>& nodes,
                              const std::vector<std::uint32_t>& root_children,
                              std::vector<std::vector<std::uint32_t>> leaf_prims,
                              std::size_t skipped);

  Bounds scene_;
  std::vector<Shell> shells_;
  std::vector<std::uint32_t> shell_offsets_;
  std::vector<std::uint32_t> prims_;
  std::vector<std::uint32_t> prim_offsets_;
  std::size_t skipped_ = 0;
  int depth_ = 0;
};

}  // namespace rtsim::accel
