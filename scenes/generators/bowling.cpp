#include "scenes/generators/bowling.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

namespace rtsim::scenes {

namespace {

constexpr double kInch = 0.0254;  // metres
constexpr double kPinHeight = 15.0 * kInch;
constexpr double kPinSpacing = 12.0 * kInch;
constexpr double kLaneWidth = 41.5 * kInch;
constexpr double kBallRadius = 4.25 * kInch;

/// A pin's profile: (height, radius) in inches, base to top (after the USBC drawing's
/// landmarks: 2.03 in across the base, 4.766 in at the belly 4.5 in up, 1.797 in at the neck
/// 9.4 in up, 2.547 in across the head 13.5 in up).
constexpr std::array<std::array<double, 2>, 12> kPinProfile = {{{0.0, 1.015},
                                                                {0.75, 1.45},
                                                                {2.25, 2.05},
                                                                {4.5, 2.383},
                                                                {6.5, 2.2},
                                                                {8.0, 1.62},
                                                                {9.4, 0.899},
                                                                {10.6, 0.95},
                                                                {12.0, 1.2},
                                                                {13.5, 1.274},
                                                                {14.6, 0.95},
                                                                {15.0, 0.0}}};

enum MaterialId : std::uint32_t { kPin, kAlley, kBall };

/// The profile at parameter s in [0, 1] along its points (Catmull-Rom through them), with its
/// derivative: (height, radius) and (dh, dr).
void profile_at(double s, double& h, double& r, double& dh, double& dr) {
  const int n = static_cast<int>(kPinProfile.size());
  const double t = s * (n - 1);
  const int i = std::min(n - 2, static_cast<int>(std::floor(t)));
  const double f = t - i;
  const auto p = [&](int k, int c) {
    return kPinProfile[static_cast<std::size_t>(std::clamp(k, 0, n - 1))]
                      [static_cast<std::size_t>(c)];
  };
  for (int c = 0; c < 2; ++c) {
    const double p0 = p(i - 1, c), p1 = p(i, c), p2 = p(i + 1, c), p3 = p(i + 2, c);
    const double a = -0.5 * p0 + 1.5 * p1 - 1.5 * p2 + 0.5 * p3;
    const double b = p0 - 2.5 * p1 + 2.0 * p2 - 0.5 * p3;
    const double cc = -0.5 * p0 + 0.5 * p2;
    const double v = ((a * f + b) * f + cc) * f + p1;
    const double d = (3.0 * a * f + 2.0 * b) * f + cc;
    (c == 0 ? h : r) = v * kInch;
    (c == 0 ? dh : dr) = d * kInch;
  }
  r = std::max(0.0, r);
}

/// A rotation about the horizontal axis `axis` (unit, z = 0) by `angle` radians.
Vec3 rotate(const Vec3& v, const Vec3& axis, double angle) {
  const double c = std::cos(angle), s = std::sin(angle);
  return v * c + glm::cross(axis, v) * s + axis * glm::dot(axis, v) * (1.0 - c);
}

struct Builder {
  Scene& scene;
  void triangle(const std::array<Vec3, 3>& p, const std::array<Vec3, 3>& n,
                const std::array<glm::dvec2, 3>& uv, std::uint32_t material) {
    Polygon poly;
    poly.vertices = {p[0], p[1], p[2]};
    poly.normals = {n[0], n[1], n[2]};
    poly.uvs = {uv[0], uv[1], uv[2]};
    const double area = glm::length(glm::cross(p[1] - p[0], p[2] - p[0]));
    if (!(area > 1e-14)) return;
    scene.primitives.push_back(
        {PrimitiveKind::Polygon, static_cast<std::uint32_t>(scene.polygons.size()), material, 0});
    scene.polygons.push_back(std::move(poly));
  }
};

/// A pin standing at `base` (its axis up), leaning by `lean` radians about `axis`.
void add_pin(Builder& b, const Vec3& base, const Vec3& axis, double lean) {
  const int segs = kBowlingPinSegments, rings = kBowlingPinRings;
  struct Ring {
    double h, r;
    double nh, nr;  // the surface normal's height and radial parts
  };
  std::vector<Ring> ring(static_cast<std::size_t>(rings + 1));
  for (int i = 0; i <= rings; ++i) {
    double h, r, dh, dr;
    profile_at(double(i) / rings, h, r, dh, dr);
    // The profile's normal: perpendicular to its tangent (dh, dr), pointing out.
    const double len = std::hypot(dh, dr);
    ring[static_cast<std::size_t>(i)] = {h, r, len > 0 ? -dr / len : 1.0, len > 0 ? dh / len : 0.0};
  }
  ring.back().nh = 1.0;  // the top: straight up
  ring.back().nr = 0.0;
  const auto place = [&](const Vec3& local) { return base + rotate(local, axis, lean); };
  const auto orient = [&](const Vec3& local) { return rotate(local, axis, lean); };
  const auto vertex = [&](int i, int j, Vec3& p, Vec3& n, glm::dvec2& uv) {
    const Ring& g = ring[static_cast<std::size_t>(i)];
    const double phi = 2.0 * kPi * j / segs;
    const Vec3 radial(std::cos(phi), std::sin(phi), 0.0);
    p = place(radial * g.r + Vec3(0.0, 0.0, g.h));
    n = orient(glm::normalize(radial * g.nr + Vec3(0.0, 0.0, g.nh)));
    uv = glm::dvec2(double(j) / segs, 0.999 * g.h / kPinHeight);
  };
  for (int i = 0; i < rings; ++i)
    for (int j = 0; j < segs; ++j) {
      std::array<Vec3, 4> p, n;
      std::array<glm::dvec2, 4> uv;
      vertex(i, j, p[0], n[0], uv[0]);
      vertex(i, j + 1, p[1], n[1], uv[1]);
      vertex(i + 1, j + 1, p[2], n[2], uv[2]);
      vertex(i + 1, j, p[3], n[3], uv[3]);
      b.triangle({p[0], p[1], p[2]}, {n[0], n[1], n[2]}, {uv[0], uv[1], uv[2]}, kPin);
      if (i + 1 < rings)  // the top ring is a point: its quads are triangles
        b.triangle({p[0], p[2], p[3]}, {n[0], n[2], n[3]}, {uv[0], uv[2], uv[3]}, kPin);
    }
  // The base: a disc facing down.
  const Vec3 down = orient(Vec3(0.0, 0.0, -1.0));
  const Vec3 centre = place(Vec3(0.0));
  for (int j = 0; j < segs; ++j) {
    Vec3 p0, p1, n0;
    glm::dvec2 uv0, uv1;
    vertex(0, j, p0, n0, uv0);
    vertex(0, j + 1, p1, n0, uv1);
    b.triangle({centre, p1, p0}, {down, down, down}, {glm::dvec2(0.0), uv1, uv0}, kPin);
  }
}

void add_ball(Builder& b, const Vec3& centre) {
  const int segs = kBowlingBallSegments, rings = kBowlingBallRings;
  const auto vertex = [&](int i, int j, Vec3& p, Vec3& n, glm::dvec2& uv) {
    const double theta = kPi * i / rings, phi = 2.0 * kPi * j / segs;
    n = Vec3(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta));
    p = centre + kBallRadius * n;
    uv = glm::dvec2(double(j) / segs, 0.999 * i / rings);
  };
  for (int i = 0; i < rings; ++i)
    for (int j = 0; j < segs; ++j) {
      std::array<Vec3, 4> p, n;
      std::array<glm::dvec2, 4> uv;
      vertex(i, j, p[0], n[0], uv[0]);
      vertex(i + 1, j, p[1], n[1], uv[1]);
      vertex(i + 1, j + 1, p[2], n[2], uv[2]);
      vertex(i, j + 1, p[3], n[3], uv[3]);
      if (i > 0) b.triangle({p[0], p[1], p[3]}, {n[0], n[1], n[3]}, {uv[0], uv[1], uv[3]}, kBall);
      if (i + 1 < rings)
        b.triangle({p[3], p[1], p[2]}, {n[3], n[1], n[2]}, {uv[3], uv[1], uv[2]}, kBall);
    }
}

/// The lane's top, z = 0, from 7.8 m before the headpin (y = -7.8 m) to the pin deck's end (y = 1.2
/// m): 8 strips across, 1 m steps along. u across the lane, v along it (the wood repeats every 2
/// m).
void add_alley(Builder& b) {
  const int across = 8;
  const double y0 = -7.8, y1 = 1.2, step = 1.0;
  const Vec3 up(0.0, 0.0, 1.0);
  const int along = static_cast<int>(std::lround((y1 - y0) / step));
  for (int k = 0; k < along; ++k)
    for (int i = 0; i < across; ++i) {
      const double xa = -0.5 * kLaneWidth + kLaneWidth * i / across;
      const double xb = -0.5 * kLaneWidth + kLaneWidth * (i + 1) / across;
      const double ya = y0 + step * k, yb = y0 + step * (k + 1);
      const auto uv = [&](double x, double y) {
        return glm::dvec2((x + 0.5 * kLaneWidth) / kLaneWidth * 0.999, (y - y0) / 2.0);
      };
      const Vec3 p0(xa, ya, 0.0), p1(xb, ya, 0.0), p2(xb, yb, 0.0), p3(xa, yb, 0.0);
      b.triangle({p0, p1, p2}, {up, up, up}, {uv(xa, ya), uv(xb, ya), uv(xb, yb)}, kAlley);
      b.triangle({p0, p2, p3}, {up, up, up}, {uv(xa, ya), uv(xb, yb), uv(xa, yb)}, kAlley);
    }
}

}  // namespace

