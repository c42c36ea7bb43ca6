#pragma once
// What the host of Ullner's ray-tracing array broadcasts to every processor (seed 000 L785-L797),
// as the words on the links. Three kinds of record, in this order:
//   polygon      one a polygon (L787, L791: "information needed to apply a shading model must
//                be included"): a header, the peripheral's 25-word line (the 20 parameters, 4
//                pole thresholds, flags; ullner_quad_words.hpp), the polygon's identity (its
//                number in scene-file order) and material number, its corner normals when it
//                has them (4 coefficient vectors, L452-L456), and its bounding box, which the
//                keep test reads (L787);
//   attributes   "the other attributes of the scene, including the positions and intensities
//                of every light source" (L789): the background, the lights, the materials;
//   view         "the viewing parameters" (L795): eye, look-at point, up vector, field of view,
//                hither distance. The image size is the array's frame buffer (configuration).
// The header word holds the kind in bits 28-31 and, for a polygon, whether corner normals follow
// in bit 0. A real number is an IEEE double in two words (low, then high) so that what the
// processors compute from the words is exactly what the functional render computes (the thesis's
// 32-bit singles would change the image in its last bits: a what-if not modelled).
//
// A processor keeps a polygon record in its memory without the bounding box: the line its
// intersection unit and shading read (kLine* offsets). Decoding never reads past a record: a
// corrupted count or flag (a fault) gives fewer lights or no corner normals, never a crash.
#include <cstdint>
#include <span>
#include <vector>

#include "firmware/bounds.hpp"
#include "firmware/scene.hpp"
#include "platform/functional/scene_geometry.hpp"

namespace rtsim::platform::ullner_array {

enum class RecordKind : std::uint32_t { kNone = 0, kPolygon = 1, kAttributes = 2, kView = 3 };

/// A polygon header's flag: corner normals follow its material.
inline constexpr std::uint32_t kRecordHasNormals = 1u << 0;

/// The kind a record's header word gives.
RecordKind record_kind(std::uint32_t header);

// A polygon's line, offsets from its header word.
inline constexpr std::size_t kLineParams = 1;     ///< the 25 words of the peripheral's line
inline constexpr std::size_t kLineIdentity = 26;  ///< its number in scene-file order
inline constexpr std::size_t kLineMaterial = 27;  ///< its material's number
inline constexpr std::size_t kLineNormals = 28;   ///< 4 vectors of doubles, 24 words, if flagged
inline constexpr std::size_t kNormalWords = 24;
inline constexpr std::size_t kBoundsWords = 12;  ///< lo, hi: 6 doubles, the record's last words
/// Words of a polygon record and of the line kept from it (with and without corner normals).
std::size_t polygon_record_words(bool normals);
std::size_t polygon_line_words(bool normals);

/// The host's records, from its copy of the scene (the polygons as the functional model converts
/// them: an Ullner quad each).
std::vector<std::uint32_t> polygon_record(const functional::SceneGeometry& g, std::uint32_t slot);
std::vector<std::uint32_t> attributes_record(const scenes::Scene& scene);
std::vector<std::uint32_t> view_record(const scenes::Camera& camera);

/// A processor's reading of its memory. `record` spans one record from its header.
/// The bounding box a polygon record carries (empty if the record is too short).
Bounds polygon_bounds(std::span<const std::uint32_t> record);
/// Background, lights and materials into `scene` (what a record holds of them).
void read_attributes(std::span<const std::uint32_t> record, scenes::Scene& scene);
/// The view into `camera` (left as it was if the record is too short).
void read_view(std::span<const std::uint32_t> record, scenes::Camera& camera);

/// One real number as two words, and back.
void put_real(std::vector<std::uint32_t>& words, double v);
double get_real(std::span<const std::uint32_t> words, std::size_t at);

}  // namespace rtsim::platform::ullner_array
