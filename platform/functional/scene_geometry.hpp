#pragma once
// The functional renderer's geometry conversion: every scene primitive becomes one or more
// kernel shapes (polygons are triangulated by ear clipping; spheres, cones and Bezier patches
// map one to one). Each shape remembers the scene primitive it came from (its prim_id, the
// index in scene-file order) and its material. Degenerate primitives are skipped and counted.
#include <cstdint>
#include <memory>
#include <string>
#include <variant>
#include <vector>

#include "firmware/bounds.hpp"
#include "firmware/kernels/bezier_patch_kernel.hpp"
#include "firmware/kernels/cone.hpp"
#include "firmware/kernels/sphere.hpp"
#include "firmware/kernels/triangle.hpp"
#include "firmware/kernels/ullner_quad.hpp"
#include "firmware/scene.hpp"
#include "platform/functional/render_params.hpp"

namespace rtsim::functional {

/// Wang's patch kernel holds two control nets (about 630 bytes): it is kept behind a pointer so
/// that the shapes of large polygon scenes (a million of Ullner's quads) stay small.
struct PatchShape {
  std::unique_ptr<const kernels::BezierPatchKernel> kernel;

  static constexpr Cost kTestCost = kernels::BezierPatchKernel::kTestCost;
  bool intersect(const Ray& ray, double t_min, double t_max, SurfaceHit& hit,
                 kernels::WangCounters* counters = nullptr) const {
    return kernel->intersect(ray, t_min, t_max, hit, counters);
  }
  Bounds bounds() const { return kernel->bounds(); }
};

using Shape = std::variant<kernels::TriangleKernel, kernels::UllnerQuadKernel,
                           kernels::SphereKernel, kernels::ConeKernel, PatchShape>;

struct ShapeRecord {
  Shape shape;
  std::int32_t prim_id = -1;
  std::uint32_t material = 0;
};

struct ConversionReport {
  std::size_t triangles = 0;
  std::size_t quads = 0;  ///< Ullner quads (triangles among them given as quads)
  std::size_t spheres = 0;
  std::size_t cones = 0;
  std::size_t patches = 0;
  std::size_t rejected = 0;           ///< primitives skipped as degenerate
  std::vector<std::string> messages;  ///< the first few reasons, with the source line
};

struct SceneGeometry {
  std::vector<ShapeRecord> shapes;
  std::vector<Bounds> bounds;  ///< one per shape
  Bounds scene_bounds;         ///< of all shapes (empty for an empty scene)
  ConversionReport report;
  std::string accel_description;  ///< filled by make_tracer
};

/// How many rejection messages are kept (the count is always exact).
inline constexpr std::size_t kMaxConversionMessages = 20;

SceneGeometry convert_scene(const scenes::Scene& scene, const RenderSettings& settings);

/// Largest side of the scene box, at least a tiny positive value.
double scene_extent(const Bounds& b);

}  // namespace rtsim::functional
