#pragma once
// Gaudet's search of the shell hierarchy, functional form (seed 001 §4.2-4.5, L583-L800).
//
// ShellTask (Fig. 4-10, L755-L757): starting with SHELL_ARRAY[0] (the root's children; the ray
// is assumed to hit the root, L378), test every shell of a sibling packet; a hit parent shell
// sends the search into its children's packet, a hit leaf shell adds {child_index, t-value} to
// the LeafShellList; finally the list is sorted on increasing t (§4.3.7, L638-L640).
//
// PrimTask (Fig. 4-12, L780-L786): the primitives of the leaf shells are tested in t order, a
// whole PRIM packet at a time; after a packet, if the nearest primitive hit so far, t_p, is below
// the t-value of the next leaf shell, t_s, it is the closest and the search stops (L646-L648).
// A light ray stops at the first hit (L776).
//
// Two readings are ours and documented:
//  * Fig. 4-12 compares the nearest hit *in the current packet* with the next shell's t; a hit
//    from an earlier packet that was not yet accepted would then be lost if later packets miss.
//    We keep the nearest hit over all packets tested so far (the prose of L646: "the t-value
//    of an intersected primitive t_p is checked against the t-value of the next closest leaf
//    shell"). A ray whose list runs out with a hit in hand reports that hit.
//  * The t-value of a leaf shell is its entry distance clipped to t_min (0 when the ray starts
//    inside it); boxes are also clipped to t_max, which only prunes shells beyond the segment.
//
// SHELL_TO_PRIM carries at most 50 leaf shells (LSS LeafShellList[50], Fig. 4-11, L766). The
// functional search keeps them all and counts how many rays, and entries, exceed the cap.
//
// PrimTest: double test(std::uint32_t slot, double t_min, double t_max) returns the t of the
// primitive's closest hit in (t_min, t_max), or +inf on a miss. We pass t_max = the best hit so
// far, so every finite return is a new closest hit and the callback may remember its details.
#include <algorithm>
#include <cstdint>
#include <span>
#include <vector>

#include "firmware/accel/shell_tree.hpp"
#include "firmware/cost.hpp"
#include "firmware/ray.hpp"

namespace rtsim::accel {

/// LSS: one LeafShellList entry (Fig. 4-11, L766): the leaf's PRIM_ARRAY index and t-value.
struct LeafShellEntry {
  std::uint32_t child_index = 0;
  double t = 0.0;
};

/// Capacity of LeafShellList in SHELL_TO_PRIM (Fig. 4-11, seed 001 L766).
inline constexpr std::size_t kLeafShellListCapacity = 50;

/// Slab test of a ray against one SHELL box with the reciprocal direction precomputed per ray:
/// per axis 2 subtractions, 2 multiplications, 1 compare to order the pair and 2 compares to
/// narrow [t_enter, t_exit]; the final empty-interval compare is counted in those. Reads the
/// 6 box words. The per-ray setup (3 reciprocals) is kShellRaySetupCost.
inline constexpr Cost kShellBoxTestCost{
    .fp_add = 3 * 5, .fp_mul = 3 * 2, .fp_div = 0, .fp_sqrt = 0, .mem_words = 6, .instructions = 2};
inline constexpr Cost kShellRaySetupCost{
    .fp_add = 0, .fp_mul = 0, .fp_div = 3, .fp_sqrt = 0, .mem_words = 0, .instructions = 0};

struct ShellTraversalStats {
  std::uint64_t rays = 0;
  std::uint64_t box_tests = 0;           ///< shells tested (ShellTask)
  std::uint64_t shell_packets = 0;       ///< SHELL packets the ShellTask needed (incl. packet 0)
  std::uint64_t leaf_shells_sorted = 0;  ///< LeafShellList entries (leaf shells hit)
  std::uint64_t leaf_shells_tested = 0;  ///< PRIM packets whose primitives were tested
  std::uint64_t prim_tests = 0;
  std::uint64_t rays_with_leaf_shells = 0;
  double tested_fraction_sum = 0.0;         ///< sum over rays with a list of tested / sorted
  std::uint64_t rays_over_capacity = 0;     ///< rays whose list is longer than 50
  std::uint64_t entries_over_capacity = 0;  ///< list entries beyond the 50th, summed
  std::uint64_t longest_list = 0;

