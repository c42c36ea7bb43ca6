#pragma once
// builtin:ullner-mosaic-N — a scene for the scan-line tree's bandwidth (seed 000 L1551-L1594):
// one flat sheet facing the eye, cut into N columns and 8 rows of quadrilaterals, that fills the
// view. Every scan line crosses N quadrilaterals, 2N triangles once the rasterization layer has
// split them, so it needs 2N segments, and none of them is hidden: the segments a line the tree
// must deliver is 2N, with no segment created or destroyed on the way up (the balance L1557
// assumes). Two materials in a checkerboard, no lights.
#include <cstddef>
#include <optional>
#include <string_view>

#include "firmware/scene.hpp"

namespace rtsim::scenes {

inline constexpr std::string_view kUllnerMosaicPrefix = "ullner-mosaic-";
inline constexpr std::size_t kUllnerMosaicRows = 8;
inline constexpr std::size_t kUllnerMosaicMinColumns = 1;
/// x is a 12-bit word in the tree (4096 steps a line): more columns would be under a step.
inline constexpr std::size_t kUllnerMosaicMaxColumns = 4096;

/// The mosaic of `columns` x kUllnerMosaicRows quadrilaterals.
Scene make_ullner_mosaic(std::size_t columns);

/// N of a name "ullner-mosaic-N" (decimal, no sign, no leading zero); nullopt if the name is not
/// of that form.
std::optional<std::size_t> parse_ullner_mosaic_name(std::string_view name);

}  // namespace rtsim::scenes
