#include "firmware/accel/gaudet_data_sets.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace rtsim::accel {
namespace {

std::uint32_t bits(float f) { return std::bit_cast<std::uint32_t>(f); }

}  // namespace

void RecordWriter::f32(double v) { word(bits(static_cast<float>(v))); }

void RecordWriter::f32_down(double v) {
  float f = static_cast<float>(v);
  if (static_cast<double>(f) > v) f = std::nextafter(f, -std::numeric_limits<float>::infinity());
  word(bits(f));
}

void RecordWriter::f32_up(double v) {
  float f = static_cast<float>(v);
  if (static_cast<double>(f) < v) f = std::nextafter(f, std::numeric_limits<float>::infinity());
  word(bits(f));
}

void RecordWriter::finish() {
  const std::size_t used = out_->size() - start_;
  if (used > words_) {
    throw std::invalid_argument(std::string("RecordWords: a ") + what_ + " record needs " +
                                std::to_string(used) + " words, the configured size is " +
                                std::to_string(words_));
  }
  out_->resize(start_ + words_, 0u);
}

void encode_shell(const Shell& s, const RecordWords& words, std::vector<std::uint32_t>& out) {
  RecordWriter w(out, words.shell, "SHELL");
  w.word(s.leaf ? 1u : 0u);                             // int leaf
  w.word(s.child_index);                                // int child_index
  for (int a = 0; a < 3; ++a) w.f32_up(s.box.hi[a]);    // COORD max
  for (int a = 0; a < 3; ++a) w.f32_down(s.box.lo[a]);  // COORD min
  w.finish();                                           // struct shell *next: implicit
}

Shell decode_shell(std::span<const std::uint32_t> record) {
  if (record.size() < 8) throw std::invalid_argument("a SHELL record needs 8 words");
  const auto single = [&record](std::size_t i) {
    return static_cast<double>(std::bit_cast<float>(record[i]));
  };
  Shell s;
  s.leaf = record[0] != 0;
  s.child_index = record[1];
  s.box.hi = Vec3(single(2), single(3), single(4));
  s.box.lo = Vec3(single(5), single(6), single(7));
  return s;
}

std::size_t decode_prim(std::span<const std::uint32_t> words, const RecordWords& rw,
                        PrimRecord& out) {
  const auto single = [&words](std::size_t i) {
    return static_cast<double>(std::bit_cast<float>(words[i]));
  };
  const std::size_t h = rw.prim_header;
  if (words.size() < std::max<std::size_t>(h, 3)) return 0;
  out.prim_id = words[0];
  out.surface_index = words[1];
  out.vertices.clear();
  if (words[2] == static_cast<std::uint32_t>(PrimType::Sphere)) {
    const std::size_t size = h + rw.sphere;
    if (rw.sphere < 4 || words.size() < size) return 0;
    out.type = PrimType::Sphere;
    out.center = Vec3(single(3), single(4), single(5));
    out.radius = single(6);
    return size;
  }
  if (words[2] == static_cast<std::uint32_t>(PrimType::Polygon)) {
    if (words.size() < 4) return 0;
    const std::uint32_t count = words[3] & 0x7fffffffu;
    const bool normals = (words[3] & 0x80000000u) != 0;
    const std::size_t size = h + rw.polygon_fixed + std::size_t{count} * rw.polygon_per_vertex +
                             (normals ? std::size_t{count} * rw.polygon_per_normal : 0);
    if (count < 3 || rw.polygon_per_vertex < 3 || words.size() < size ||
        words.size() < 4 + 3 * std::size_t{count})
      return 0;
    out.type = PrimType::Polygon;
    for (std::uint32_t v = 0; v < count; ++v)
      out.vertices.emplace_back(single(4 + 3 * v), single(5 + 3 * v), single(6 + 3 * v));
    return size;
  }
  return 0;
}

Bounds stored_shell_box(const Bounds& box) {
  std::vector<std::uint32_t> record;
  encode_shell(Shell{false, 0, box}, RecordWords{}, record);
  return decode_shell(record).box;
}

