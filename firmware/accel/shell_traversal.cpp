#include "firmware/accel/shell_traversal.hpp"

#include <algorithm>

namespace rtsim::accel {
namespace {

/// The slab test of Bounds::intersect with 1/d computed once per ray.
bool hit_box(const Bounds& b, const Ray& ray, const Vec3& inv, double t_min, double t_max,
             double& t_enter) {
  for (int a = 0; a < 3; ++a) {
    double t0 = (b.lo[a] - ray.origin[a]) * inv[a];
    double t1 = (b.hi[a] - ray.origin[a]) * inv[a];
    if (t0 > t1) std::swap(t0, t1);
    if (!(t0 <= t1)) {  // NaN: origin on the slab plane with a zero direction component
      if (ray.origin[a] < b.lo[a] || ray.origin[a] > b.hi[a]) return false;
      continue;
    }
    t_min = std::max(t_min, t0);
    t_max = std::min(t_max, t1);
    if (t_min > t_max) return false;
  }
  t_enter = t_min;
  return true;
}

}  // namespace

bool shell_search_possible(const ShellTree& tree, const Ray& ray, double t_min, double t_max) {
  return tree.shell_packet_count() > 0 && is_finite(ray.origin) && is_finite(ray.direction) &&
         t_min <= t_max;
}

std::size_t shell_packet_task(const ShellTree& tree, std::uint32_t packet, const Ray& ray,
                              const Vec3& inv_dir, double t_min, double t_max,
                              std::vector<LeafShellEntry>& leaves,
                              std::vector<std::uint32_t>& children) {
  const auto shells = tree.shell_packet(packet);
  for (const Shell& s : shells) shell_box_task(s, ray, inv_dir, t_min, t_max, leaves, children);
  return shells.size();
}

void shell_box_task(const Shell& shell, const Ray& ray, const Vec3& inv_dir, double t_min,
                    double t_max, std::vector<LeafShellEntry>& leaves,
                    std::vector<std::uint32_t>& children) {
  double t = 0.0;
  if (!hit_box(shell.box, ray, inv_dir, t_min, t_max, t)) return;
  if (shell.leaf) {
    leaves.push_back({shell.child_index, t});  // LeafShellList U= {child_index, t-value}
  } else {
    children.push_back(shell.child_index);  // ShellTask(child_index of shell)
  }
}

void sort_leaf_shell_list(std::vector<LeafShellEntry>& list) {
  std::sort(list.begin(), list.end(), [](const LeafShellEntry& a, const LeafShellEntry& b) {
    return a.t < b.t || (a.t == b.t && a.child_index < b.child_index);
  });
}

void shell_task(const ShellTree& tree, const Ray& ray, double t_min, double t_max,
                std::vector<LeafShellEntry>& list, ShellTraversalStats& stats) {
  list.clear();
  ++stats.rays;
  if (!shell_search_possible(tree, ray, t_min, t_max)) return;
  const Vec3 inv(1.0 / ray.direction.x, 1.0 / ray.direction.y, 1.0 / ray.direction.z);
  // Fig. 4-10 recurses into a hit parent's children; a stack of packet indices does the same.
  std::vector<std::uint32_t> pending{0};  // SHELL_ARRAY[0]: the root's children (L662)
  std::vector<std::uint32_t> children;
  while (!pending.empty()) {
    const std::uint32_t packet = pending.back();
    pending.pop_back();
    ++stats.shell_packets;
    children.clear();
    stats.box_tests += shell_packet_task(tree, packet, ray, inv, t_min, t_max, list, children);
    pending.insert(pending.end(), children.begin(), children.end());
  }
  sort_leaf_shell_list(list);
  stats.leaf_shells_sorted += list.size();
  stats.longest_list = std::max<std::uint64_t>(stats.longest_list, list.size());
  if (list.size() > kLeafShellListCapacity) {
    ++stats.rays_over_capacity;
    stats.entries_over_capacity += list.size() - kLeafShellListCapacity;
  }
}

}  // namespace rtsim::accel
