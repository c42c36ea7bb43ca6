#include "firmware/sortfirst/region_store.hpp"

#include <random>

namespace rtsim::sortfirst {

void RegionStore::load(const PrimitiveRecord& r) {
  const auto t = unpack(r, materials_);
  if (!t) return;
  held_[record_id(r)] = HeldPrimitive{r, *t, RegionRange{}, true};
}

ClassifyResult RegionStore::classify_all(const raster::ViewTransform& view) {
  ClassifyResult out;
  const int row = region_ / regions_.side, col = region_ % regions_.side;
  if (sort_ != Sort::First) {
    // The initial share never moves. Sort-middle: last frame's arrivals go, and every primitive
    // of the share goes to every other region it covers (L511); sort-last: nothing is sent.
    for (auto it = held_.begin(); it != held_.end();) {
      if (!it->second.master) {
        ++out.dropped_copies;
        it = held_.erase(it);
        continue;
      }
      HeldPrimitive& h = it->second;
      h.range = classify(h.triangle, view, regions_);
      ++out.classified;
      if (sort_ == Sort::Middle)
        for (int r = h.range.r0; h.range.on_screen && r <= h.range.r1; ++r)
          for (int c = h.range.c0; c <= h.range.c1; ++c)
            if (regions_.index(r, c) != region_)
              out.sends.push_back({regions_.index(r, c), h.record});
      ++it;
    }
    return out;
  }
  for (auto it = held_.begin(); it != held_.end();) {
    HeldPrimitive& h = it->second;
    const RegionRange range = classify(h.triangle, view, regions_);
    ++out.classified;
    if (!range.on_screen) {
      // Off the screen: the owner keeps it (L566), the copies go.
      if (!h.master) {
        ++out.dropped_copies;
        it = held_.erase(it);
        continue;
      }
      h.range = range;
      ++it;
      continue;
    }
    const int owner = regions_.owner(range);
    const bool was_master = h.master;
    if (h.master) {
      // A copy to each covered region that held none: not last frame's range, not this one.
      for (int r = range.r0; r <= range.r1; ++r)
        for (int c = range.c0; c <= range.c1; ++c) {
          const int to = regions_.index(r, c);
          if (to != region_ && !h.range.covers(r, c)) out.sends.push_back({to, h.record});
        }
      if (owner != region_) h.master = false;
    } else if (owner == region_) {
      h.master = true;
    }
    h.range = range;
    if (!h.master && !range.covers(row, col)) {
      // No longer needed here (an owner's sends above went out first).
      if (!was_master) ++out.dropped_copies;
      it = held_.erase(it);
      continue;
    }
    ++it;
  }
  return out;
}

bool RegionStore::receive(const PrimitiveRecord& r, const raster::ViewTransform& view,
                          std::uint32_t primitives) {
  const std::uint32_t id = record_id(r);
  if (id >= primitives) return false;
  const auto t = unpack(r, materials_);
  if (!t) return false;
  const RegionRange range = classify(*t, view, regions_);
  const int row = region_ / regions_.side, col = region_ % regions_.side;
  if (!range.covers(row, col)) return false;
  // Sort-middle's arrivals are this frame's only; a sort-first arrival may be the new owner's.
  const bool master = sort_ == Sort::First && regions_.owner(range) == region_;
  auto [at, added] = held_.try_emplace(id, HeldPrimitive{r, *t, range, master});
  if (!added && !(sort_ == Sort::Middle && at->second.master)) at->second = {r, *t, range, master};
  return true;
}

raster::RasterMesh RegionStore::to_render() const {
  raster::RasterMesh mesh;
  const int row = region_ / regions_.side, col = region_ % regions_.side;
  for (const auto& [id, h] : held_)
    if (sort_ == Sort::Last ? h.range.on_screen : h.range.covers(row, col)) {
      mesh.triangles.push_back(h.triangle);
      for (const auto& v : h.triangle.v) mesh.bounds.extend(v.position);
    }
  return mesh;
}

std::size_t RegionStore::masters() const {
  std::size_t n = 0;
  for (const auto& [id, h] : held_) n += h.master ? 1 : 0;
  return n;
}

std::vector<std::uint64_t> migration_counts(const raster::RasterMesh& mesh,
                                            const std::vector<raster::ViewTransform>& views,
                                            const ScreenRegions& regions,
                                            const std::vector<int>& initial_owner) {
  std::vector<int> owner = initial_owner;
  std::vector<RegionRange> last(mesh.triangles.size());
  std::vector<std::uint64_t> sent;
  for (const auto& view : views) {
    std::uint64_t n = 0;
    for (std::size_t i = 0; i < mesh.triangles.size(); ++i) {
      const RegionRange range = classify(mesh.triangles[i], view, regions);
      if (!range.on_screen) {
        last[i] = range;
        continue;
      }
      for (int r = range.r0; r <= range.r1; ++r)
        for (int c = range.c0; c <= range.c1; ++c)
          if (regions.index(r, c) != owner[i] && !last[i].covers(r, c)) ++n;
      owner[i] = regions.owner(range);
      last[i] = range;
    }
    sent.push_back(n);
  }
  return sent;
}

std::vector<int> random_distribution(std::size_t primitives, int regions, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::vector<int> out(primitives);
  for (auto& r : out) r = static_cast<int>(rng() % static_cast<std::uint64_t>(regions));
  return out;
}

}  // namespace rtsim::sortfirst
