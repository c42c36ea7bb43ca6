#include "platform/machines/pixelflow/shading_costs.hpp"

#include "firmware/raster/region_grid.hpp"

namespace rtsim::platform::pixelflow {

namespace {

modules::TimeParam fig9(const char* name, const char* value, const char* what, const char* source) {
  return modules::TimeParam(
      {.name = name, .default_value = value, .description = what, .source = source});
}

// Fig. 9 (L134-L146), one node, one sample, one region, lookups excluded.
const modules::TimeParam kCrown =
    fig9("cost.crown", "2 us", "the pin's procedural crown (pre-light)", "seed 004 Fig. 9, L138");
const modules::TimeParam kLabel = fig9(
    "cost.label", "15 us", "the pin's mip-mapped label, the lookup's set-up and use (pre-light)",
    "seed 004 Fig. 9, L139");
const modules::TimeParam kScuffs = fig9(
    "cost.scuffs", "24 us", "the pin's bump-mapped scuffs (pre-light)", "seed 004 Fig. 9, L140");
const modules::TimeParam kDirt =
    fig9("cost.dirt", "15 us", "the pin's mip-mapped dirt (pre-light)", "seed 004 Fig. 9, L141");
const modules::TimeParam kPinPhong =
    fig9("cost.pin_phong", "12 us", "the pin's Phong shader (post-light)", "seed 004 Fig. 9, L144");
const modules::TimeParam kWood =
    fig9("cost.wood", "15 us", "the alley's mip-mapped wood (pre-light)", "seed 004 Fig. 9, L142");
const modules::TimeParam kReflection =
    fig9("cost.reflection", "27 us",
         "the alley's reflection and Phong (post-light; Fig. 9 lists no separate Phong for it)",
         "seed 004 Fig. 9, L145 (note 004: the alley's Phong is folded in)");
const modules::TimeParam kBallPhong = fig9(
    "cost.ball_phong", "12 us", "the ball's Phong shader (post-light)", "seed 004 Fig. 9, L146");
const modules::TimeParam kPhong = fig9(
    "cost.phong", "12 us", "the plain Phong shading function of scenes that name none (post-light)",
    "assumption: the ball's Phong shader, Fig. 9 L146 (a ball is plain Phong)");
const modules::TimeParam kLight =
    fig9("cost.light", "28 us",
         "the common light loop, once a light for every pixel of every function (shadowing, L143)",
         "seed 004 Fig. 9, L143");
const modules::TimeParam kLookup =
    fig9("cost.lookup", "190 us",
         "one table lookup for all 8K pixels; a region pays this times the share of its pixels "
         "that need the data",
         "seed 004 L148");

}  // namespace

void ShadingCosts::declare_params(const modules::ParamDecls& d) {
  for (const auto* p : {&kCrown, &kLabel, &kScuffs, &kDirt, &kPinPhong, &kWood, &kReflection,
                        &kBallPhong, &kPhong, &kLight, &kLookup})
    d.add(*p);
}

ShadingCosts::ShadingCosts(const modules::ModuleParams& p)
    : crown_(p.get(kCrown)),
      label_(p.get(kLabel)),
      scuffs_(p.get(kScuffs)),
      dirt_(p.get(kDirt)),
      pin_phong_(p.get(kPinPhong)),
      wood_(p.get(kWood)),
      reflection_(p.get(kReflection)),
      ball_phong_(p.get(kBallPhong)),
      phong_(p.get(kPhong)),
      light_(p.get(kLight)),
      lookup_(p.get(kLookup)) {}

sc_core::sc_time ShadingCosts::shading_part(const deferred::RegionWork& w) const {
  using deferred::ShadingFunction;
  sc_core::sc_time t = sc_core::SC_ZERO_TIME;
  // Fig. 7: each function present runs its parts once for all its pixels.
  if (w.has(ShadingFunction::Pin)) t += crown_ + label_ + scuffs_ + dirt_ + pin_phong_;
  if (w.has(ShadingFunction::Alley)) t += wood_ + reflection_;
  if (w.has(ShadingFunction::Ball)) t += ball_phong_;
  if (w.has(ShadingFunction::Phong)) t += phong_;
  // The light loop runs once a light for all the pixels that need it.
  if (w.lit_pixels > 0) t += light_ * static_cast<double>(w.lights);
  return t;
}

sc_core::sc_time ShadingCosts::lookup_part(const deferred::RegionWork& w) const {
  std::uint64_t pixels = 0;
  for (const std::uint32_t n : w.lookups) pixels += n;
  // L148: proportional to the pixels that need data, 190 us for all 8K.
  return lookup_ * (static_cast<double>(pixels) / raster::kRegionPixels);
}

sc_core::sc_time ShadingCosts::time_for(const deferred::RegionWork& w) const {
  return shading_part(w) + lookup_part(w);
}

}  // namespace rtsim::platform::pixelflow
