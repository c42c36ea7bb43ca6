#include "platform/machines/ullner_array/broadcast_record.hpp"

#include <bit>
#include <cmath>
#include <variant>

#include "firmware/kernels/ullner_quad_words.hpp"

namespace rtsim::platform::ullner_array {

namespace {

constexpr unsigned kKindShift = 28;

std::uint32_t header(RecordKind k, std::uint32_t flags = 0) {
  return (static_cast<std::uint32_t>(k) << kKindShift) | flags;
}

void put_vec(std::vector<std::uint32_t>& w, const Vec3& v) {
  for (int a = 0; a < 3; ++a) put_real(w, v[a]);
}

Vec3 get_vec(std::span<const std::uint32_t> w, std::size_t at) {
  return {get_real(w, at), get_real(w, at + 2), get_real(w, at + 4)};
}

// Words of one light (position, colour) and one material (colour, kd, ks, shine, T, ior).
constexpr std::size_t kLightWords = 12;
constexpr std::size_t kMaterialWords = 16;
constexpr std::size_t kViewWords = 1 + 6 + 6 + 6 + 2 + 2;

}  // namespace

void put_real(std::vector<std::uint32_t>& words, double v) {
  const auto bits = std::bit_cast<std::uint64_t>(v);
  words.push_back(static_cast<std::uint32_t>(bits));
  words.push_back(static_cast<std::uint32_t>(bits >> 32));
}

double get_real(std::span<const std::uint32_t> words, std::size_t at) {
  if (at + 1 >= words.size()) return 0.0;
  const double v = std::bit_cast<double>(static_cast<std::uint64_t>(words[at]) |
                                         (static_cast<std::uint64_t>(words[at + 1]) << 32));
  return std::isfinite(v) ? v : 0.0;
}

RecordKind record_kind(std::uint32_t h) {
  const std::uint32_t k = h >> kKindShift;
  return k >= 1 && k <= 3 ? static_cast<RecordKind>(k) : RecordKind::kNone;
}

std::size_t polygon_line_words(bool normals) { return kLineNormals + (normals ? kNormalWords : 0); }

std::size_t polygon_record_words(bool normals) {
  return polygon_line_words(normals) + kBoundsWords;
}

std::vector<std::uint32_t> polygon_record(const functional::SceneGeometry& g, std::uint32_t slot) {
  const auto& shape = g.shapes[slot];
  const auto& quad = std::get<kernels::UllnerQuadKernel>(shape.shape);
  std::vector<std::uint32_t> w;
  w.reserve(polygon_record_words(quad.has_corner_normals));
  w.push_back(header(RecordKind::kPolygon, quad.has_corner_normals ? kRecordHasNormals : 0));
  w.resize(kLineParams + kernels::kUllnerStoredWords);
  kernels::store_words(quad.params, std::span<std::uint32_t, kernels::kUllnerStoredWords>(
                                        w.data() + kLineParams, kernels::kUllnerStoredWords));
  w.push_back(static_cast<std::uint32_t>(shape.prim_id));
  w.push_back(shape.material);
  if (quad.has_corner_normals)
    for (const Vec3* n : {&quad.nrm_a, &quad.nrm_b, &quad.nrm_c, &quad.nrm_d}) put_vec(w, *n);
  put_vec(w, g.bounds[slot].lo);
  put_vec(w, g.bounds[slot].hi);
  return w;
}

Bounds polygon_bounds(std::span<const std::uint32_t> r) {
  if (r.size() < polygon_record_words(false)) return Bounds{};
  const std::size_t at = r.size() - kBoundsWords;
  Bounds b;
  b.lo = get_vec(r, at);
  b.hi = get_vec(r, at + 6);
  return b;
}

std::vector<std::uint32_t> attributes_record(const scenes::Scene& scene) {
  std::vector<std::uint32_t> w{header(RecordKind::kAttributes)};
  put_vec(w, scene.background);
  w.push_back(static_cast<std::uint32_t>(scene.lights.size()));
  for (const auto& l : scene.lights) {
    put_vec(w, l.position);
    put_vec(w, l.color);
  }
  w.push_back(static_cast<std::uint32_t>(scene.materials.size()));
  for (const auto& m : scene.materials) {
    put_vec(w, m.color);
    for (const double v : {m.kd, m.ks, m.shine, m.transmittance, m.ior}) put_real(w, v);
  }
  return w;
}

void read_attributes(std::span<const std::uint32_t> r, scenes::Scene& scene) {
  std::size_t at = 1;
  scene.background = get_vec(r, at);
  at += 6;
  // A count says how many follow; what the record does not hold is not read.
  auto count = [&](std::size_t each) {
    if (at >= r.size()) return std::size_t{0};
    const std::size_t n = r[at++];
    return std::min(n, (r.size() - at) / each);
  };
  const std::size_t lights = count(kLightWords);
  scene.lights.assign(lights, scenes::Light{});
  for (auto& l : scene.lights) {
    l.position = get_vec(r, at);
    l.color = get_vec(r, at + 6);
    at += kLightWords;
  }
  const std::size_t materials = count(kMaterialWords);
  scene.materials.assign(materials, scenes::Material{});
  for (auto& m : scene.materials) {
    m.color = get_vec(r, at);
    m.kd = get_real(r, at + 6);
    m.ks = get_real(r, at + 8);
    m.shine = get_real(r, at + 10);
    m.transmittance = get_real(r, at + 12);
    m.ior = get_real(r, at + 14);
    if (!(m.ior > 0.0)) m.ior = 1.0;  // refraction divides by it
    at += kMaterialWords;
  }
  // Every polygon names a material: a table emptied by a fault still has one.
  if (scene.materials.empty()) scene.materials.emplace_back();
}

std::vector<std::uint32_t> view_record(const scenes::Camera& c) {
  std::vector<std::uint32_t> w{header(RecordKind::kView)};
  put_vec(w, c.from);
  put_vec(w, c.at);
  put_vec(w, c.up);
  put_real(w, c.angle_deg);
  put_real(w, c.hither);
  return w;
}

void read_view(std::span<const std::uint32_t> r, scenes::Camera& c) {
  if (r.size() < kViewWords) return;
  scenes::Camera v = c;
  v.from = get_vec(r, 1);
  v.at = get_vec(r, 7);
  v.up = get_vec(r, 13);
  v.angle_deg = get_real(r, 19);
  v.hither = get_real(r, 21);
  // A view no camera can be made from (a fault): the processor keeps the one it had.
  const Vec3 dir = v.at - v.from;
  if (glm::length(dir) == 0.0 || !(v.angle_deg > 0.0 && v.angle_deg < 180.0) ||
      !std::isfinite(glm::length(dir)))
    return;
  c = v;
}

}  // namespace rtsim::platform::ullner_array
