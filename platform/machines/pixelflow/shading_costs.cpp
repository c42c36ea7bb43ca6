#include "platform/machines/pixelflow/shading_costs.hpp"

#include <array>
#include <string>

#include "firmware/raster/region_grid.hpp"

namespace rtsim::platform::pixelflow {

namespace {

namespace simd = deferred::simd;

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

const modules::ChoiceParam kModel(
    {.name = "cost.model",
     .default_value = "parts",
     .allowed = {"parts", "instructions"},
     .description = "parts: each shading part at Fig. 9's measured time (cost.*); instructions: "
                    "the SIMD instructions the shading programs issue for it, at Fig. 6's times "
                    "(simd.*). Lookups cost cost.lookup either way",
     .source = "seed 004 Fig. 9 (L134-L146) and Fig. 6 (L5-L13)"});

/// Fig. 6 (L5-L11): one SIMD instruction, every pixel processor at once (L3).
struct Fig6Entry {
  simd::Arith op;
  simd::Repr repr;
  modules::TimeParam param;
};

modules::TimeParam fig6(const char* name, const char* value, const char* what, const char* line) {
  return modules::TimeParam({.name = name,
                             .default_value = value,
                             .description = what,
                             .source = std::string("seed 004 Fig. 6, ") + line});
}

const std::array<Fig6Entry, simd::kAriths* simd::kReprs> kFig6 = {{
    {simd::Arith::Add, simd::Repr::Short, fig6("simd.add_short", "0.07 us", "2-byte add", "L7")},
    {simd::Arith::Add, simd::Repr::Long, fig6("simd.add_long", "0.13 us", "4-byte add", "L7")},
    {simd::Arith::Add, simd::Repr::Float,
     fig6("simd.add_float", "3.94 us",
          "4-byte float add (slower than the float multiply as printed; note 004)", "L7")},
    {simd::Arith::Mul, simd::Repr::Short,
     fig6("simd.mul_short", "0.50 us", "2-byte multiply", "L8")},
    {simd::Arith::Mul, simd::Repr::Long, fig6("simd.mul_long", "2.00 us", "4-byte multiply", "L8")},
    {simd::Arith::Mul, simd::Repr::Float,
     fig6("simd.mul_float", "2.53 us", "4-byte float multiply", "L8")},
    {simd::Arith::Div, simd::Repr::Short, fig6("simd.div_short", "1.60 us", "2-byte divide", "L9")},
    {simd::Arith::Div, simd::Repr::Long, fig6("simd.div_long", "6.40 us", "4-byte divide", "L9")},
    {simd::Arith::Div, simd::Repr::Float,
     fig6("simd.div_float", "7.04 us", "4-byte float divide", "L9")},
    {simd::Arith::Sqrt, simd::Repr::Short,
     fig6("simd.sqrt_short", "1.22 us", "2-byte square root", "L10")},
    {simd::Arith::Sqrt, simd::Repr::Long,
     fig6("simd.sqrt_long", "3.33 us", "4-byte square root", "L10")},
    {simd::Arith::Sqrt, simd::Repr::Float,
     fig6("simd.sqrt_float", "6.98 us", "4-byte float square root", "L10")},
}};
const modules::TimeParam kFloatToLong =
    fig6("simd.float_to_long", "1.35 us", "float to 4-byte integer conversion", "L13");
const modules::TimeParam kLongToFloat =
    fig6("simd.long_to_float", "1.57 us", "4-byte integer to float conversion", "L13");

}  // namespace

void ShadingCosts::declare_params(const modules::ParamDecls& d) {
  for (const auto* p : {&kCrown, &kLabel, &kScuffs, &kDirt, &kPinPhong, &kWood, &kReflection,
                        &kBallPhong, &kPhong, &kLight, &kLookup})
    d.add(*p);
  d.add(kModel);
  for (const Fig6Entry& e : kFig6) d.add(e.param);
  d.add(kFloatToLong);
  d.add(kLongToFloat);
}

ShadingCosts::ShadingCosts(const modules::ModuleParams& p,
                           const deferred::ProgramUniforms& uniforms)
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
      lookup_(p.get(kLookup)),
      instructions_(p.get(kModel) == "instructions"),
      programs_(deferred::shading_programs(uniforms)) {
  for (const Fig6Entry& e : kFig6) times_.at(e.op, e.repr) = p.get(e.param).to_seconds();
  times_.float_to_long = p.get(kFloatToLong).to_seconds();
  times_.long_to_float = p.get(kLongToFloat).to_seconds();
}

sc_core::sc_time ShadingCosts::shading_part(const deferred::RegionWork& w) const {
  if (!instructions_) return fig9_part(w);
  return sc_core::sc_time(times_.time_of(deferred::region_instructions(programs_, w)),
                          sc_core::SC_SEC);
}

sc_core::sc_time ShadingCosts::fig9_part(const deferred::RegionWork& w) const {
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

}  // namespace rtsim::platform::pixelflow
