#include "scenes/generators/npp_scene.hpp"

#include <array>
#include <cmath>
#include <stdexcept>

#include "common/splitmix64.hpp"

namespace rtsim::scenes {

namespace {

// --- Cluster shape and sphere sizes (assumption: the thesis shows only lost pictures, Figs
// 6-2..6-6, and says "64 clusters of randomly placed primitives", L970) -----------------------
// A cluster is a ball of radius kNppClusterRadius (cell units) centred at a random point of its
// cell, placed so the ball stays inside the cell shrunk by kNppCellMargin. Its spheres lie
// wholly inside the ball. Clusters are therefore visibly separate, with void between them, which
// is what makes a box-shell hierarchy over them worthwhile.
constexpr double kNppClusterRadius = 0.38;
// Largest sphere radius for pp spheres per cluster: kNppRadiusScale / sqrt(pp) cell units, so
// the silhouette area of a cluster (pp r^2) is about the same for every pp and the pictures of
// 204..820 look alike in coverage. A radius is drawn uniformly in [kNppMinRadiusFraction, 1] of
// that maximum.
constexpr double kNppRadiusScale = 0.3;
constexpr double kNppMinRadiusFraction = 0.55;
/// Smallest gap between two spheres of one cluster (cell units): no touching or overlapping.
constexpr double kNppMinGap = 0.01;
/// Rejection sampling: attempts to place one sphere before its radius is shrunk by
/// kNppShrinkFactor, and the number of shrinks before giving up. The spheres fill at most ~25 %
/// of the cluster ball (pp = 4 with every radius at its maximum; ~15 % on average), below
/// random-packing limits, so shrinking is rare: only pp = 2, whose two largest spheres cannot
/// both fit, needs it. Giving up is unreachable for pp <= 99. A draw outside the ball counts as
/// a failed attempt, so every loop is bounded.
constexpr int kNppPlacementAttempts = 1000;
constexpr double kNppShrinkFactor = 0.9;
constexpr int kNppMaxShrinks = 60;

// --- Look (assumption) -----------------------------------------------------------------------
// The grid spans [-2, 2]^3. The eye looks at its centre from above and to the front-right; a
// 32 degree field of view holds the grid's bounding sphere (radius 2 sqrt 3 = 3.46 at distance
// 13.0 needs 30.8 degrees) with a small border.
constexpr Vec3 kNppEye{7.0, -9.5, 5.5};
constexpr Vec3 kNppLookAt{0.0, 0.0, 0.0};
constexpr Vec3 kNppUp{0.0, 0.0, 1.0};
constexpr double kNppFieldOfViewDeg = 32.0;
constexpr int kNppImageSize = 512;
constexpr Color kNppBackground{0.05, 0.07, 0.12};
/// Key light high behind the eye, and a dimmer bluish fill from the left: two lights, so
/// shadow rays are exercised without doubling the cost of every hit more than needed.
constexpr std::array<Light, 2> kNppLights = {
    Light{Vec3{9.0, -6.0, 12.0}, Color{0.85, 0.85, 0.8}},
    Light{Vec3{-8.0, -10.0, 4.0}, Color{0.35, 0.35, 0.45}},
};
/// Sphere materials, drawn uniformly per sphere. Two of six are reflective (Ks >= 0.6), so
/// reflection rays appear, as in Gaudet's Whitted/Hall shading (seed 001 L258-L269).
const std::array<Material, 6> kNppPalette = {
    Material{Color{0.85, 0.22, 0.15}, 0.75, 0.25, 30.0, 0.0, 1.0},   // red plastic
    Material{Color{0.95, 0.75, 0.30}, 0.35, 0.65, 80.0, 0.0, 1.0},   // gold, reflective
    Material{Color{0.20, 0.40, 0.90}, 0.75, 0.25, 20.0, 0.0, 1.0},   // blue plastic
    Material{Color{0.25, 0.80, 0.35}, 0.80, 0.20, 15.0, 0.0, 1.0},   // green plastic
    Material{Color{0.90, 0.90, 0.95}, 0.20, 0.80, 200.0, 0.0, 1.0},  // chrome mirror
    Material{Color{0.95, 0.95, 0.92}, 0.90, 0.10, 10.0, 0.0, 1.0},   // white matte
};

constexpr double kGridHalfWidth = 0.5 * kNppCellsPerAxis * kNppCellSize;

/// Cell coordinates of Morton index k: x from bits 0,3; y from bits 1,4; z from bits 2,5.
std::array<int, 3> morton_cell(int k) {
  std::array<int, 3> c{0, 0, 0};
  for (int bit = 0; bit < 2; ++bit) {
    for (int axis = 0; axis < 3; ++axis) {
      c[static_cast<std::size_t>(axis)] |= ((k >> (3 * bit + axis)) & 1) << bit;
    }
  }
  return c;
}

}  // namespace

Bounds npp_cluster_cell(int cluster) {
  if (cluster < 0 || cluster >= kNppClusterCount) {
    throw std::invalid_argument("npp_cluster_cell: cluster out of range");
  }
  const auto c = morton_cell(cluster);
  Bounds b;
  b.lo = Vec3{c[0] * kNppCellSize - kGridHalfWidth, c[1] * kNppCellSize - kGridHalfWidth,
              c[2] * kNppCellSize - kGridHalfWidth};
  b.hi = b.lo + Vec3{kNppCellSize};
  return b;
}

Scene make_npp_scene(int branching, int spheres_per_cluster, std::uint64_t seed) {
  if (branching != 2 && branching != 4 && branching != 8) {
    throw std::invalid_argument("make_npp_scene: branching factor must be 2, 4 or 8");
  }
  if (spheres_per_cluster < kNppMinSpheresPerCluster ||
      spheres_per_cluster > kNppMaxSpheresPerCluster) {
    throw std::invalid_argument("make_npp_scene: spheres per cluster must be 1..99");
  }
  const int pp = spheres_per_cluster;
  Scene scene;
  scene.name =
      "builtin:npp-" + std::to_string(branching) + (pp < 10 ? "0" : "") + std::to_string(pp);
  scene.has_camera = true;
  scene.camera.from = kNppEye;
  scene.camera.at = kNppLookAt;
  scene.camera.up = kNppUp;
  scene.camera.angle_deg = kNppFieldOfViewDeg;
  scene.camera.width = kNppImageSize;
  scene.camera.height = kNppImageSize;
  scene.background = kNppBackground;
  scene.lights.assign(kNppLights.begin(), kNppLights.end());
  scene.materials.assign(kNppPalette.begin(), kNppPalette.end());

  // One stream per (seed, pp); n is not an input, so 2pp/4pp/8pp share primitive data (L970).
  SplitMix64 rng(seed * 0x100000001B3ull + static_cast<std::uint64_t>(pp));
  const double r_max = kNppRadiusScale * kNppCellSize / std::sqrt(static_cast<double>(pp));
  const double margin = kNppCellMargin * kNppCellSize;
  const auto count = static_cast<std::size_t>(kNppClusterCount * pp);
  scene.spheres.reserve(count);
  scene.primitives.reserve(count);
  scene.cluster_of_primitive.reserve(count);
  scene.cluster_branching = branching;

  for (int k = 0; k < kNppClusterCount; ++k) {
    const Bounds cell = npp_cluster_cell(k);
    const double ball_radius = kNppClusterRadius * kNppCellSize;
    Vec3 ball_centre;
    for (int a = 0; a < 3; ++a) {
      ball_centre[a] =
          rng.uniform(cell.lo[a] + margin + ball_radius, cell.hi[a] - margin - ball_radius);
    }
    const std::size_t first = scene.spheres.size();
    for (int s = 0; s < pp; ++s) {
      double r = r_max * rng.uniform(kNppMinRadiusFraction, 1.0);
      const std::uint64_t material = rng.below(kNppPalette.size());
      bool placed = false;
      for (int shrink = 0; shrink <= kNppMaxShrinks && !placed; ++shrink) {
        for (int attempt = 0; attempt < kNppPlacementAttempts && !placed; ++attempt) {
          // A point uniform in the ball of radius (ball_radius - r): rejection from its cube.
          const Vec3 u{rng.uniform(-1.0, 1.0), rng.uniform(-1.0, 1.0), rng.uniform(-1.0, 1.0)};
          if (glm::dot(u, u) > 1.0) continue;
          const Vec3 c = ball_centre + (ball_radius - r) * u;
          bool clear = true;
          for (std::size_t j = first; j < scene.spheres.size() && clear; ++j) {
            const double need = r + scene.spheres[j].radius + kNppMinGap * kNppCellSize;
            const Vec3 d = c - scene.spheres[j].center;
            clear = glm::dot(d, d) >= need * need;
          }
          if (clear) {
            scene.spheres.push_back(Sphere{c, r});
            placed = true;
          }
        }
        if (!placed) r *= kNppShrinkFactor;
      }
      if (!placed) throw std::logic_error("make_npp_scene: could not place a sphere");
      scene.primitives.push_back(Primitive{PrimitiveKind::Sphere,
                                           static_cast<std::uint32_t>(scene.spheres.size() - 1),
                                           static_cast<std::uint32_t>(material), 0});
      scene.cluster_of_primitive.push_back(static_cast<std::uint32_t>(k));
    }
  }
  return scene;
}

bool parse_npp_name(std::string_view name, int& branching, int& spheres_per_cluster) {
  constexpr std::string_view kPrefix = "npp-";
  if (name.size() != kPrefix.size() + 3 || name.substr(0, kPrefix.size()) != kPrefix) return false;
  const std::string_view digits = name.substr(kPrefix.size());
  for (char ch : digits) {
    if (ch < '0' || ch > '9') return false;
  }
  const int n = digits[0] - '0';
  const int pp = (digits[1] - '0') * 10 + (digits[2] - '0');
  if ((n != 2 && n != 4 && n != 8) || pp < kNppMinSpheresPerCluster ||
      pp > kNppMaxSpheresPerCluster) {
    return false;
  }
  branching = n;
  spheres_per_cluster = pp;
  return true;
}

NppShellCounts npp_expected_counts(int branching, int spheres_per_cluster) {
  if (branching != 2 && branching != 4 && branching != 8) {
    throw std::invalid_argument("npp_expected_counts: branching factor must be 2, 4 or 8");
  }
  NppShellCounts counts;
  // Level sizes of a complete tree with 64 leaves: b, b^2, ..., 64 below the root.
  for (int level = branching; level <= kNppClusterCount; level *= branching) {
    counts.shells += level;
    counts.shell_packets += level / branching;  // one packet per parent of this level
  }
  counts.primitives = kNppClusterCount * spheres_per_cluster;
  counts.primitive_packets = kNppClusterCount;
  return counts;
}

}  // namespace rtsim::scenes
