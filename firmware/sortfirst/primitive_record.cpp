#include "firmware/sortfirst/primitive_record.hpp"

#include <bit>
#include <cmath>
#include <string>

#include "common/input_error.hpp"

namespace rtsim::sortfirst {

namespace {

constexpr std::uint32_t kOneSidedBit = 1u << 31;

std::uint32_t word_of(double v) { return std::bit_cast<std::uint32_t>(static_cast<float>(v)); }

bool float_of(std::uint32_t w, double& out) {
  const float f = std::bit_cast<float>(w);
  if (!std::isfinite(f)) return false;
  out = f;
  return true;
}

}  // namespace

PrimitiveRecord pack(const raster::RasterTriangle& t, std::uint32_t id) {
  PrimitiveRecord r;
  std::size_t k = 0;
  for (const auto& v : t.v) {
    for (int i = 0; i < 3; ++i) r.words[k++] = word_of(v.position[i]);
    for (int i = 0; i < 3; ++i) r.words[k++] = word_of(v.normal[i]);
    for (int i = 0; i < 2; ++i) r.words[k++] = word_of(v.uv[i]);
  }
  for (int i = 0; i < 3; ++i) r.words[k++] = word_of(t.face_normal[i]);
  r.words[k++] = (t.material & ~kOneSidedBit) | (t.one_sided ? kOneSidedBit : 0u);
  r.words[k++] = t.primitive;
  r.words[k++] = id;
  return r;
}

std::optional<raster::RasterTriangle> unpack(const PrimitiveRecord& r, std::size_t materials) {
  raster::RasterTriangle t;
  std::size_t k = 0;
  for (auto& v : t.v) {
    for (int i = 0; i < 3; ++i)
      if (!float_of(r.words[k++], v.position[i])) return std::nullopt;
    for (int i = 0; i < 3; ++i)
      if (!float_of(r.words[k++], v.normal[i])) return std::nullopt;
    for (int i = 0; i < 2; ++i)
      if (!float_of(r.words[k++], v.uv[i])) return std::nullopt;
  }
  for (int i = 0; i < 3; ++i)
    if (!float_of(r.words[k++], t.face_normal[i])) return std::nullopt;
  const std::uint32_t m = r.words[k++];
  t.material = m & ~kOneSidedBit;
  t.one_sided = (m & kOneSidedBit) != 0;
  if (t.material >= materials) return std::nullopt;
  t.primitive = r.words[k++];
  return t;
}

raster::RasterMesh stored_mesh(const raster::RasterMesh& mesh, std::size_t materials) {
  raster::RasterMesh out;
  out.triangles.reserve(mesh.triangles.size());
  for (const auto& t : mesh.triangles) {
    const auto stored =
        unpack(pack(t, static_cast<std::uint32_t>(out.triangles.size())), materials);
    if (!stored)
      throw InputError("", 0,
                       "sort-first: scene primitive " + std::to_string(t.primitive) +
                           " has a coordinate beyond single precision (a renderer keeps "
                           "primitives as 32-bit floats)");
    out.triangles.push_back(*stored);
    for (const auto& v : out.triangles.back().v) out.bounds.extend(v.position);
  }
  return out;
}

}  // namespace rtsim::sortfirst