Scene make_bowling() {
  Scene scene;
  scene.name = "builtin:bowling";
  scene.has_camera = true;
  // Low behind the ball, looking down the lane into the pins (the "Textbook Strike" view).
  scene.camera.from = Vec3(0.32, -1.55, 0.42);
  scene.camera.at = Vec3(0.0, 0.42, 0.12);
  scene.camera.up = Vec3(0.0, 0.0, 1.0);
  scene.camera.angle_deg = 26.0;
  scene.camera.width = 640;  // L93
  scene.camera.height = 512;
  scene.background = Color(0.05, 0.05, 0.07);  // the dark pit beyond the pins
  // The point light that casts shadows, above and in front of the pins (L97); the ambient light
  // is the shading model's ambient term.
  scene.lights.push_back({Vec3(-0.6, -0.9, 2.4), Color(1.0)});
  scene.materials = {
      Material{Color(0.95, 0.94, 0.90), 0.8, 0.35, 40.0, 0.0, 1.0},  // pin: white maple
      Material{Color(1.0, 1.0, 1.0), 0.75, 0.22, 60.0, 0.0, 1.0},    // alley: the wood's colour
      Material{Color(0.16, 0.10, 0.52), 0.6, 0.6, 120.0, 0.0, 1.0},  // ball: deep blue
  };
  scene.surface_shading = {{"pin", true}, {"alley", true}, {"ball", true}};
  Builder b{scene};
  add_alley(b);
  // Pins 1-10 in their triangle: row r has r + 1 pins, 12 in apart, rows 10.39 in apart.
  const double row = kPinSpacing * std::sqrt(3.0) / 2.0;
  int pin = 0;
  for (int r = 0; r < 4; ++r)
    for (int k = 0; k <= r; ++k, ++pin) {
      const Vec3 base((k - 0.5 * r) * kPinSpacing, r * row, 0.0);
      // The headpin (1) leans back and to the left, struck; the 3 pin behind it starts to.
      double lean = 0.0;
      Vec3 axis(1.0, 0.0, 0.0);
      if (pin == 0) {
        lean = 0.45;
        axis = glm::normalize(Vec3(1.0, 0.35, 0.0));
      } else if (pin == 2) {
        lean = 0.18;
        axis = glm::normalize(Vec3(1.0, -0.2, 0.0));
      }
      add_pin(b, base, axis, lean);
    }
  add_ball(b, Vec3(0.09, -0.16, kBallRadius));
  return scene;
}

}  // namespace rtsim::scenes
