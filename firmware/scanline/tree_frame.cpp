#include "firmware/scanline/tree_frame.hpp"

#include <limits>
#include <numeric>
#include <random>

#include "firmware/scanline/scan_converter.hpp"

namespace rtsim::scanline {

std::vector<std::uint32_t> leaf_assignment(std::size_t polygons, bool random, std::uint64_t seed) {
  std::vector<std::uint32_t> leaf(polygons);
  std::iota(leaf.begin(), leaf.end(), 0u);
  if (random) {
    // Fisher-Yates with a fixed generator (std::shuffle's use of it is not specified).
    std::mt19937_64 rng(seed);
    for (std::size_t i = leaf.size(); i > 1; --i) std::swap(leaf[i - 1], leaf[rng() % i]);
  }
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
                        const std::vector<std::uint32_t>& leaf_polygon) {
  TreeFrame out;
  const std::vector<EdgeChains> chains = transform_and_clip(frame);
  std::vector<std::vector<Segment>> streams;
  streams.reserve(leaf_polygon.size());
  for (const std::uint32_t p : leaf_polygon) {
    streams.push_back(scan_convert(chains[p], lines, p));
    out.leaf_segments += streams.back().size() - 1;
  }
  out.root = merge_tree(streams, &out.tally);
  return out;
}

std::vector<PixelRow> paint_frame(const std::vector<Segment>& root, int width, int height,
                                  const Color& background, bool ids, bool depth) {
  std::vector<PixelRow> rows(static_cast<std::size_t>(height));
  const auto w = static_cast<std::size_t>(width);
  for (PixelRow& r : rows) {
    r.colour.assign(w, background);
    if (ids) r.polygon.assign(w, -1);
    if (depth) r.depth.assign(w, std::numeric_limits<float>::infinity());
  }
  for (const Segment& s : root)
    if (!s.dummy() && s.y < height) paint(s, width, rows[static_cast<std::size_t>(s.y)]);
  return rows;
}

}  // namespace rtsim::scanline
