#include "firmware/scanline/tree_frame.hpp"

#include <algorithm>
#include <limits>
#include <numeric>
#include <random>
#include <stdexcept>

#include "firmware/scanline/scan_converter.hpp"
#include "firmware/scanline/splitting.hpp"

namespace rtsim::scanline {

namespace {
/// Deals `order` to leaves [lo, hi): alternately to the right subtree (first) and the left, so
/// the right, the larger, takes ceil((hi - lo) / 2) of them.
void deal(const std::vector<std::uint32_t>& order, std::size_t lo, std::size_t hi,
          std::vector<std::uint32_t>& leaf) {
  if (hi - lo == 1) {
    leaf[lo] = order.front();
    return;
  }
  std::vector<std::uint32_t> left, right;
  for (std::size_t k = 0; k < order.size(); ++k) (k % 2 == 0 ? right : left).push_back(order[k]);
  const std::size_t mid = (lo + hi) / 2;
  deal(left, lo, mid, leaf);
  deal(right, mid, hi, leaf);
}

/// The polygons in subvolume order: by the cell of a cells^3 grid over their bounds holding
/// their centroid (x fastest), the scene's order within a cell.
std::vector<std::uint32_t> by_subvolume(const std::vector<TcPolygon>& polygons, int cells) {
  Vec3 lo(std::numeric_limits<double>::infinity()), hi(-std::numeric_limits<double>::infinity());
  std::vector<Vec3> centre(polygons.size());
  for (std::size_t k = 0; k < polygons.size(); ++k) {
    Vec3 c(0.0);
    for (const Vec3& v : polygons[k].vertex) {
      lo = glm::min(lo, v);
      hi = glm::max(hi, v);
      c += v;
    }
    centre[k] = c / 4.0;
  }
  const auto cell = [&](const Vec3& c) {
    std::int64_t index = 0;
    for (int a = 2; a >= 0; --a) {
      const double extent = hi[a] - lo[a];
      const double f = extent > 0.0 ? (c[a] - lo[a]) / extent : 0.0;
      // NaN or out of range (a vertex at infinity) clamps to the grid.
      const int i = f >= 0.0 ? std::min(cells - 1, static_cast<int>(f * cells)) : 0;
      index = index * cells + i;
    }
    return index;
  };
  std::vector<std::pair<std::int64_t, std::uint32_t>> keyed(polygons.size());
  for (std::size_t k = 0; k < polygons.size(); ++k)
    keyed[k] = {cell(centre[k]), static_cast<std::uint32_t>(k)};
  std::sort(keyed.begin(), keyed.end());
  std::vector<std::uint32_t> order;
  order.reserve(keyed.size());
  for (const auto& [c, k] : keyed) order.push_back(k);
  return order;
}
}  // namespace

std::vector<std::uint32_t> leaf_assignment(const std::vector<TcPolygon>& polygons,
                                           std::size_t leaves, const LeafPlan& plan) {
  const std::size_t n = polygons.size();
  if (leaves < n) throw std::invalid_argument("leaf_assignment: fewer leaves than polygons");
  std::vector<std::uint32_t> order(n);
  std::iota(order.begin(), order.end(), 0u);
  if (plan.order == LeafOrder::Random) {
    // Fisher-Yates with a fixed generator (std::shuffle's use of it is not specified).
    std::mt19937_64 rng(plan.seed);
    for (std::size_t i = order.size(); i > 1; --i) std::swap(order[i - 1], order[rng() % i]);
  } else if (plan.order == LeafOrder::Subvolume) {
    order = by_subvolume(polygons, std::max(1, plan.subvolumes));
  }
  for (std::size_t k = n; k < leaves; ++k) order.push_back(static_cast<std::uint32_t>(k));
  if (plan.order != LeafOrder::Subvolume || leaves == 0) return order;
  std::vector<std::uint32_t> leaf(leaves);
  deal(order, 0, leaves, leaf);
  return leaf;
}

std::vector<EdgeChains> transform_and_clip(const BroadcastProgram& program,
                                           const std::vector<TcPolygon>& polygons,
                                           std::uint64_t* executed) {
  std::vector<EdgeChains> chains;
  chains.reserve(polygons.size());
  // The processors hear the same stream; a batch at a time keeps their memories in the cache.
  constexpr std::size_t kBatch = 64;
  std::vector<TcProcessor> batch;
  for (std::size_t first = 0; first < polygons.size(); first += kBatch) {
    const std::size_t n = std::min(kBatch, polygons.size() - first);
    batch.assign(n, TcProcessor{});
    for (std::size_t k = 0; k < n; ++k) load_polygon(batch[k], polygons[first + k]);
    broadcast(program, batch);
    for (const TcProcessor& p : batch) {
      if (executed) *executed += p.executed;
      chains.push_back(edge_chains(p.sent));
    }
  }
  return chains;
}

std::vector<EdgeChains> transform_and_clip(const TcFrame& frame) {
  return transform_and_clip(build_tc_program(frame.literals), frame.polygons, nullptr);
}

namespace {
std::vector<Segment> merge_range(const std::vector<std::vector<Segment>>& streams, std::size_t lo,
                                 std::size_t hi, MergeTally* tally) {
  if (hi - lo == 1) return streams[lo];
  const std::size_t mid = (lo + hi) / 2;
  return merge_streams(merge_range(streams, lo, mid, tally), merge_range(streams, mid, hi, tally),
                       tally);
}
}  // namespace

std::vector<Segment> merge_tree(const std::vector<std::vector<Segment>>& streams,
                                MergeTally* tally) {
  if (streams.empty()) return {dummy_segment()};
  return merge_range(streams, 0, streams.size(), tally);
}

TreeFrame evaluate_tree(const TcFrame& frame, int lines,
                        const std::vector<std::uint32_t>& leaf_polygon, int split_levels) {
  TreeFrame out;
  const std::vector<EdgeChains> chains = transform_and_clip(frame);
  std::vector<std::vector<Segment>> streams;
  streams.reserve(leaf_polygon.size());
  for (const std::uint32_t p : leaf_polygon) {
    // An idle leaf's scan converter has no polygon: its stream is the dummy.
    streams.push_back(p < chains.size() ? scan_convert(chains[p], lines, p)
                                        : std::vector<Segment>{dummy_segment()});
    out.leaf_segments += streams.back().size() - 1;
  }
  std::vector<std::vector<Segment>> roots;
  if (streams.empty()) {
    roots.push_back({dummy_segment()});
  } else {
    for (const auto& [lo, hi] : subtree_ranges(streams.size(), split_levels))
      roots.push_back(merge_range(streams, lo, hi, &out.tally));
  }
  out.strips = split_network(std::move(roots), split_levels, &out.tally, &out.broken);
  return out;
}

std::vector<PixelRow> blank_frame(int width, int height, const Color& background, bool ids,
                                  bool depth) {
  std::vector<PixelRow> rows(static_cast<std::size_t>(height));
  const auto w = static_cast<std::size_t>(width);
  for (PixelRow& r : rows) {
    r.colour.resize(w);
    if (ids) r.polygon.resize(w);
    if (depth) r.depth.resize(w);
    blank_pixels(r, 0, width, background);
  }
  return rows;
}

std::vector<PixelRow> paint_frame(const std::vector<std::vector<Segment>>& strips, int width,
                                  int height, const Color& background, bool ids, bool depth) {
  std::vector<PixelRow> rows = blank_frame(width, height, background, ids, depth);
  int levels = 0;
  while ((std::size_t{1} << levels) < strips.size()) ++levels;
  for (std::size_t k = 0; k < strips.size(); ++k)
    for (const Segment& s : strips[k])
      if (!s.dummy() && !s.mark && s.y < height)
        paint(s, width, rows[static_cast<std::size_t>(s.y)],
              {.levels = levels, .index = static_cast<int>(k)});
  return rows;
}

}  // namespace rtsim::scanline