void encode_shade(const scenes::Material& m, const RecordWords& words,
                  std::vector<std::uint32_t>& out) {
  RecordWriter w(out, words.shade, "SHADE");
  w.f32(m.ks);  // float k_s
  w.f32(m.kd);  // float k_d
  const double n = std::isfinite(m.shine) ? std::round(std::clamp(m.shine, 0.0, 1e9)) : 0.0;
  w.word(static_cast<std::uint32_t>(static_cast<std::int32_t>(n)));  // int n
  w.coord(m.color);                                                  // RGB reflectance
  w.coord(Vec3(m.transmittance));                                    // RGB transmittance
  w.finish();
}

BroadcastImage shell_data_set(const ShellTree& tree, const RecordWords& words) {
  BroadcastImageBuilder b;
  for (std::size_t i = 0; i < tree.shell_packet_count(); ++i) {
    b.begin_packet();
    for (const Shell& s : tree.shell_packet(i)) encode_shell(s, words, b.words());
  }
  return std::move(b).finish(words.id_list_entry);
}

BroadcastImage prim_data_set(const ShellTree& tree, const PrimEncoder& encode,
                             const RecordWords& words) {
  BroadcastImageBuilder b;
  for (std::size_t j = 0; j < tree.prim_packet_count(); ++j) {
    b.begin_packet();
    for (const std::uint32_t slot : tree.prim_packet(j)) encode(slot, b.words());
  }
  return std::move(b).finish(words.id_list_entry);
}

BroadcastImage shade_data_set(std::span<const scenes::Material> materials,
                              const RecordWords& words) {
  BroadcastImageBuilder b;
  for (const scenes::Material& m : materials) {
    b.begin_packet();
    encode_shade(m, words, b.words());
  }
  return std::move(b).finish(words.id_list_entry);
}

PrimEncoder scene_prim_encoder(const scenes::Scene& scene, const RecordWords& words) {
  return [&scene, words](std::uint32_t slot, std::vector<std::uint32_t>& out) {
    const scenes::Primitive& p = scene.primitives.at(slot);
    std::uint32_t size = words.prim_header;
    PrimType type = PrimType::Sphere;
    switch (p.kind) {
      case scenes::PrimitiveKind::Sphere:
        size += words.sphere;
        type = PrimType::Sphere;
        break;
      case scenes::PrimitiveKind::Polygon: {
        const scenes::Polygon& poly = scene.polygons.at(p.index);
        size += words.polygon_fixed +
                words.polygon_per_vertex * static_cast<std::uint32_t>(poly.vertices.size()) +
                (poly.normals.empty()
                     ? 0u
                     : words.polygon_per_normal * static_cast<std::uint32_t>(poly.normals.size()));
        type = PrimType::Polygon;
        break;
      }
      case scenes::PrimitiveKind::Cone:
        size += words.cone;
        type = PrimType::Cone;
        break;
      case scenes::PrimitiveKind::Patch:
        size += words.patch;
        type = PrimType::Patch;
        break;
    }
    RecordWriter w(out, size, "PRIM");
    w.word(slot);                              // int prim_id
    w.word(p.material);                        // int surface_index
    w.word(static_cast<std::uint32_t>(type));  // int type
    switch (p.kind) {                          // PTYPE p
      case scenes::PrimitiveKind::Sphere: {
        const scenes::Sphere& s = scene.spheres.at(p.index);
        w.coord(s.center);
        w.f32(s.radius);
        break;
      }
      case scenes::PrimitiveKind::Polygon: {
        const scenes::Polygon& poly = scene.polygons.at(p.index);
        w.word(static_cast<std::uint32_t>(poly.vertices.size()) |
               (poly.normals.empty() ? 0u : 0x80000000u));
        for (const Vec3& v : poly.vertices) w.coord(v);
        for (const Vec3& n : poly.normals) w.coord(n);
        break;
      }
      case scenes::PrimitiveKind::Cone: {
        const scenes::Cone& c = scene.cones.at(p.index);
        w.coord(c.base);
        w.f32(c.base_radius);
        w.coord(c.apex);
        w.f32(c.apex_radius);
        break;
      }
      case scenes::PrimitiveKind::Patch:
        for (const Vec3& v : scene.patches.at(p.index).control) w.coord(v);
        break;
    }
    w.finish();  // struct prim *next: implicit
  };
}

GaudetDataSets make_gaudet_data_sets(const ShellTree& tree, const scenes::Scene& scene,
                                     const RecordWords& words) {
  return {shell_data_set(tree, words), prim_data_set(tree, scene_prim_encoder(scene, words), words),
          shade_data_set(scene.materials, words)};
}

}  // namespace rtsim::accel
