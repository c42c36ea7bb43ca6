#include "firmware/raster/region_samples.hpp"

#include <algorithm>
#include <cmath>

#include "firmware/tasks/vision_ray_task.hpp"

namespace rtsim::raster {

RegionSampleGrid RegionSampleGrid::of(const RegionGrid& grid, int region, int sample) {
  RegionSampleGrid g;
  g.region = region;
  g.sample = sample;
  g.x0 = grid.x0(region);
  g.y0 = grid.y0(region);
  g.width = grid.pixel_width(region);
  g.height = grid.pixel_height(region);
  double dx = 0.5, dy = 0.5;
  tasks::sample_offset(sample, dx, dy);
  g.offset_x = std::clamp(static_cast<int>(std::lround(dx * kSubpixel)), 0, kSubpixel - 1);
  g.offset_y = std::clamp(static_cast<int>(std::lround(dy * kSubpixel)), 0, kSubpixel - 1);
  return g;
}

namespace {

/// The triangle's three edge functions over the subpixel grid, oriented positive inside.
struct Edges {
  std::array<std::int64_t, 3> a{}, b{}, c{};  ///< E_i(X, Y) = a_i X + b_i Y + c_i
  std::array<bool, 3> owns{};                 ///< a sample exactly on edge i is inside
  std::int64_t area2 = 0;                     ///< twice the area, > 0

