// Quantities with units: every spelling, exact picoseconds, formatting, and the error messages.
#include <gtest/gtest.h>

#include <cstdio>
#include <string>

#include "params/units.hpp"

namespace rtsim::params {
namespace {

struct Spelling {
  const char* text;
  UnitClass unit_class;
  double si;  // expected value in the SI base unit
};

TEST(Units, EverySpellingParsesToItsSiValue) {
  const Spelling cases[] = {
      {"400 ns", UnitClass::kTime, 400e-9},
      {"1 us", UnitClass::kTime, 1e-6},
      {"5.6 \u00b5s", UnitClass::kTime, 5.6e-6},  // micro sign
      {"5.6 \u03bcs", UnitClass::kTime, 5.6e-6},  // Greek mu
      {"0.333333 us", UnitClass::kTime, 0.333333e-6},
      {"2 ms", UnitClass::kTime, 2e-3},
      {"1 s", UnitClass::kTime, 1.0},
      {"1 ps", UnitClass::kTime, 1e-12},
      {"400ns", UnitClass::kTime, 400e-9},  // space optional
      {"  7 ns\t", UnitClass::kTime, 7e-9},
      {"1e3 ns", UnitClass::kTime, 1e-6},
      {"5 MHz", UnitClass::kFrequency, 5e6},
      {"1 GHz", UnitClass::kFrequency, 1e9},
      {"750 kHz", UnitClass::kFrequency, 750e3},
      {"1 Hz", UnitClass::kFrequency, 1.0},
      {"5 Gbit/s", UnitClass::kBitRate, 5e9},
      {"10 Mbit/s", UnitClass::kBitRate, 10e6},
      {"1 kbit/s", UnitClass::kBitRate, 1e3},
      {"1 bit/s", UnitClass::kBitRate, 1.0},
      {"64 KiB", UnitClass::kDataSize, 64.0 * 1024 * 8},
      {"2 MiB", UnitClass::kDataSize, 2.0 * 1024 * 1024 * 8},
      {"1 GiB", UnitClass::kDataSize, 1024.0 * 1024 * 1024 * 8},
      {"4 bytes", UnitClass::kDataSize, 32.0},
      {"1 byte", UnitClass::kDataSize, 8.0},
      {"3 B", UnitClass::kDataSize, 24.0},
      {"32 bits", UnitClass::kDataSize, 32.0},
      {"1 bit", UnitClass::kDataSize, 1.0},
      {"2.5", UnitClass::kDimensionless, 2.5},
      {"-2", UnitClass::kDimensionless, -2.0},
      {".5", UnitClass::kDimensionless, 0.5},
  };
  for (const Spelling& c : cases) {
    const Quantity q = parse_quantity(c.text, c.unit_class);
    EXPECT_DOUBLE_EQ(q.value, c.si) << c.text;
    EXPECT_EQ(q.unit_class, c.unit_class) << c.text;
  }
}

TEST(Units, WholeNumbersGiveTheSameDoubleAsTheLiteral) {
  // One rounding, not two: 400 * 1e-9 would be 4.0000000000000003e-7.
  EXPECT_EQ(parse_quantity("400 ns", UnitClass::kTime).value, 400e-9);
  EXPECT_EQ(parse_quantity("3 us", UnitClass::kTime).value, 3e-6);
  EXPECT_EQ(parse_quantity("1 ps", UnitClass::kTime).value, 1e-12);
  EXPECT_EQ(parse_quantity("7 ms", UnitClass::kTime).value, 7e-3);
  EXPECT_EQ(parse_quantity("5 MHz", UnitClass::kFrequency).value, 5e6);
}

TEST(Units, EveryTabledSpellingIsAccepted) {
  for (UnitClass c :
       {UnitClass::kTime, UnitClass::kFrequency, UnitClass::kBitRate, UnitClass::kDataSize}) {
    ASSERT_FALSE(units_of(c).empty());
    for (const Unit& u : units_of(c)) {
      const std::string text = "3 " + std::string(u.symbol);
      EXPECT_DOUBLE_EQ(parse_quantity(text, c).value, 3.0 * u.scale) << text;
    }
  }
  EXPECT_TRUE(units_of(UnitClass::kDimensionless).empty());
}

TEST(Units, TimesConvertExactlyToPicoseconds) {
  EXPECT_EQ(parse_quantity("333.333 ns", UnitClass::kTime).to_ps(), 333333);
  EXPECT_EQ(parse_quantity("0.333333 us", UnitClass::kTime).to_ps(), 333333);
  EXPECT_EQ(parse_quantity("5.6 \u00b5s", UnitClass::kTime).to_ps(), 5600000);
  EXPECT_EQ(parse_quantity("400 ns", UnitClass::kTime).to_ps(), 400000);
  EXPECT_EQ(parse_quantity("1 ps", UnitClass::kTime).to_ps(), 1);
  EXPECT_EQ(parse_quantity("0.001 ns", UnitClass::kTime).to_ps(), 1);
  EXPECT_EQ(parse_quantity("2 ms", UnitClass::kTime).to_ps(), 2'000'000'000);
  EXPECT_EQ(parse_quantity("1 s", UnitClass::kTime).to_ps(), 1'000'000'000'000);
  EXPECT_EQ(parse_quantity("1000 s", UnitClass::kTime).to_ps(), 1'000'000'000'000'000);
  EXPECT_EQ(parse_quantity("-3 ns", UnitClass::kTime).to_ps(), -3000);
  EXPECT_EQ(parse_quantity("0 s", UnitClass::kTime).to_ps(), 0);

  // Every whole picosecond count below 10^6 written in ns with 3 decimals, and every 7th one below
  // 10^7 written in us with 6 decimals, comes back exactly.
  char text[64];
  for (long ps = 0; ps < 1'000'000; ++ps) {
    std::snprintf(text, sizeof text, "%ld.%03ld ns", ps / 1000, ps % 1000);
    ASSERT_EQ(parse_quantity(text, UnitClass::kTime).to_ps(), ps) << text;
  }
  for (long ps = 0; ps < 10'000'000; ps += 7) {
    std::snprintf(text, sizeof text, "%ld.%06ld us", ps / 1'000'000, ps % 1'000'000);
    ASSERT_EQ(parse_quantity(text, UnitClass::kTime).to_ps(), ps) << text;
  }
}

TEST(Units, PicosecondsRejectWhatIsNotAWholeCount) {
  const auto message_of = [](const Quantity& q) {
    try {
      q.to_ps();
    } catch (const UnitError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_EQ(message_of(parse_quantity("0.5 ps", UnitClass::kTime)),
            "0.5 ps is not a whole number of picoseconds");
  EXPECT_EQ(message_of(parse_quantity("1.0001 ns", UnitClass::kTime)),
            "1.0001 ns is not a whole number of picoseconds");
  EXPECT_EQ(message_of(parse_quantity("1e-13 s", UnitClass::kTime)),
            "0.1 ps is not a whole number of picoseconds");
  EXPECT_EQ(message_of(parse_quantity("1e7 s", UnitClass::kTime)),
            "10000000 s is beyond the int64 picosecond range");
  EXPECT_EQ(message_of(parse_quantity("5 MHz", UnitClass::kFrequency)),
            "a frequency is not a time");
}

std::string parse_error(std::string_view text, UnitClass c) {
  try {
    parse_quantity(text, c);
  } catch (const UnitError& e) {
    return e.what();
  }
  return "no error";
}

TEST(Units, BadTextNamesTheUnitClassAndItsSpellings) {
  const std::string time_tail =
      "; expected a time such as \"400 ns\"; units: ps, ns, us, \u00b5s, ms, s";
  EXPECT_EQ(parse_error("400", UnitClass::kTime), "\"400\" has no unit" + time_tail);
  EXPECT_EQ(parse_error("5 MHz", UnitClass::kTime), "\"5 MHz\" is a frequency" + time_tail);
  EXPECT_EQ(parse_error("400 nsec", UnitClass::kTime),
            "\"400 nsec\" has an unknown unit \"nsec\"" + time_tail);
  EXPECT_EQ(parse_error("NS", UnitClass::kTime), "\"NS\" is not a number" + time_tail);
  EXPECT_EQ(parse_error("", UnitClass::kTime), "\"\" is not a number" + time_tail);
  EXPECT_EQ(parse_error("inf ns", UnitClass::kTime),
            "\"inf ns\" is not a finite number" + time_tail);
  EXPECT_EQ(parse_error("nan s", UnitClass::kTime), "\"nan s\" is not a finite number" + time_tail);
  EXPECT_EQ(parse_error("1e999 s", UnitClass::kTime), "\"1e999 s\" is out of range" + time_tail);
  EXPECT_EQ(parse_error("400 Ns", UnitClass::kTime),
            "\"400 Ns\" has an unknown unit \"Ns\"" + time_tail);  // case-sensitive, as SI

  EXPECT_EQ(parse_error("5 mhz", UnitClass::kFrequency),
            "\"5 mhz\" has an unknown unit \"mhz\"; expected a frequency such as \"5 MHz\"; "
            "units: Hz, kHz, MHz, GHz");
  EXPECT_EQ(parse_error("1e308 GHz", UnitClass::kFrequency),
            "\"1e308 GHz\" is out of range; expected a frequency such as \"5 MHz\"; "
            "units: Hz, kHz, MHz, GHz");
  EXPECT_EQ(parse_error("5 Gbps", UnitClass::kBitRate),
            "\"5 Gbps\" has an unknown unit \"Gbps\"; expected a bit rate such as \"5 Gbit/s\"; "
            "units: bit/s, kbit/s, Mbit/s, Gbit/s");
  EXPECT_EQ(parse_error("64 ns", UnitClass::kDataSize),
            "\"64 ns\" is a time; expected a data size such as \"64 KiB\"; "
            "units: bit, bits, B, byte, bytes, KiB, MiB, GiB");
  EXPECT_EQ(parse_error("3 ns", UnitClass::kDimensionless),
            "\"3 ns\" is a time; expected a number such as \"2.5\"");
  EXPECT_EQ(parse_error("3 x", UnitClass::kDimensionless),
            "\"3 x\" has an unknown unit \"x\"; expected a number such as \"2.5\"");
}

TEST(Units, FormatsWithTheLargestUnitKeepingTheNumberAboveOne) {
  const auto fmt = [](double v, UnitClass c) { return format_quantity({v, c}); };
  EXPECT_EQ(fmt(400e-9, UnitClass::kTime), "400 ns");
  EXPECT_EQ(fmt(333.333e-9, UnitClass::kTime), "333.333 ns");
  EXPECT_EQ(fmt(5.6e-6, UnitClass::kTime), "5.6 us");
  EXPECT_EQ(fmt(1.5e-3, UnitClass::kTime), "1.5 ms");
  EXPECT_EQ(fmt(1.0, UnitClass::kTime), "1 s");
  EXPECT_EQ(fmt(120.0, UnitClass::kTime), "120 s");
  EXPECT_EQ(fmt(1e-12, UnitClass::kTime), "1 ps");
  EXPECT_EQ(fmt(1e-15, UnitClass::kTime), "0.001 ps");
  EXPECT_EQ(fmt(0.0, UnitClass::kTime), "0 s");
  EXPECT_EQ(fmt(-3e-9, UnitClass::kTime), "-3 ns");
  EXPECT_EQ(fmt(5e6, UnitClass::kFrequency), "5 MHz");
  EXPECT_EQ(fmt(750e3, UnitClass::kFrequency), "750 kHz");
  EXPECT_EQ(fmt(1.0, UnitClass::kFrequency), "1 Hz");
  EXPECT_EQ(fmt(5e9, UnitClass::kBitRate), "5 Gbit/s");
  EXPECT_EQ(fmt(10e6, UnitClass::kBitRate), "10 Mbit/s");
  EXPECT_EQ(fmt(64.0 * 1024 * 8, UnitClass::kDataSize), "64 KiB");
  EXPECT_EQ(fmt(1536.0 * 8, UnitClass::kDataSize), "1.5 KiB");
  EXPECT_EQ(fmt(32.0, UnitClass::kDataSize), "4 B");
  EXPECT_EQ(fmt(12.0, UnitClass::kDataSize), "12 bit");
  EXPECT_EQ(fmt(0.0, UnitClass::kDataSize), "0 bit");
  EXPECT_EQ(fmt(2.5, UnitClass::kDimensionless), "2.5");
}

TEST(Units, FormattedTextReadsBack) {
  const Spelling cases[] = {
      {"333.333 ns", UnitClass::kTime, 0},    {"5.6 us", UnitClass::kTime, 0},
      {"0.333333 us", UnitClass::kTime, 0},   {"86400 s", UnitClass::kTime, 0},
      {"750 kHz", UnitClass::kFrequency, 0},  {"1.25 GHz", UnitClass::kFrequency, 0},
      {"2.5 Mbit/s", UnitClass::kBitRate, 0}, {"100 bytes", UnitClass::kDataSize, 0},
      {"0.1", UnitClass::kDimensionless, 0}};
  for (const Spelling& c : cases) {
    const Quantity q = parse_quantity(c.text, c.unit_class);
    const std::string text = format_quantity(q);
    const Quantity back = parse_quantity(text, c.unit_class);
    EXPECT_DOUBLE_EQ(back.value, q.value) << c.text << " -> " << text;
    if (c.unit_class == UnitClass::kTime) {
      EXPECT_EQ(back.to_ps(), q.to_ps()) << text;
    }
  }
}

TEST(Units, NamesAndBaseUnits) {
  EXPECT_EQ(unit_class_name(UnitClass::kBitRate), "bit rate");
  EXPECT_EQ(base_unit(UnitClass::kTime), "s");
  EXPECT_EQ(base_unit(UnitClass::kFrequency), "Hz");
  EXPECT_EQ(base_unit(UnitClass::kBitRate), "bit/s");
  EXPECT_EQ(base_unit(UnitClass::kDataSize), "bit");
  EXPECT_EQ(base_unit(UnitClass::kDimensionless), "");
}

}  // namespace
}  // namespace rtsim::params
