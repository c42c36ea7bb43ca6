#include "firmware/deferred/deferred_shader.hpp"

#include <algorithm>
#include <cmath>

#include "firmware/shading/whitted_shader.hpp"

namespace rtsim::deferred {

namespace {

/// A pixel between the parts of Fig. 7: what pre-light leaves for the light loop and post-light.
struct PixelState {
  std::uint8_t material = 0;
  Vec3 position{0.0};
  Vec3 normal{0.0};
  Vec3 to_eye{0.0};
  Color base{0.0};
  Color diffuse{0.0};   ///< sum over the lights of their colour times n.l, where lit
  Color specular{0.0};  ///< sum over the lights of their colour times (r.v)^shine, where lit
};

/// The pin's procedural crown (Fig. 9's "procedural crown"): two red stripes round its neck.
bool in_crown(double v) { return (v > 0.665 && v < 0.69) || (v > 0.715 && v < 0.74); }

/// The scuffs' bump map: the normal tilted along the surface by the height field's slope, in a
/// tangent frame from dP/dx and the normal.
Vec3 bumped(const raster::Appearance& a, const Vec3& n, const raster::MipMap& scuffs,
            double scale) {
  const double u = a.tex_u(), v = a.tex_v();
  const double fu = a.footprint_u / 65536.0, fv = a.footprint_v / 65536.0;
  const double step = 1.0 / scuffs.size();
  const double h = scuffs.lookup(u, v, fu, fv).r;
  const double gu = (scuffs.lookup(u + step, v, fu, fv).r - h) / step;
  const double gv = (scuffs.lookup(u, v + step, fu, fv).r - h) / step;
  Vec3 t = a.tangent_x();
  t -= n * glm::dot(n, t);
  const double len = glm::length(t);
  if (!(len > 1e-9)) return n;
  t /= len;
  const Vec3 b = glm::cross(n, t);
  const Vec3 moved = n - scale * (gu * t + gv * b);
  const double m = glm::length(moved);
  return m > 1e-9 ? moved / m : n;
}

}  // namespace

RegionWork shade_region(const raster::RegionSamples& in, const raster::ViewTransform& view,
                        const ShadingSetup& setup, const ShadingTables& tables,
                        std::vector<Color>& colours) {
  RegionWork work;
  const auto& g = in.at;
  colours.assign(in.words.size(), setup.background);
  // The covered pixels' states, in row order (a region partly covered, or a small tile of a
  // larger buffer, costs what it covers).
  std::vector<PixelState> px;
  std::vector<std::size_t> at;
  const auto uniforms = [&](std::uint8_t shader) -> const MaterialUniforms& {
    static const MaterialUniforms kDefault{};
    return shader >= 1 && shader <= setup.materials.size() ? setup.materials[shader - 1u]
                                                           : kDefault;
  };
  const auto count_lookup = [&](Lookup l) { ++work.lookups[static_cast<std::size_t>(l)]; };

  // Pre-light, every function's pixels: the surface point from the depth word, the base colour
  // and the shading normal.
  for (int y = 0; y < g.height; ++y)
    for (int x = 0; x < g.width; ++x) {
      const std::size_t i = static_cast<std::size_t>(y * raster::kRegionWidth + x);
      const raster::Appearance a = raster::unpack(in.words[i]);
      if (!a.covered() || a.depth == raster::kBackgroundDepth) continue;
      at.push_back(i);
      PixelState& p = px.emplace_back();
      ++work.lit_pixels;
      p.material = a.shader;
      p.position = view.world_at(g.screen_x(x), g.screen_y(y), view.depth_of(a.depth));
      const Vec3 eye = view.origin - p.position;
      const double d = glm::length(eye);
      p.to_eye = d > 0.0 ? eye / d : -view.forward;
      p.normal = a.shading_normal();
      p.base = a.intrinsic_colour();
      const MaterialUniforms& m = uniforms(a.shader);
      ++work.pixels[static_cast<std::size_t>(m.function)];
      const double fu = a.footprint_u / 65536.0, fv = a.footprint_v / 65536.0;
      const BowlingTextures* tex = tables.textures;
      if (m.function == ShadingFunction::Pin && tex) {
        if (in_crown(a.tex_v())) p.base = Color(0.78, 0.06, 0.06);
        p.base *= tex->label.lookup(a.tex_u(), a.tex_v(), fu, fv);
        count_lookup(Lookup::Label);
        p.normal = bumped(a, p.normal, tex->scuffs, setup.bump_scale);
        count_lookup(Lookup::Scuffs);
        p.base *= tex->dirt.lookup(a.tex_u(), a.tex_v(), fu, fv);
        count_lookup(Lookup::Dirt);
      } else if (m.function == ShadingFunction::Alley && tex) {
        p.base *= tex->wood.lookup(a.tex_u(), a.tex_v(), fu, fv);
        count_lookup(Lookup::Wood);
      }
    }

  // The common light loop, once for all pixels of every function (Fig. 7).
  const double intensity = shading::effective_light_intensity(setup.shade, setup.lights.size());
  work.lights = static_cast<std::uint32_t>(setup.lights.size());
  for (std::size_t l = 0; l < setup.lights.size(); ++l) {
    const raster::DepthMap* map = l < tables.shadow.size() ? tables.shadow[l] : nullptr;
    const Color light = intensity * setup.lights[l].color;
    for (PixelState& p : px) {
      if (map) count_lookup(Lookup::Shadow);
      const Vec3 to_light = setup.lights[l].position - p.position;
      const double dist = glm::length(to_light);
      if (!(dist > 0.0)) continue;
      const Vec3 ldir = to_light / dist;
      const double cos_i = glm::dot(p.normal, ldir);
      if (cos_i <= 0.0) continue;
      if (map && !map->lit(p.position, p.normal, setup.shadow_bias_texels)) continue;
      p.diffuse += cos_i * light;
      const MaterialUniforms& m = uniforms(p.material);
      if (m.ks > 0.0 && m.shine > 0.0) {
        const double cos_s = glm::dot(-ldir + 2.0 * cos_i * p.normal, p.to_eye);
        if (cos_s > 0.0) p.specular += std::pow(cos_s, m.shine) * light;
      }
    }
  }

  // Post-light, every function's pixels: Phong (R I_a + k_d n.l + k_s (r.v)^n, seed 000 L414-
  // L448 as the ray tracers shade), the alley adding its reflection map weighted by k_s.
  for (std::size_t k = 0; k < px.size(); ++k) {
    const PixelState& p = px[k];
    const std::size_t i = at[k];
    const MaterialUniforms& m = uniforms(p.material);
    Color c = setup.shade.ambient * m.kd * p.base + m.kd * p.base * p.diffuse + m.ks * p.specular;
    if (m.function == ShadingFunction::Alley && tables.reflection) {
      c += m.ks * tables.reflection->lookup(p.position);
      count_lookup(Lookup::Reflection);
    }
    for (int k = 0; k < 3; ++k)
      if (!std::isfinite(c[k])) c[k] = 0.0;
    colours[i] = c;
  }
  return work;
}

}  // namespace rtsim::deferred
