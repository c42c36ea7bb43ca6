#pragma once
// Helpers shared by the scene tests (header only; not a test executable of its own).
#include <gtest/gtest.h>

#include <functional>
#include <string>

#include "common/input_error.hpp"
#include "firmware/scene.hpp"

namespace rtsim::scenes::testing {

inline std::string shared_scene(const std::string& file) {
  return std::string(RTSIM_SHARED_DIR) + "/scenes/" + file;
}

/// Runs `fn`, which must throw exactly one rtsim::InputError at `line` whose message contains
/// `fragment`. Returns the message for further checks.
inline std::string expect_input_error(const std::function<void()>& fn, std::size_t line,
                                      const std::string& fragment) {
  try {
    fn();
  } catch (const InputError& e) {
    EXPECT_EQ(e.line(), line) << "message: " << e.what();
    EXPECT_NE(e.message().find(fragment), std::string::npos)
        << "expected fragment: " << fragment << "\nactual message:   " << e.message();
    return e.what();
  } catch (const std::exception& e) {
    ADD_FAILURE() << "threw a non-InputError: " << e.what();
    return {};
  }
  ADD_FAILURE() << "did not throw; expected line " << line << ": " << fragment;
  return {};
}

/// Structural invariants every parsed or generated scene must satisfy: indices in range, every
/// number finite, polygons with >= 3 vertices and matching normal counts.
inline void expect_scene_sound(const Scene& s) {
  auto finite = [](const Vec3& v) { return is_finite(v); };
  ASSERT_TRUE(finite(s.background));
  for (const Light& l : s.lights) ASSERT_TRUE(finite(l.position) && finite(l.color));
  for (const Material& m : s.materials) {
    ASSERT_TRUE(finite(m.color) && std::isfinite(m.kd) && std::isfinite(m.ks) &&
                std::isfinite(m.shine) && std::isfinite(m.transmittance) && std::isfinite(m.ior));
  }
  for (const Primitive& p : s.primitives) {
    ASSERT_LT(p.material, s.materials.size());
    switch (p.kind) {
      case PrimitiveKind::Sphere:
        ASSERT_LT(p.index, s.spheres.size());
        ASSERT_TRUE(finite(s.spheres[p.index].center));
        ASSERT_GT(s.spheres[p.index].radius, 0.0);
        break;
      case PrimitiveKind::Polygon: {
        ASSERT_LT(p.index, s.polygons.size());
        const Polygon& poly = s.polygons[p.index];
        ASSERT_GE(poly.vertices.size(), 3u);
        ASSERT_TRUE(poly.normals.empty() || poly.normals.size() == poly.vertices.size());
        for (const Vec3& v : poly.vertices) ASSERT_TRUE(finite(v));
        for (const Vec3& v : poly.normals) ASSERT_TRUE(finite(v));
        break;
      }
      case PrimitiveKind::Cone:
        ASSERT_LT(p.index, s.cones.size());
        ASSERT_TRUE(finite(s.cones[p.index].base) && finite(s.cones[p.index].apex));
        break;
      case PrimitiveKind::Patch:
        ASSERT_LT(p.index, s.patches.size());
        for (const Vec3& v : s.patches[p.index].control) ASSERT_TRUE(finite(v));
        break;
    }
  }
  ASSERT_TRUE(s.cluster_of_primitive.empty() ||
              s.cluster_of_primitive.size() == s.primitives.size());
  if (s.has_camera) {
    ASSERT_GT(s.camera.width, 0);
    ASSERT_GT(s.camera.height, 0);
    ASSERT_TRUE(finite(s.camera.from) && finite(s.camera.at) && finite(s.camera.up));
  }
}

/// Exact equality of two scenes' view: camera, background and lights.
inline void expect_same_view(const Scene& a, const Scene& b) {
  ASSERT_EQ(a.has_camera, b.has_camera);
  if (a.has_camera) {
    EXPECT_EQ(a.camera.from, b.camera.from);
    EXPECT_EQ(a.camera.at, b.camera.at);
    EXPECT_EQ(a.camera.up, b.camera.up);
    EXPECT_EQ(a.camera.angle_deg, b.camera.angle_deg);
    EXPECT_EQ(a.camera.hither, b.camera.hither);
    EXPECT_EQ(a.camera.width, b.camera.width);
    EXPECT_EQ(a.camera.height, b.camera.height);
  }
  EXPECT_EQ(a.background, b.background);
  ASSERT_EQ(a.lights.size(), b.lights.size());
  for (std::size_t i = 0; i < a.lights.size(); ++i) {
    EXPECT_EQ(a.lights[i].position, b.lights[i].position);
    EXPECT_EQ(a.lights[i].color, b.lights[i].color);
  }
}

/// Exact equality of two scenes' content (name and source lines excluded). Materials are
/// compared through the primitives that use them, so dedup order does not matter.
inline void expect_same_content(const Scene& a, const Scene& b) {
  expect_same_view(a, b);
  ASSERT_EQ(a.primitives.size(), b.primitives.size());
  for (std::size_t i = 0; i < a.primitives.size(); ++i) {
    const Primitive& pa = a.primitives[i];
    const Primitive& pb = b.primitives[i];
    ASSERT_EQ(pa.kind, pb.kind) << "primitive " << i;
    const Material& ma = a.materials.at(pa.material);
    const Material& mb = b.materials.at(pb.material);
    EXPECT_TRUE(ma.color == mb.color && ma.kd == mb.kd && ma.ks == mb.ks && ma.shine == mb.shine &&
                ma.transmittance == mb.transmittance && ma.ior == mb.ior)
        << "material of primitive " << i;
    switch (pa.kind) {
      case PrimitiveKind::Sphere:
        EXPECT_EQ(a.spheres[pa.index].center, b.spheres[pb.index].center);
        EXPECT_EQ(a.spheres[pa.index].radius, b.spheres[pb.index].radius);
        break;
      case PrimitiveKind::Polygon:
        EXPECT_EQ(a.polygons[pa.index].vertices, b.polygons[pb.index].vertices);
        EXPECT_EQ(a.polygons[pa.index].normals, b.polygons[pb.index].normals);
        break;
      case PrimitiveKind::Cone:
        EXPECT_EQ(a.cones[pa.index].base, b.cones[pb.index].base);
        EXPECT_EQ(a.cones[pa.index].apex, b.cones[pb.index].apex);
        EXPECT_EQ(a.cones[pa.index].base_radius, b.cones[pb.index].base_radius);
        EXPECT_EQ(a.cones[pa.index].apex_radius, b.cones[pb.index].apex_radius);
        break;
      case PrimitiveKind::Patch:
        EXPECT_EQ(a.patches[pa.index].control, b.patches[pb.index].control);
        break;
    }
  }
}

}  // namespace rtsim::scenes::testing