  /// Mean over rays of the fraction of sorted leaf shells whose contents were tested (Gaudet
  /// measured 80% on his jogger scene, seed 001 L650).
  double mean_tested_fraction() const {
    return rays_with_leaf_shells ? tested_fraction_sum / rays_with_leaf_shells : 0.0;
  }
  ShellTraversalStats& operator+=(const ShellTraversalStats& o) {
    rays += o.rays;
    box_tests += o.box_tests;
    shell_packets += o.shell_packets;
    leaf_shells_sorted += o.leaf_shells_sorted;
    leaf_shells_tested += o.leaf_shells_tested;
    prim_tests += o.prim_tests;
    rays_with_leaf_shells += o.rays_with_leaf_shells;
    tested_fraction_sum += o.tested_fraction_sum;
    rays_over_capacity += o.rays_over_capacity;
    entries_over_capacity += o.entries_over_capacity;
    longest_list = std::max(longest_list, o.longest_list);
    return *this;
  }
};

struct ShellHit {
  std::int32_t prim = -1;  ///< primitive slot, -1 for a miss
  double t = kInfinity;
  bool valid() const { return prim >= 0; }
};

/// Whether ShellTask can search at all: a tree with packets, a finite ray, t_min <= t_max.
/// (A ray that cannot search asks for no packet and gets an empty LeafShellList.)
bool shell_search_possible(const ShellTree& tree, const Ray& ray, double t_min, double t_max);

/// The box test of one SHELL of a packet (Fig. 4-10, L755-L757): on a hit, a leaf shell is
/// appended to `leaves` ({child_index, t-value}) and a parent shell's child_index (the packet of
/// its children, to be asked for next) to `children`. A ShellProcessor posts that ID as soon as
/// this test is done, while it goes on with the packet's other SHELLs.
void shell_box_task(const Shell& shell, const Ray& ray, const Vec3& inv_dir, double t_min,
                    double t_max, std::vector<LeafShellEntry>& leaves,
                    std::vector<std::uint32_t>& children);

/// One step of ShellTask (Fig. 4-10, L755-L757), as a ShellProcessor runs it when a SHELL
/// packet arrives: every SHELL of packet `packet` is box-tested; a hit leaf shell is appended to
/// `leaves` ({child_index, t-value}), a hit parent shell's child_index (the packet of its
/// children, to be asked for next) to `children`. `inv_dir` is 1/direction per axis (the per-ray
/// setup, kShellRaySetupCost). Returns the number of boxes tested.
std::size_t shell_packet_task(const ShellTree& tree, std::uint32_t packet, const Ray& ray,
                              const Vec3& inv_dir, double t_min, double t_max,
                              std::vector<LeafShellEntry>& leaves,
                              std::vector<std::uint32_t>& children);

/// Sorts a LeafShellList on increasing t-value (L734); ties keep PRIM_ARRAY order.
void sort_leaf_shell_list(std::vector<LeafShellEntry>& list);

/// ShellTask: the sorted LeafShellList of `ray` over (t_min, t_max), into `list` (cleared).
/// Ties in t keep PRIM_ARRAY order, so the result is deterministic.
void shell_task(const ShellTree& tree, const Ray& ray, double t_min, double t_max,
                std::vector<LeafShellEntry>& list, ShellTraversalStats& stats);

/// ShellTask + PrimTask for one tree. Holds scratch space, so use one per thread.
class ShellTraverser {
 public:
  explicit ShellTraverser(const ShellTree& tree) : tree_(&tree) {}

  /// Closest hit in (t_min, t_max) (initial and reflected rays).
  template <class PrimTest>
  ShellHit closest_hit(const Ray& ray, double t_min, double t_max, PrimTest&& test,
                       ShellTraversalStats& stats) {
    shell_task(*tree_, ray, t_min, t_max, list_, stats);
    ShellHit best;
    best.t = t_max;
    std::size_t tested = 0;
    for (std::size_t k = 0; k < list_.size(); ++k) {
      ++tested;
      for (const std::uint32_t slot : tree_->prim_packet(list_[k].child_index)) {
        ++stats.prim_tests;
        const double t = test(slot, t_min, best.t);
        if (t > t_min && t < best.t) {
          best.t = t;
          best.prim = static_cast<std::int32_t>(slot);
        }
      }
      // Stop rule (L646-L648): t_p < t_s of the next leaf shell.
      if (best.valid() && (k + 1 == list_.size() || best.t < list_[k + 1].t)) break;
    }
    finish(tested, stats);
    if (!best.valid()) best.t = kInfinity;
    return best;
  }

  /// Any hit in (t_min, t_max): light rays need not find the closest (L776).
  template <class PrimTest>
  ShellHit any_hit(const Ray& ray, double t_min, double t_max, PrimTest&& test,
                   ShellTraversalStats& stats) {
    shell_task(*tree_, ray, t_min, t_max, list_, stats);
    ShellHit hit;
    std::size_t tested = 0;
    for (std::size_t k = 0; k < list_.size() && !hit.valid(); ++k) {
      ++tested;
      for (const std::uint32_t slot : tree_->prim_packet(list_[k].child_index)) {
        ++stats.prim_tests;
        const double t = test(slot, t_min, t_max);
        if (t > t_min && t < t_max) {
          hit.t = t;
          hit.prim = static_cast<std::int32_t>(slot);
          break;
        }
      }
    }
    finish(tested, stats);
    return hit;
  }

  /// The LeafShellList of the last ray (what SHELL_TO_PRIM would carry, uncapped).
  std::span<const LeafShellEntry> leaf_shell_list() const { return list_; }

 private:
  void finish(std::size_t tested, ShellTraversalStats& stats) const {
    stats.leaf_shells_tested += tested;
    if (!list_.empty()) {
      ++stats.rays_with_leaf_shells;
      stats.tested_fraction_sum += static_cast<double>(tested) / static_cast<double>(list_.size());
    }
  }

  const ShellTree* tree_;
  std::vector<LeafShellEntry> list_;
};

}  // namespace rtsim::accel