  explicit Edges(const ScreenTriangle& t) {
    for (int i = 0; i < 3; ++i) {
      const int j = (i + 1) % 3, k = (i + 2) % 3;
      const std::int64_t dx = t.x[k] - t.x[j], dy = t.y[k] - t.y[j];
      // E_i = dx (Y - y_j) - dy (X - x_j): zero on the edge j -> k, the weight of vertex i.
      a[i] = -dy;
      b[i] = dx;
      c[i] = dy * t.x[j] - dx * t.y[j];
    }
    area2 = a[0] * t.x[0] + b[0] * t.y[0] + c[0];
    const std::int64_t sign = area2 < 0 ? -1 : 1;
    area2 *= sign;
    for (int i = 0; i < 3; ++i) {
      a[i] *= sign;
      b[i] *= sign;
      c[i] *= sign;
      // The edge's direction with the inside on its left is (b_i, -a_i); of an edge shared by
      // two triangles exactly one owns it.
      const std::int64_t ex = b[i], ey = -a[i];
      owns[i] = ey > 0 || (ey == 0 && ex > 0);
    }
  }
  bool inside(std::int64_t X, std::int64_t Y, std::array<std::int64_t, 3>& e) const {
    for (int i = 0; i < 3; ++i) {
      e[i] = a[i] * X + b[i] * Y + c[i];
      if (e[i] < 0 || (e[i] == 0 && !owns[i])) return false;
    }
    return true;
  }
};

/// Perspective-correct interpolation at a sample with edge values e: the weights and 1/z, and
/// their derivatives along the screen's x and y (per pixel).
struct Weights {
  std::array<double, 3> w{};  ///< perspective-correct barycentric weights
  double z = 0.0;
  std::array<double, 3> wx{}, wy{};  ///< dw/dx, dw/dy
};

Weights weigh(const ScreenTriangle& t, const Edges& ed, const std::array<std::int64_t, 3>& e,
              bool derivatives) {
  Weights out;
  const double inv_area = 1.0 / static_cast<double>(ed.area2);
  std::array<double, 3> bq{};
  double q = 0.0;
  for (int i = 0; i < 3; ++i) {
    bq[i] = static_cast<double>(e[i]) * inv_area * t.inv_z[i];
    q += bq[i];
  }
  out.z = 1.0 / q;
  for (int i = 0; i < 3; ++i) out.w[i] = bq[i] * out.z;
  if (derivatives) {
    // w_i = bq_i / q; d(bq_i) = d(E_i) q_i / area; dw_i = (d bq_i - w_i d q) / q.
    std::array<double, 3> bx{}, by{};
    double qx = 0.0, qy = 0.0;
    for (int i = 0; i < 3; ++i) {
      bx[i] = static_cast<double>(ed.a[i]) * kSubpixel * inv_area * t.inv_z[i];
      by[i] = static_cast<double>(ed.b[i]) * kSubpixel * inv_area * t.inv_z[i];
      qx += bx[i];
      qy += by[i];
    }
    for (int i = 0; i < 3; ++i) {
      out.wx[i] = (bx[i] - out.w[i] * qx) * out.z;
      out.wy[i] = (by[i] - out.w[i] * qy) * out.z;
    }
  }
  return out;
}

/// The record of the triangle at a sample.
Appearance record(const ScreenTriangle& t, const Weights& w, std::uint32_t depth) {
  Appearance a;
  a.depth = depth;
  a.shader = t.material.shader;
  a.colour = t.material.colour;
  Vec3 n(0.0), px(0.0), py(0.0);
  glm::dvec2 uv(0.0), ux(0.0), uy(0.0);
  for (int i = 0; i < 3; ++i) {
    n += w.w[i] * t.attr[i].normal;
    uv += w.w[i] * t.attr[i].uv;
    px += w.wx[i] * t.attr[i].position;
    py += w.wy[i] * t.attr[i].position;
    ux += w.wx[i] * t.attr[i].uv;
    uy += w.wy[i] * t.attr[i].uv;
  }
  const double len = glm::length(n);
  n = len > 0.0 ? n / len : Vec3(0.0, 0.0, 1.0);
  if (t.flip) n = -n;
  const auto unit_words = [](const Vec3& v) {
    const double l = glm::length(v);
    const Vec3 u = l > 0.0 && std::isfinite(l) ? v / l : Vec3(0.0);
    return std::array<std::int16_t, 3>{unit_component(u.x), unit_component(u.y),
                                       unit_component(u.z)};
  };
  a.normal = unit_words(n);
  a.u = texture_fraction(uv.x);
  a.v = texture_fraction(uv.y);
  a.footprint_u = footprint_word(std::max(std::fabs(ux.x), std::fabs(uy.x)));
  a.footprint_v = footprint_word(std::max(std::fabs(ux.y), std::fabs(uy.y)));
  a.dp_dx = unit_words(px);
  a.dp_dy = unit_words(py);
  return a;
}

/// Calls visit(x, y, e) for every sample of the region-sample inside `t` (x, y relative to the
/// region).
template <class Visit>
void for_each_sample(const ScreenTriangle& t, const Edges& ed, const RegionSampleGrid& g,
                     Visit visit) {
  const int x_lo = std::max(t.x_min, g.x0), x_hi = std::min(t.x_max, g.x0 + g.width - 1);
  const int y_lo = std::max(t.y_min, g.y0), y_hi = std::min(t.y_max, g.y0 + g.height - 1);
  std::array<std::int64_t, 3> e{};
  for (int py = y_lo; py <= y_hi; ++py) {
    const std::int64_t Y = static_cast<std::int64_t>(py) * kSubpixel + g.offset_y;
    for (int px = x_lo; px <= x_hi; ++px) {
      const std::int64_t X = static_cast<std::int64_t>(px) * kSubpixel + g.offset_x;
      if (ed.inside(X, Y, e)) visit(px - g.x0, py - g.y0, e);
    }
  }
}

}  // namespace

ScanCount scan_convert(const ScreenTriangle& t, const ViewTransform& view, RegionSamples& into) {
  ScanCount count;
  const Edges ed(t);
  if (ed.area2 == 0) return count;
  for_each_sample(t, ed, into.at, [&](int x, int y, const std::array<std::int64_t, 3>& e) {
    ++count.covered;
    const Weights depth_only = weigh(t, ed, e, false);
    const std::uint32_t depth = view.depth_word(depth_only.z);
    AppearanceWord& held = into.word(x, y);
    if (depth > depth_word(held)) return;
    const AppearanceWord word = pack(record(t, weigh(t, ed, e, true), depth));
    if (nearer(word, held)) {
      held = word;
      ++count.written;
    }
  });
  return count;
}

ScanCount scan_depth(const ScreenTriangle& t, const ViewTransform& view, RegionDepths& into) {
  ScanCount count;
  const Edges ed(t);
  if (ed.area2 == 0) return count;
  for_each_sample(t, ed, into.at, [&](int x, int y, const std::array<std::int64_t, 3>& e) {
    ++count.covered;
    const std::uint32_t depth = view.depth_word(weigh(t, ed, e, false).z);
    std::uint32_t& held = into.depth[static_cast<std::size_t>(y * kRegionWidth + x)];
    if (depth < held) {
      held = depth;
      ++count.written;
    }
  });
  return count;
}

std::size_t z_composite(RegionSamples& into, const RegionSamples& from) {
  std::size_t won = 0;
  for (std::size_t i = 0; i < into.words.size(); ++i)
    if (nearer(from.words[i], into.words[i])) {
      into.words[i] = from.words[i];
      ++won;
    }
  return won;
}

std::size_t z_composite(RegionDepths& into, const RegionDepths& from) {
  std::size_t won = 0;
  for (std::size_t i = 0; i < into.depth.size(); ++i)
    if (from.depth[i] < into.depth[i]) {
      into.depth[i] = from.depth[i];
      ++won;
    }
  return won;
}

}  // namespace rtsim::raster
