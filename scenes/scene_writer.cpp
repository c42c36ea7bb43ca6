#include "scenes/scene_writer.hpp"

#include <charconv>
#include <stdexcept>

namespace rtsim::scenes {

namespace {

/// Shortest text that reads back to exactly `v`.
void put(std::string& out, double v) {
  char buf[32];
  const auto [ptr, ec] = std::to_chars(buf, buf + sizeof buf, v);
  out.append(buf, ec == std::errc{} ? ptr : buf);
}

void put(std::string& out, const Vec3& v) {
  put(out, v.x);
  out += ' ';
  put(out, v.y);
  out += ' ';
  put(out, v.z);
}

void line(std::string& out, const char* keyword, const Vec3& v) {
  out += keyword;
  out += ' ';
  put(out, v);
  out += '\n';
}

}  // namespace

std::string write_nff(const Scene& scene) {
  std::string out;
  out += "# ";
  for (char ch : scene.name) {
    out += (static_cast<unsigned char>(ch) < 0x20 || ch == 0x7F) ? '?' : ch;  // keep one line
  }
  out += " (written by rtsim)\n";
  line(out, "b", scene.background);
  if (scene.has_camera) {
    const Camera& c = scene.camera;
    out += "v\n";
    line(out, "from", c.from);
    line(out, "at", c.at);
    line(out, "up", c.up);
    out += "angle ";
    put(out, c.angle_deg);
    out += "\nhither ";
    put(out, c.hither);
    out += "\nresolution " + std::to_string(c.width) + ' ' + std::to_string(c.height) + '\n';
  }
  for (const Light& l : scene.lights) {
    out += "l ";
    put(out, l.position);
    out += ' ';
    put(out, l.color);
    out += '\n';
  }
  bool have_material = false;
  std::uint32_t material = 0;
  for (const Primitive& p : scene.primitives) {
    if (!have_material || p.material != material) {
      const Material& m = scene.materials.at(p.material);
      out += "f ";
      put(out, m.color);
      for (double v : {m.kd, m.ks, m.shine, m.transmittance, m.ior}) {
        out += ' ';
        put(out, v);
      }
      out += '\n';
      have_material = true;
      material = p.material;
    }
    switch (p.kind) {
      case PrimitiveKind::Sphere: {
        const Sphere& s = scene.spheres.at(p.index);
        out += "s ";
        put(out, s.center);
        out += ' ';
        put(out, s.radius);
        out += '\n';
        break;
      }
      case PrimitiveKind::Cone: {
        const Cone& c = scene.cones.at(p.index);
        out += "c\n";
        put(out, c.base);
        out += ' ';
        put(out, c.base_radius);
        out += '\n';
        put(out, c.apex);
        out += ' ';
        put(out, c.apex_radius);
        out += '\n';
        break;
      }
      case PrimitiveKind::Polygon: {
        const Polygon& poly = scene.polygons.at(p.index);
        const bool normals = !poly.normals.empty();
        out += normals ? "pp " : "p ";
        out += std::to_string(poly.vertices.size());
        out += '\n';
        for (std::size_t i = 0; i < poly.vertices.size(); ++i) {
          put(out, poly.vertices[i]);
          if (normals) {
            out += ' ';
            put(out, poly.normals.at(i));
          }
          out += '\n';
        }
        break;
      }
      case PrimitiveKind::Patch:
        throw std::invalid_argument("write_nff: NFF cannot hold Bezier patches");
    }
  }
  return out;
}

std::string write_bpt(const Scene& scene) {
  std::string out = std::to_string(scene.primitives.size()) + '\n';
  for (const Primitive& p : scene.primitives) {
    if (p.kind != PrimitiveKind::Patch) {
      throw std::invalid_argument("write_bpt: .bpt holds only Bezier patches");
    }
    out += "3 3\n";
    for (const Vec3& v : scene.patches.at(p.index).control) {
      put(out, v);
      out += '\n';
    }
  }
  return out;
}

}  // namespace rtsim::scenes
