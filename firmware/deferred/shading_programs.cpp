#include "firmware/deferred/shading_programs.hpp"

namespace rtsim::deferred {

namespace {

using simd::Lane;
using simd::Repr;
using simd::Stream;
using simd::Uniform;
using simd::Vec;
using Short = Lane<Repr::Short>;
using Long = Lane<Repr::Long>;
using ShortVec = Vec<Repr::Short>;
using LongVec = Vec<Repr::Long>;
constexpr Uniform U{};

/// A Fig. 8 colour (3 bytes) or a colour a part left in memory, as shorts.
ShortVec colour_in(Stream& s) { return s.in_vec<Repr::Short>(); }

/// The surface point every part reads: deferred_shader.cpp's "view.world_at(..., depth_of)".
LongVec surface_point(Stream& s) {
  const Long word = s.in<Repr::Long>();
  const Long z = word * U + U;  // depth_of: linear in the word (view_transform.cpp)
  // world_at(sx, sy, z): ex = (sx - cx) pixel z, ey likewise, p = o + r ex + u ey + f z. The
  // GP folds the uniforms: a component is z times a linear expression of the processor's own
  // screen position, plus the eye's.
  const Long sx = s.in<Repr::Long>(), sy = s.in<Repr::Long>();
  const auto component = [&] { return (sx * U + sy * U + U) * z + U; };
  return {component(), component(), component()};
}

/// A point's coordinates in another view (a light's, the mirror's): ViewTransform::to_eye, one
/// dot product with a row of the view's frame and its origin folded in.
LongVec in_view(const LongVec& p) { return {dot(p, U) + U, dot(p, U) + U, dot(p, U) + U}; }

/// ViewTransform::screen_x and screen_y: c + e / (z pixel), one reciprocal for both.
void to_screen(const LongVec& e) {
  const Long recip = U / (e.z * U);
  (void)(e.x * recip + U);
  (void)(e.y * recip + U);
}

/// MipMap::lookup's arithmetic for `channels` channels (the table read itself is the node's
/// lookup, L148). `levels` the texture's mip-map levels; `offset`: one coordinate moved a texel
/// (the bump map's neighbours) before the lookup.
void mip_lookup_arithmetic(Stream& s, int levels, int channels, bool with_level, bool offset) {
  const Short u = s.in<Repr::Short>(), v = s.in<Repr::Short>();
  if (with_level) {
    const Short fu = s.in<Repr::Short>(), fv = s.in<Repr::Short>();
    // footprint = max(fu, fv) size (size a power of two: a shift); level = round(log2): one
    // comparison a level boundary, each setting the level under the mask.
    Short footprint = select(less(fu, fv), fv, fu);
    for (int l = 1; l < levels; ++l) footprint = select(less(footprint, U), footprint, footprint);
  }
  const Short s_texels = s.in<Repr::Short>();  // size >> level, left by the level's selection
  // x = frac(u) s - 1/2 (frac: the fixed-point word's low bits).
  Short x = (offset ? u + U : u) * s_texels - U;
  const Short y = v * s_texels - U;
  // ax = x - floor(x), ay likewise (floor: the word's high bits).
  const Short ax = x - x, ay = y - y;
  const Short bx = U - ax, by = U - ay;
  for (int c = 0; c < channels; ++c) {
    const Short t00 = s.in<Repr::Short>(), t10 = s.in<Repr::Short>();
    const Short t01 = s.in<Repr::Short>(), t11 = s.in<Repr::Short>();
    // (1 - ay) ((1 - ax) t00 + ax t10) + ay ((1 - ax) t01 + ax t11)
    (void)(by * (bx * t00 + ax * t10) + ay * (bx * t01 + ax * t11));
  }
}

/// A mip-mapped texture multiplying the base colour (the label, the dirt, the wood).
void mip_mapped_colour(Stream& s, int levels) {
  mip_lookup_arithmetic(s, levels, 3, true, false);
  const ShortVec base = colour_in(s), texel = colour_in(s);
  (void)(base * texel);  // p.base *= tex.lookup(...)
}

/// Phong, post-light: ambient kd base + kd base diffuse + ks specular.
ShortVec phong(Stream& s) {
  const ShortVec base = colour_in(s), diffuse = colour_in(s), specular = colour_in(s);
  const ShortVec kd_base = base * U;
  return base * U + kd_base * diffuse + specular * U;
}

void run(ShadingPart part, Stream& s, const ProgramUniforms& u) {
  switch (part) {
    case ShadingPart::Surface: {
      const LongVec p = surface_point(s);
      // to_eye = (o - p) / |o - p|: the difference narrowed, the direction in shorts.
      (void)normalize(simd::narrow(U - p));
      return;
    }
    case ShadingPart::Crown: {
      // in_crown(v): two bands, four comparisons; the crown's red stored under the mask.
      const Short v = s.in<Repr::Short>();
      for (int k = 0; k < 4; ++k) (void)less(v, U);
      return;
    }
    case ShadingPart::Label:
    case ShadingPart::Dirt:
    case ShadingPart::Wood:
      mip_mapped_colour(s, u.texture_levels);
      return;
    case ShadingPart::Scuffs: {
      // bumped(): the height and its two neighbours (one footprint, one level).
      mip_lookup_arithmetic(s, u.texture_levels, 1, true, false);
      mip_lookup_arithmetic(s, u.texture_levels, 1, false, true);
      mip_lookup_arithmetic(s, u.texture_levels, 1, false, true);
      const Short h = s.in<Repr::Short>(), hu = s.in<Repr::Short>(), hv = s.in<Repr::Short>();
      const Short gu = (hu - h) * U, gv = (hv - h) * U;  // / step: the reciprocal is uniform
      const ShortVec n = s.in_vec<Repr::Short>();
      ShortVec t = s.in_vec<Repr::Short>();  // tangent_x, from dP/dx (Fig. 8)
      t = t - n * dot(n, t);
      const Short len = length(t);
      (void)less(len, U);  // degenerate: the normal kept (under the mask)
      t = t * (U / len);
      const ShortVec b = cross(n, t);
      const ShortVec moved = n - (t * gu + b * gv) * U;
      (void)less(length(moved), U);
      (void)normalize(moved);
      return;
    }
    case ShadingPart::PinPhong:
    case ShadingPart::BallPhong:
    case ShadingPart::Phong:
      (void)phong(s);
      return;
    case ShadingPart::Reflection: {
      const ShortVec c = phong(s);
      // c += ks reflection->lookup(p): the point in the mirrored view, its texel (clamped).
      const LongVec e = in_view(s.in_vec<Repr::Long>());
      (void)less(e.z, U);  // behind the mirror's eye: texel 0
      to_screen(e);
      for (int k = 0; k < 4; ++k) (void)less(e.x, U);  // clamped to the map
      (void)(c + colour_in(s) * U);
      return;
    }
    case ShadingPart::Light: {
      const LongVec p = s.in_vec<Repr::Long>();
      const ShortVec n = s.in_vec<Repr::Short>(), to_eye = s.in_vec<Repr::Short>();
      // ldir = (L - p) / |L - p|, narrowed after the subtraction; cos_i = n.ldir, facing.
      const ShortVec ldir = normalize(simd::narrow(U - p));
      const Short cos_i = dot(n, ldir);
      (void)less(cos_i, U);
      // DepthMap::lit: the point in the light's view, in front of it, inside the map ...
      const LongVec e = in_view(p);
      (void)less(e.z, U);
      to_screen(e);
      for (int k = 0; k < 4; ++k) (void)less(e.x, U);
      const Long word = s.in<Repr::Long>();  // the map's depth word (the lookup)
      (void)less(word, U);                   // background: lit
      // ... and the bias: c = clamp(|n.l|, 1/8, 1) (n.l is cos_i: the map's eye is the light),
      // slope = sqrt(1 - c^2) / c, e.z - bias texel (1 + slope) <= depth_of(word).
      Short c = select(less(cos_i, U), cos_i, cos_i);
      c = select(less(c, U), c, c);
      const Short slope = sqrt(U - c * c) / c;
      const Long texel = e.z * U;  // e.z pixel
      const Long biased = e.z - texel * U * simd::widen(slope + U);
      (void)less(biased, word * U + U);
      // diffuse += cos_i light (where facing and lit).
      ShortVec diffuse = s.in_vec<Repr::Short>();
      diffuse = diffuse + ShortVec{cos_i * U, cos_i * U, cos_i * U};
      // specular += (r.v)^shine light, r = -l + 2 cos_i n.
      const ShortVec r = n * (cos_i * U) - ldir;
      const Short cos_s = dot(r, to_eye);
      (void)less(cos_s, U);
      const Short highlight = simd::pow(cos_s, u.max_shine);
      ShortVec specular = s.in_vec<Repr::Short>();
      specular = specular + ShortVec{highlight * U, highlight * U, highlight * U};
      return;
    }
  }
}

}  // namespace

ShadingPrograms shading_programs(const ProgramUniforms& uniforms) {
  ShadingPrograms out;
  for (int k = 0; k < kShadingParts; ++k) {
    Stream s;
    run(static_cast<ShadingPart>(k), s, uniforms);
    out.parts[static_cast<std::size_t>(k)] = s.mix();
  }
  return out;
}

std::array<bool, kShadingParts> parts_of(ShadingFunction f) {
  std::array<bool, kShadingParts> on{};
  const auto use = [&](ShadingPart p) { on[static_cast<std::size_t>(p)] = true; };
  switch (f) {
    case ShadingFunction::Pin:
      for (const ShadingPart p : {ShadingPart::Crown, ShadingPart::Label, ShadingPart::Scuffs,
                                  ShadingPart::Dirt, ShadingPart::PinPhong})
        use(p);
      break;
    case ShadingFunction::Alley:
      use(ShadingPart::Wood);
      use(ShadingPart::Reflection);
      break;
    case ShadingFunction::Ball:
      use(ShadingPart::BallPhong);
      break;
    case ShadingFunction::Phong:
      use(ShadingPart::Phong);
      break;
  }
  return on;
}

simd::InstructionMix region_instructions(const ShadingPrograms& programs, const RegionWork& work) {
  simd::InstructionMix mix;
  if (work.lit_pixels == 0) return mix;  // background only: nothing to shade
  mix += programs.of(ShadingPart::Surface);
  for (int f = 0; f < kShadingFunctions; ++f) {
    const auto function = static_cast<ShadingFunction>(f);
    if (!work.has(function)) continue;
    const auto on = parts_of(function);
    for (int p = 0; p < kShadingParts; ++p)
      if (on[static_cast<std::size_t>(p)]) mix += programs.parts[static_cast<std::size_t>(p)];
  }
  for (std::uint32_t l = 0; l < work.lights; ++l) mix += programs.of(ShadingPart::Light);
  return mix;
}

}  // namespace rtsim::deferred
