// PixelFlow's SIMD instruction stream and shading programs (firmware/deferred/simd_stream.*,
// shading_programs.*): an operation on lanes issues one instruction of its width, uniforms are
// free, a region's instructions follow the functions it holds (Fig. 7), and Fig. 6's times price
// them. The parts' totals against Fig. 9 are validation row PF8a.
#include <gtest/gtest.h>

#include "firmware/deferred/shading_programs.hpp"
#include "firmware/deferred/simd_stream.hpp"

namespace {

using namespace rtsim::deferred;
using simd::Arith;
using simd::Repr;

TEST(SimdStream, AnOperationOnLanesIsOneInstructionOfItsWidth) {
  simd::Stream s;
  const auto a = s.in<Repr::Short>(), b = s.in<Repr::Short>();
  (void)(a * b + a);
  const auto p = s.in<Repr::Long>();
  (void)(p * simd::Uniform{} - p);
  (void)simd::to_float(p);
  const auto& m = s.mix();
  EXPECT_EQ(m.at(Arith::Mul, Repr::Short), 1u);
  EXPECT_EQ(m.at(Arith::Add, Repr::Short), 1u);
  EXPECT_EQ(m.at(Arith::Mul, Repr::Long), 1u);
  EXPECT_EQ(m.at(Arith::Add, Repr::Long), 1u);
  EXPECT_EQ(m.long_to_float, 1u);
  EXPECT_EQ(m.total(), 5u);
}

TEST(SimdStream, VectorHelpersIssueWhatTheyComputeAndPowSquares) {
  simd::Stream s;
  (void)normalize(s.in_vec<Repr::Short>());
  // |v| = sqrt(x x + y y + z z), one reciprocal, three products.
  EXPECT_EQ(s.mix().at(Arith::Mul, Repr::Short), 6u);
  EXPECT_EQ(s.mix().at(Arith::Add, Repr::Short), 2u);
  EXPECT_EQ(s.mix().at(Arith::Sqrt, Repr::Short), 1u);
  EXPECT_EQ(s.mix().at(Arith::Div, Repr::Short), 1u);
  simd::Stream q;
  (void)simd::pow(q.in<Repr::Short>(), 120.0);  // 120 = 0b1111000: 6 squarings, 3 products
  EXPECT_EQ(q.mix().at(Arith::Mul, Repr::Short), 9u);
  simd::Stream one;
  (void)simd::pow(one.in<Repr::Short>(), 1.0);
  EXPECT_EQ(one.mix().total(), 0u);
}

TEST(SimdStream, Fig6TimesPriceAMix) {
  simd::InstructionMix m;
  m.at(Arith::Mul, Repr::Long) = 3;
  m.at(Arith::Add, Repr::Float) = 2;
  m.float_to_long = 1;
  simd::InstructionTimes t;
  t.at(Arith::Mul, Repr::Long) = 2.0e-6;
  t.at(Arith::Add, Repr::Float) = 3.94e-6;
  t.float_to_long = 1.35e-6;
  EXPECT_NEAR(t.time_of(m), 3 * 2.0e-6 + 2 * 3.94e-6 + 1.35e-6, 1e-15);
}

TEST(ShadingPrograms, ARegionIssuesTheProgramsOfTheFunctionsItHolds) {
  ProgramUniforms u;
  u.max_shine = 120.0;
  const ShadingPrograms programs = shading_programs(u);
  for (int k = 0; k < kShadingParts; ++k)
    EXPECT_GT(programs.parts[static_cast<std::size_t>(k)].total(), 0u) << kShadingPartNames[k];
  const auto& of = [&](ShadingPart p) { return programs.of(p); };

  RegionWork background;
  background.lights = 1;
  EXPECT_EQ(region_instructions(programs, background).total(), 0u);

  RegionWork ball;
  ball.lights = 2;
  ball.lit_pixels = 10;
  ball.pixels[static_cast<std::size_t>(ShadingFunction::Ball)] = 10;
  simd::InstructionMix want = of(ShadingPart::Surface);
  want += of(ShadingPart::BallPhong);
  want += of(ShadingPart::Light);
  want += of(ShadingPart::Light);
  EXPECT_EQ(region_instructions(programs, ball), want);

  // Adding pins adds the pin's five parts, whatever their number of pixels.
  RegionWork both = ball;
  both.pixels[static_cast<std::size_t>(ShadingFunction::Pin)] = 1;
  const auto few = region_instructions(programs, both).total();
  both.pixels[static_cast<std::size_t>(ShadingFunction::Pin)] = 8000;
  EXPECT_EQ(region_instructions(programs, both).total(), few);
  std::uint32_t pin = 0;
  for (const auto p : {ShadingPart::Crown, ShadingPart::Label, ShadingPart::Scuffs,
                       ShadingPart::Dirt, ShadingPart::PinPhong})
    pin += of(p).total();
  EXPECT_EQ(few, want.total() + pin);

  // A higher exponent costs the light loop more squarings.
  u.max_shine = 1000.0;
  EXPECT_GT(shading_programs(u).of(ShadingPart::Light).total(), of(ShadingPart::Light).total());
}

}  // namespace
