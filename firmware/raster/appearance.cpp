#include "firmware/raster/appearance.hpp"

#include <algorithm>
#include <cmath>

namespace rtsim::raster {

namespace {

Vec3 unit_of(const std::array<std::int16_t, 3>& c) {
  const Vec3 v(c[0], c[1], c[2]);
  const double len = glm::length(v);
  return len > 0.0 ? v / len : Vec3(0.0, 0.0, 1.0);
}

void put16(std::uint8_t* p, std::uint16_t x) {
  p[0] = static_cast<std::uint8_t>(x & 0xFFu);
  p[1] = static_cast<std::uint8_t>(x >> 8);
}
std::uint16_t get16(const std::uint8_t* p) {
  return static_cast<std::uint16_t>(p[0] | (p[1] << 8));
}

}  // namespace

Vec3 Appearance::shading_normal() const { return unit_of(normal); }
Vec3 Appearance::tangent_x() const { return unit_of(dp_dx); }

std::int16_t unit_component(double c) {
  return static_cast<std::int16_t>(std::lround(std::clamp(c, -1.0, 1.0) * 32767.0));
}

std::uint16_t texture_fraction(double t) {
  const double f = t - std::floor(t);
  return static_cast<std::uint16_t>(std::min(65535.0, std::floor(f * 65536.0)));
}

std::uint16_t footprint_word(double f) {
  if (!(f > 0.0)) return 0;
  return static_cast<std::uint16_t>(std::min(65535.0, std::round(f * 65536.0)));
}

std::uint8_t colour_byte(double c) {
  return static_cast<std::uint8_t>(std::lround(std::clamp(c, 0.0, 1.0) * 255.0));
}

AppearanceWord pack(const Appearance& a) {
  AppearanceWord w{};
  std::uint8_t* p = w.data();
  for (int i = 0; i < 4; ++i) p[i] = static_cast<std::uint8_t>((a.depth >> (8 * i)) & 0xFFu);
  p[4] = a.shader;
  p[5] = a.colour[0];
  p[6] = a.colour[1];
  p[7] = a.colour[2];
  for (int i = 0; i < 3; ++i) put16(p + 8 + 2 * i, static_cast<std::uint16_t>(a.normal[i]));
  put16(p + 14, a.u);
  put16(p + 16, a.v);
  put16(p + 18, a.footprint_u);
  put16(p + 20, a.footprint_v);
  for (int i = 0; i < 3; ++i) put16(p + 22 + 2 * i, static_cast<std::uint16_t>(a.dp_dx[i]));
  for (int i = 0; i < 3; ++i) put16(p + 28 + 2 * i, static_cast<std::uint16_t>(a.dp_dy[i]));
  return w;
}

Appearance unpack(const AppearanceWord& w) {
  Appearance a;
  const std::uint8_t* p = w.data();
  a.depth = depth_word(w);
  a.shader = p[4];
  a.colour = {p[5], p[6], p[7]};
  for (int i = 0; i < 3; ++i) a.normal[i] = static_cast<std::int16_t>(get16(p + 8 + 2 * i));
  a.u = get16(p + 14);
  a.v = get16(p + 16);
  a.footprint_u = get16(p + 18);
  a.footprint_v = get16(p + 20);
  for (int i = 0; i < 3; ++i) a.dp_dx[i] = static_cast<std::int16_t>(get16(p + 22 + 2 * i));
  for (int i = 0; i < 3; ++i) a.dp_dy[i] = static_cast<std::int16_t>(get16(p + 28 + 2 * i));
  return a;
}

AppearanceWord background_word() { return pack(Appearance{}); }

}  // namespace rtsim::raster
