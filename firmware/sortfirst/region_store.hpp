#pragma once
// What a sort-first region renderer holds from frame to frame, and its classification step
// (seed 004 L503-L505, L560-L566): the primitives it owns (its "masters") and copies of other
// renderers' primitives that cover its region. Each frame it classifies everything it holds by
// the new view's screen bounding boxes, and for each master sends a copy to every covered region
// that did not hold one last frame; the upper-left covered region's renderer becomes the owner
// (L564). A primitive off the screen stays with its owner (L566). Copies no longer covering the
// region are dropped. The results form the next frame's distribution (L505).
//
// Every holder of a primitive classifies it itself, so owner and copy holders agree on the
// new owner without a message: the old owner knows which regions held copies (last frame's
// range, which it kept), and the regions in the new range that did not are sent one. The
// primitives a region renders are then exactly those whose range covers it.
//
// Study's rule kept: "primitives which fall into multiple regions may need to be sent more than
// once" (L599): a copy goes to each region that needs one, so more than 100% of the primitives
// can migrate in a frame.
#include <cstdint>
#include <map>
#include <vector>

#include "firmware/sortfirst/primitive_record.hpp"
#include "firmware/sortfirst/screen_regions.hpp"

namespace rtsim::sortfirst {

/// Where a machine sorts primitives to screen regions (seed 004 L483-L515, Figs. 1-3), the same
/// renderers holding the same initial distribution:
///   First   a primitive moves to the regions it now covers and stays there (L503-L505);
///   Middle  each renderer keeps its initial share as a transformation processor and sends every
///           primitive to every region it covers, every frame (L509-L511; the two logical sets
///           on one set of hardware, L509);
///   Last    each renderer keeps its initial share, renders the whole screen from it and sends
///           its partial image to be depth-composited (L515); nothing is redistributed.
enum class Sort { First, Middle, Last };

struct HeldPrimitive {
  PrimitiveRecord record;           ///< as it arrived (what a migration sends on)
  raster::RasterTriangle triangle;  ///< the record unpacked
  RegionRange range;                ///< the regions it covered when last classified
  bool master = false;              ///< this renderer owns it
};

/// A record to send: to region `to`.
struct Migration {
  int to = 0;
  PrimitiveRecord record;
};

/// What one frame's classification did at one renderer.
struct ClassifyResult {
  std::vector<Migration> sends;      ///< in primitive order, then region order
  std::uint64_t classified = 0;      ///< primitives classified
  std::uint64_t dropped_copies = 0;  ///< copies no longer covering the region
};

class RegionStore {
 public:
  RegionStore(int region, const ScreenRegions& regions, std::size_t materials,
              Sort sort = Sort::First)
      : region_(region), regions_(regions), materials_(materials), sort_(sort) {}

  /// The initial distribution (L562): a master with nothing covered yet.
  void load(const PrimitiveRecord& r);
  /// Classifies everything held for `view`.
  ClassifyResult classify_all(const raster::ViewTransform& view);
  /// A record that migrated here, classified for the same view: kept if it covers the region
  /// (master if its upper-left region is this one). False if it was refused (a record that
  /// does not unpack, a database index past `primitives`, or not covering this region).
  bool receive(const PrimitiveRecord& r, const raster::ViewTransform& view,
               std::uint32_t primitives);

  /// What it renders this frame: the primitives whose range covers the region (Sort::Last: its
  /// share that is on the screen, for the whole screen).
  raster::RasterMesh to_render() const;
  std::size_t held() const { return held_.size(); }
  std::size_t masters() const;

 private:
  int region_;
  ScreenRegions regions_;
  std::size_t materials_;
  Sort sort_;
  std::map<std::uint32_t, HeldPrimitive> held_;  ///< by database index
};

/// The functional twin of the migration: for each frame's view, the number of records sent
/// (sum over primitives of the regions newly covered, not counting the old owner's), starting
/// from `initial_owner` (a region per primitive) with nothing covered.
std::vector<std::uint64_t> migration_counts(const raster::RasterMesh& mesh,
                                            const std::vector<raster::ViewTransform>& views,
                                            const ScreenRegions& regions,
                                            const std::vector<int>& initial_owner);

/// The study's random initial distribution (L562): each primitive's region, uniformly from a
/// generator seeded with `seed` (the same every run).
std::vector<int> random_distribution(std::size_t primitives, int regions, std::uint64_t seed);

}  // namespace rtsim::sortfirst
