#pragma once
// A sort-first primitive as a region renderer holds it in memory and sends it when it migrates
// (seed 004 L503-L505: "the processors redistribute the primitives"): one mesh triangle in
// 32-bit words, single-precision floats as a 1995 geometry processor keeps them.
//
//   3 vertices x (position 3, shading normal 3, u v 2)   24 words
//   face normal                                           3 words
//   material | one_sided << 31                            1 word
//   scene primitive id                                    1 word
//   the primitive's index in the database                  1 word
//
// 30 words, 120 bytes (the seed gives no format: this model's, named here). The database a
// machine holds is its primitives in this form, so the machine and its functional twin
// rasterize the same single-precision triangles (stored_mesh). A record with a word that is not
// a finite float (a corrupted word) is refused by unpack: the renderer drops it.
#include <array>
#include <cstdint>
#include <optional>

#include "firmware/raster/raster_mesh.hpp"

namespace rtsim::sortfirst {

inline constexpr int kRecordWords = 30;
inline constexpr int kRecordBytes = 4 * kRecordWords;

struct PrimitiveRecord {
  std::array<std::uint32_t, kRecordWords> words{};
};

/// Triangle `t`, the database's primitive `id`.
PrimitiveRecord pack(const raster::RasterTriangle& t, std::uint32_t id);
/// The database index a record names (its last word).
inline std::uint32_t record_id(const PrimitiveRecord& r) { return r.words[kRecordWords - 1]; }
/// The triangle a record holds; nothing if a float word is not finite or the material word
/// names no material below `materials`.
std::optional<raster::RasterTriangle> unpack(const PrimitiveRecord& r, std::size_t materials);

/// `mesh` as the machine stores it: every triangle through pack and unpack.
raster::RasterMesh stored_mesh(const raster::RasterMesh& mesh, std::size_t materials);

}  // namespace rtsim::sortfirst
