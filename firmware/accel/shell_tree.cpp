#include "firmware/accel/shell_tree.hpp"

#include <algorithm>
#include <deque>
#include <limits>
#include <map>
#include <stdexcept>
#include <string>
#include <utility>

namespace rtsim::accel {

struct ShellTree::Node {
  Bounds box;
  bool leaf = false;
  std::uint32_t leaf_index = 0;         ///< PRIM_ARRAY index (leaves)
  std::vector<std::uint32_t> children;  ///< node indices (parents)
};

namespace {

bool usable(const Bounds& b) { return !b.empty() && is_finite(b.lo) && is_finite(b.hi); }

double surface_area(const Bounds& b) {
  if (b.empty()) return 0.0;
  const Vec3 e = b.extent();
  return 2.0 * (e.x * e.y + e.y * e.z + e.z * e.x);
}

void check_arguments(std::size_t prim_count, int branching) {
  if (branching < 2) {
    throw std::invalid_argument("ShellTree: branching factor must be >= 2, got " +
                                std::to_string(branching));
  }
  if (prim_count > std::numeric_limits<std::uint32_t>::max()) {
    throw std::length_error("ShellTree: more than 2^32 primitives");
  }
}

}  // namespace

ShellTree ShellTree::from_nodes(const std::vector<Node>& nodes,
                                const std::vector<std::uint32_t>& root_children,
                                std::vector<std::vector<std::uint32_t>> leaf_prims,
                                std::size_t skipped) {
  ShellTree t;
  t.skipped_ = skipped;
  for (const std::uint32_t c : root_children) t.scene_.extend(nodes[c].box);
  // SHELL_ARRAY, breadth first: packet 0 = the root's children (seed 001 L662).
  struct Pending {
    const std::vector<std::uint32_t>* list;
    int level;
  };
  std::deque<Pending> queue{{&root_children, 1}};
  std::uint32_t next_packet = 1;
  t.shell_offsets_.push_back(0);
  while (!queue.empty()) {
    const Pending p = queue.front();
    queue.pop_front();
    t.depth_ = std::max(t.depth_, p.list->empty() ? 0 : p.level);
    for (const std::uint32_t c : *p.list) {
      const Node& n = nodes[c];
      Shell s;
      s.leaf = n.leaf;
      s.box = n.box;
      if (n.leaf) {
        s.child_index = n.leaf_index;  // index into PRIM_ARRAY (L662)
      } else {
        s.child_index = next_packet++;  // index of its children list in SHELL_ARRAY (L662)
        queue.push_back({&n.children, p.level + 1});
      }
      t.shells_.push_back(s);
    }
    t.shell_offsets_.push_back(static_cast<std::uint32_t>(t.shells_.size()));
  }
  // PRIM_ARRAY: one entry per leaf shell (L664-L666).
  t.prim_offsets_.push_back(0);
  for (auto& list : leaf_prims) {
    std::sort(list.begin(), list.end());
    t.prims_.insert(t.prims_.end(), list.begin(), list.end());
    t.prim_offsets_.push_back(static_cast<std::uint32_t>(t.prims_.size()));
  }
  return t;
}

ShellTree ShellTree::from_clusters(std::span<const Bounds> prim_bounds,
                                   std::span<const std::uint32_t> cluster_of_primitive,
                                   int branching) {
  check_arguments(prim_bounds.size(), branching);
  if (cluster_of_primitive.size() != prim_bounds.size()) {
    throw std::invalid_argument(
        "ShellTree::from_clusters: " + std::to_string(cluster_of_primitive.size()) +
        " cluster numbers for " + std::to_string(prim_bounds.size()) + " primitives");
  }
  // Leaf shells in increasing cluster number.
  std::map<std::uint32_t, std::uint32_t> leaf_of_cluster;
  std::size_t skipped = 0;
  for (std::size_t i = 0; i < prim_bounds.size(); ++i) {
    if (usable(prim_bounds[i])) {
      leaf_of_cluster.emplace(cluster_of_primitive[i], 0);
    } else {
      ++skipped;
    }
  }
  std::vector<Node> nodes;
  std::vector<std::vector<std::uint32_t>> leaf_prims(leaf_of_cluster.size());
  for (auto& [cluster, leaf] : leaf_of_cluster) {
    leaf = static_cast<std::uint32_t>(nodes.size());
    Node n;
    n.leaf = true;
    n.leaf_index = leaf;
    nodes.push_back(n);
  }
  for (std::size_t i = 0; i < prim_bounds.size(); ++i) {
    if (!usable(prim_bounds[i])) continue;
    const std::uint32_t leaf = leaf_of_cluster[cluster_of_primitive[i]];
    nodes[leaf].box.extend(prim_bounds[i]);
    leaf_prims[leaf].push_back(static_cast<std::uint32_t>(i));
  }
  // Group consecutive shells b at a time, level by level (a complete b-ary tree when the leaf
  // count is a power of b), until the root's children remain.
  std::vector<std::uint32_t> level(nodes.size());
  for (std::uint32_t i = 0; i < level.size(); ++i) level[i] = i;
  const auto b = static_cast<std::size_t>(branching);
  while (level.size() > b) {
    std::vector<std::uint32_t> up;
    for (std::size_t g = 0; g < level.size(); g += b) {
      const std::size_t end = std::min(level.size(), g + b);
      if (end - g == 1) {
        up.push_back(level[g]);  // a lone shell needs no parent of its own
        continue;
      }
      Node parent;
      for (std::size_t k = g; k < end; ++k) {
        parent.children.push_back(level[k]);
        parent.box.extend(nodes[level[k]].box);
      }
      up.push_back(static_cast<std::uint32_t>(nodes.size()));
      nodes.push_back(std::move(parent));
    }
    level = std::move(up);
  }
  return from_nodes(nodes, level, std::move(leaf_prims), skipped);
}

ShellTree ShellTree::build(std::span<const Bounds> prim_bounds, int branching,
                           int max_prims_per_leaf) {
  check_arguments(prim_bounds.size(), branching);
  if (max_prims_per_leaf < 1) {
    throw std::invalid_argument("ShellTree::build: max_prims_per_leaf must be >= 1, got " +
                                std::to_string(max_prims_per_leaf));
  }
  std::vector<std::uint32_t> slots;
  std::vector<Vec3> centroid(prim_bounds.size());
  for (std::size_t i = 0; i < prim_bounds.size(); ++i) {
    if (!usable(prim_bounds[i])) continue;
    slots.push_back(static_cast<std::uint32_t>(i));
    centroid[i] = prim_bounds[i].center();
  }
  const std::size_t skipped = prim_bounds.size() - slots.size();
  const auto leaf_max = static_cast<std::size_t>(max_prims_per_leaf);
  const auto b = static_cast<std::size_t>(branching);

  std::vector<Node> nodes;
  std::vector<std::vector<std::uint32_t>> leaf_prims;
  auto bounds_of = [&](std::span<const std::uint32_t> s) {
    Bounds box;
    for (const std::uint32_t i : s) box.extend(prim_bounds[i]);
    return box;
  };
  auto make_leaf = [&](std::span<const std::uint32_t> s) {
    Node n;
    n.leaf = true;
    n.leaf_index = static_cast<std::uint32_t>(leaf_prims.size());
    n.box = bounds_of(s);
    leaf_prims.emplace_back(s.begin(), s.end());
    nodes.push_back(std::move(n));
    return static_cast<std::uint32_t>(nodes.size() - 1);
  };
  // One binary median split on the cheapest axis, recursively, into `parts` groups.
  // Precondition: parts <= s.size(), so no group is empty.
  auto split = [&](auto&& self, std::span<std::uint32_t> s, std::size_t parts,
                   std::vector<std::span<std::uint32_t>>& out) -> void {
    if (parts <= 1) {
      out.push_back(s);
      return;
    }
    const std::size_t left_n = s.size() * (parts / 2) / parts;
    auto order_on = [&](int axis) {
      std::nth_element(s.begin(), s.begin() + static_cast<std::ptrdiff_t>(left_n), s.end(),
                       [&](std::uint32_t x, std::uint32_t y) {
                         const double cx = centroid[x][axis], cy = centroid[y][axis];
                         return cx < cy || (cx == cy && x < y);
                       });
    };
    int best_axis = 0;
    double best_cost = kInfinity;
    for (int axis = 0; axis < 3; ++axis) {
      order_on(axis);
      const double cost = surface_area(bounds_of(s.first(left_n))) * left_n +
                          surface_area(bounds_of(s.subspan(left_n))) * (s.size() - left_n);
      if (cost < best_cost) {
        best_cost = cost;
        best_axis = axis;
      }
    }
    if (best_axis != 2) order_on(best_axis);
    self(self, s.first(left_n), parts / 2, out);
    self(self, s.subspan(left_n), parts - parts / 2, out);
  };
  // Children of a node holding more than leaf_max primitives.
  auto make_children = [&](auto&& self, std::span<std::uint32_t> s) -> std::vector<std::uint32_t> {
    std::vector<std::span<std::uint32_t>> groups;
    split(split, s, std::min(b, s.size()), groups);
    std::vector<std::uint32_t> children;
    for (const auto g : groups) {
      if (g.size() <= leaf_max) {
        children.push_back(make_leaf(g));
      } else {
        Node parent;
        parent.children = self(self, g);
        for (const std::uint32_t c : parent.children) parent.box.extend(nodes[c].box);
        nodes.push_back(std::move(parent));
        children.push_back(static_cast<std::uint32_t>(nodes.size() - 1));
      }
    }
    return children;
  };
  std::vector<std::uint32_t> root_children;
  if (!slots.empty()) {
    root_children = slots.size() <= leaf_max ? std::vector<std::uint32_t>{make_leaf(slots)}
                                             : make_children(make_children, slots);
  }
  return from_nodes(nodes, root_children, std::move(leaf_prims), skipped);
}

}  // namespace rtsim::accel
