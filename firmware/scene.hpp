#pragma once
// The scene as read from a file or made by a generator: camera, lights, materials and primitives
// in scene-file order. Nothing here is converted for a machine yet; firmware/ and platform/ turn
// it into what a machine stores (triangles, Ullner quads, grid cells, shells and packets). The
// data the firmware consumes lives with it, below scenes/ (the readers and generators that fill
// it): the layers include only downwards.
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "firmware/bounds.hpp"
#include "firmware/math.hpp"

namespace rtsim::scenes {

/// NFF `v` block. angle is the full field of view in degrees across the image (NFF: "the angle
/// in degrees, as measured from the center of the top pixel to the center of the bottom pixel"
/// is how SPD writes it; we use it as the vertical full angle).
struct Camera {
  Vec3 from{0.0, 0.0, 5.0};
  Vec3 at{0.0};
  Vec3 up{0.0, 1.0, 0.0};
  double angle_deg = 45.0;
  double hither = 1e-3;
  int width = 512;
  int height = 512;
};

/// NFF `l`: a point light. NFF lights without a colour are white.
struct Light {
  Vec3 position{0.0};
  Color color{1.0};
};

/// NFF `f`: colour, diffuse Kd, specular Ks (also the mirror reflection weight), Phong exponent,
/// transmittance T, index of refraction.
struct Material {
  Color color{1.0};
  double kd = 1.0;
  double ks = 0.0;
  double shine = 0.0;
  double transmittance = 0.0;
  double ior = 1.0;
};

/// How a rasterizing machine shades and culls a material's surfaces (PixelFlow's shading
/// functions, seed 004 L97, L112). NFF has no such statement: its materials are Phong and seen
/// from both sides, as the ray tracers see them.
struct SurfaceShading {
  /// The shading function: "phong", or one of the bowling scene's "pin", "alley", "ball".
  std::string shader = "phong";
  /// The material covers closed surfaces only: their back faces are hidden anyway, and a
  /// rasterizer culls them (seed 004 L132 counts front-facing triangles).
  bool one_sided = false;
};

struct Sphere {
  Vec3 center{0.0};
  double radius = 1.0;
};

/// NFF `p` / `pp`: a planar polygon, possibly concave, vertices counter-clockwise.
/// `normals` is empty for `p`, one per vertex for `pp`. `uvs` (texture coordinates, one per
/// vertex) only generated scenes give: NFF has none, and a rasterizer then takes (0, 0).
struct Polygon {
  std::vector<Vec3> vertices;
  std::vector<Vec3> normals;
  std::vector<glm::dvec2> uvs;
};

/// NFF `c`: an open cone or cylinder (no end caps) between base and apex.
/// A negative radius means "seen from inside" (NFF); the geometry uses the absolute value.
struct Cone {
  Vec3 base{0.0};
  double base_radius = 1.0;
  Vec3 apex{0.0, 0.0, 1.0};
  double apex_radius = 1.0;
};

/// A bicubic Bezier patch. control[4*i + j] is P_ij: row i (the v direction), column j (u),
/// in the order of the .bpt file (16 points, row by row).
struct BezierPatch {
  std::array<Vec3, 16> control{};
  const Vec3& at(int i, int j) const { return control[static_cast<std::size_t>(4 * i + j)]; }
};

enum class PrimitiveKind : std::uint8_t { Sphere, Polygon, Cone, Patch };

/// One primitive in scene-file order. `index` points into the array of its kind.
struct Primitive {
  PrimitiveKind kind = PrimitiveKind::Sphere;
  std::uint32_t index = 0;
  std::uint32_t material = 0;
  std::uint32_t source_line = 0;  ///< line in the scene file (0 for generated scenes)
};

struct Scene {
  std::string name;  ///< file path or builtin:NAME
  Camera camera;
  bool has_camera = false;  ///< false for files without a view (e.g. .bpt): frame automatically
  Color background{0.0};
  std::vector<Light> lights;
  std::vector<Material> materials;
  /// One per material, or empty: every material "phong" and two-sided.
  std::vector<SurfaceShading> surface_shading;
  std::vector<Primitive> primitives;
  std::vector<Sphere> spheres;
  std::vector<Polygon> polygons;
  std::vector<Cone> cones;
  std::vector<BezierPatch> patches;
  /// Optional grouping of primitives into clusters (Gaudet's npp scenes: one cluster per leaf
  /// shell). Empty, or one entry per primitive giving its cluster number.
  std::vector<std::uint32_t> cluster_of_primitive;
  /// Branching factor of the shell hierarchy the clusters are meant for (Gaudet's npp scenes:
  /// the n of npp); 0 when the scene does not say.
  int cluster_branching = 0;

  /// Ullner's modelling space (seed 000 L2118: the space the grid divides), when the scene
  /// defines one (his synthetic scenes: the unit cube). Empty: the bounding box of the geometry.
  Bounds modelling_space;

  std::size_t primitive_count() const { return primitives.size(); }
};

}  // namespace rtsim::scenes
