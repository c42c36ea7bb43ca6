#include "firmware/deferred/bowling_textures.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

namespace rtsim::deferred {

namespace {

constexpr int kSize = kBowlingTextureSize;

/// A hash of integer lattice points to [0, 1) (a 32-bit integer mix: the same on every machine).
double hash01(int x, int y, std::uint32_t seed) {
  std::uint32_t h = static_cast<std::uint32_t>(x) * 0x8da6b343u ^
                    static_cast<std::uint32_t>(y) * 0xd8163841u ^ seed * 0xcb1ab31fu;
  h ^= h >> 13;
  h *= 0x5bd1e995u;
  h ^= h >> 15;
  return (h & 0xFFFFFFu) / 16777216.0;
}

/// Smooth value noise with period `period` lattice cells (so the texture repeats seamlessly).
double noise(double x, double y, int period, std::uint32_t seed) {
  const int x0 = static_cast<int>(std::floor(x)), y0 = static_cast<int>(std::floor(y));
  const double fx = x - x0, fy = y - y0;
  const double sx = fx * fx * (3.0 - 2.0 * fx), sy = fy * fy * (3.0 - 2.0 * fy);
  const auto at = [&](int i, int j) {
    return hash01(((i % period) + period) % period, ((j % period) + period) % period, seed);
  };
  const double a = at(x0, y0), b = at(x0 + 1, y0), c = at(x0, y0 + 1), d = at(x0 + 1, y0 + 1);
  return (1 - sy) * ((1 - sx) * a + sx * b) + sy * ((1 - sx) * c + sx * d);
}

/// Three octaves of noise over the texture, repeating.
double fractal(double u, double v, int cells, std::uint32_t seed) {
  double sum = 0.0, amp = 0.5;
  for (int o = 0; o < 3; ++o) {
    const int p = cells << o;
    sum += amp * noise(u * p, v * p, p, seed + static_cast<std::uint32_t>(o));
    amp *= 0.5;
  }
  return sum / 0.875;
}

template <class Texel>
raster::MipMap make(Texel texel) {
  std::vector<std::uint8_t> rgb(static_cast<std::size_t>(3 * kSize * kSize));
  for (int y = 0; y < kSize; ++y)
    for (int x = 0; x < kSize; ++x) {
      const Color c = texel((x + 0.5) / kSize, (y + 0.5) / kSize);
      for (int k = 0; k < 3; ++k)
        rgb[static_cast<std::size_t>(3 * (y * kSize + x) + k)] = raster::colour_byte(c[k]);
    }
  return raster::MipMap(kSize, std::move(rgb));
}

}  // namespace

BowlingTextures make_bowling_textures() {
  BowlingTextures t;
  // The label: on the pin's belly (v 0.36-0.50), on the side facing -y (u 0.625-0.875), a
  // red oval with a white ring and a dark bar across it; white (no change) elsewhere.
  t.label = make([](double u, double v) {
    const double du = (u - 0.75) / 0.125, dv = (v - 0.43) / 0.07;
    const double r = std::sqrt(du * du + dv * dv);
    if (r > 1.0) return Color(1.0);
    if (r > 0.82) return Color(0.95, 0.95, 0.92);
    if (std::fabs(dv) < 0.18) return Color(0.12, 0.10, 0.10);
    return Color(0.78, 0.08, 0.10);
  });
  // Dirt: smudges of noise, heavier towards the base (v = 0).
  t.dirt = make([](double u, double v) {
    const double n = fractal(u, v, 8, 11u);
    const double weight = 0.25 + 0.75 * std::exp(-v * 6.0);
    const double d = std::clamp(1.0 - weight * std::max(0.0, n - 0.35) * 0.9, 0.55, 1.0);
    return Color(d, d * 0.97, d * 0.92);
  });
  // Scuffs: thin scratches where a stretched noise crosses a level set; height in red.
  t.scuffs = make([](double u, double v) {
    const double n = noise(u * 48.0, v * 6.0, 48, 23u);
    const double line = std::exp(-std::pow((n - 0.5) * 40.0, 2.0));
    const double keep = fractal(u, v, 4, 29u) > 0.55 ? 1.0 : 0.0;
    const double h = 1.0 - 0.8 * line * keep;
    return Color(h, h, h);
  });
  // Wood: 16 maple boards across (u), grain along the alley (v), each board its own shade.
  t.wood = make([](double u, double v) {
    const int board = static_cast<int>(u * 16.0);
    const double shade = 0.85 + 0.15 * hash01(board, 0, 37u);
    const double grain = noise(u * 256.0, v * 8.0, 256, 41u + static_cast<std::uint32_t>(board));
    const double g = 0.88 + 0.12 * grain;
    const double seam = std::fmod(u * 16.0, 1.0) < 0.04 ? 0.7 : 1.0;
    return Color(0.86, 0.66, 0.42) * (shade * g * seam);
  });
  return t;
}

}  // namespace rtsim::deferred
