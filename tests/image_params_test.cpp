// Which parameters the image depends on (params::ParamSpec::affects_image), on every machine:
//  * every parameter the machine's functional twin reads, with the scene's generation, is marked:
//    the twin's render is the image, so these are what it can depend on;
//  * every parameter not marked leaves the image byte-identical: each in turn is set to another
//    valid value (doubled, halved, toggled, the next allowed choice) and the machine's own image,
//    from the data its transactions carried, is compared with the default's.
// A sweep renders the image once for points that differ only in unmarked parameters
// (platform/sweep/image_sharing.hpp): a wrong mark would hand a point another point's image.
// The machines are called directly, each simulation in a forked child (one per process).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "platform/machine.hpp"
#include "platform/machine_registry.hpp"
#include "tests/machine_test_support.hpp"
#include "tests/test_support.hpp"

namespace fs = std::filesystem;

namespace {

// Faults (fault.*) change the image by design and are marked; this scene need not show each.
// Lit polygons: every machine holds them and shades them, so shading parameters are read.
constexpr const char* kScene = "builtin:ullner-cubes";
constexpr int kSize = 16;

std::vector<std::string> machine_names() {
  std::vector<std::string> names;
  for (const auto* m : rtsim::platform::machines()) names.push_back(m->name());
  return names;
}

/// The machine's image at kSize x kSize with `overrides`, as raw float bytes in `out`; the
/// child's exit code (2: the setting was refused as bad input).
int image_of(const std::string& machine, const std::vector<std::string>& overrides,
             const fs::path& out) {
  return rtsim::test::image_in_child(machine, kScene, kSize, overrides, {}, out);
}

/// "2 us" -> "4 us": a value with a unit, its number doubled (0 becomes 1).
std::string doubled_text(const std::string& text) {
  const std::size_t space = text.find(' ');
  const double v = std::stod(text.substr(0, space));
  std::ostringstream s;
  s.precision(12);
  s << (v == 0.0 ? 1.0 : 2.0 * v);
  if (space != std::string::npos) s << text.substr(space);
  return s.str();
}

/// Another valid value of `e` (within its bounds), or none (a free string).
std::optional<std::string> other_value(const rtsim::params::ParamRegistry& r,
                                       const rtsim::params::ParamEntry& e) {
  using rtsim::params::ParamKind;
  std::vector<std::string> candidates;
  switch (e.kind) {
    case ParamKind::kBool:
      candidates = {e.value_text == "true" ? "false" : "true"};
      break;
    case ParamKind::kString:
      for (const auto& a : e.allowed)
        if (a != e.value_text) candidates.push_back(a);
      break;
    case ParamKind::kInt: {
      const auto v = std::get<std::int64_t>(e.value);
      for (std::int64_t c : {v * 2, v + 1, v - 1, v / 2}) candidates.push_back(std::to_string(c));
      break;
    }
    default: {  // double, and the unit kinds: the number with its unit
      candidates.push_back(doubled_text(e.value_text));
      const std::size_t space = e.value_text.find(' ');
      std::ostringstream half;
      half.precision(12);
      half << std::stod(e.value_text.substr(0, space)) / 2.0;
      if (space != std::string::npos) half << e.value_text.substr(space);
      candidates.push_back(half.str());
      // A zero (a latency, say) that doubling left too large: a small value instead.
      if (space != std::string::npos) candidates.push_back("0.001" + e.value_text.substr(space));
    }
  }
  // The first the registry takes (bounds, exactness) that reads differently.
  for (const auto& c : candidates) {
    rtsim::params::ParamRegistry copy = r;
    try {
      copy.apply_override(e.name + "=" + c);
    } catch (const std::exception&) {
      continue;
    }
    if (copy.value_text(e.name) != r.value_text(e.name)) return c;
  }
  return std::nullopt;
}

class ImageParams : public testing::TestWithParam<std::string> {};

TEST_P(ImageParams, WhatTheTwinReadsIsMarked) {
  const std::string& machine = GetParam();
  auto m = rtsim::test::prepare_machine(machine, kScene);
  const auto unread = m->registry.unread();
  const std::set<std::string> not_read(unread.begin(), unread.end());
  std::size_t read = 0;
  for (const auto& e : m->registry.list()) {
    if (not_read.contains(e.name)) continue;
    ++read;
    EXPECT_TRUE(e.affects_image) << machine << ": its twin (or the scene) reads " << e.name
                                 << ", so the image may depend on it: declare it affecting_image()";
  }
  std::printf("%s: the twin and the scene read %zu parameters\n", machine.c_str(), read);
  EXPECT_GT(read, 0u);
}

TEST_P(ImageParams, EveryOtherParameterLeavesTheImageIdentical) {
  const std::string& machine = GetParam();
  const fs::path dir = rtsim::test::scratch_dir("image-params-" + machine);
  fs::create_directories(dir);
  ASSERT_EQ(image_of(machine, {}, dir / "default.bin"), 0);
  const std::string reference = rtsim::test::read_file(dir / "default.bin");
  ASSERT_EQ(reference.size(), std::size_t{kSize} * kSize * 3 * sizeof(float));

  rtsim::params::ParamRegistry r;
  rtsim::platform::declare_params_of(&rtsim::platform::find_machine(machine), r);
  std::size_t compared = 0, marked = 0;
  std::vector<std::string> refused, no_other;
  for (const auto& e : r.list()) {
    if (e.affects_image) {
      ++marked;
      continue;
    }
    const auto value = other_value(r, e);
    if (!value) {
      no_other.push_back(e.name);
      continue;
    }
    const std::string setting = e.name + "=" + *value;
    const fs::path out = dir / "changed.bin";
    fs::remove(out);
    const int code = image_of(machine, {setting}, out);
    if (code == 2) {  // bad input for this scene and size (a machine's own consistency check)
      refused.push_back(setting);
      continue;
    }
    ASSERT_EQ(code, 0) << setting;
    ++compared;
    EXPECT_TRUE(rtsim::test::read_file(out) == reference)
        << machine << ": -p " << setting << " changed the image, but " << e.name
        << " is not marked affects_image";
  }
  std::printf("%s: %zu parameters changed with the image identical, %zu marked affecting it\n",
              machine.c_str(), compared, marked);
  for (const auto& s : refused) std::printf("  refused as bad input here: -p %s\n", s.c_str());
  for (const auto& s : no_other) std::printf("  no other value to try: %s\n", s.c_str());
  // The check compares most of what it claims to.
  EXPECT_GE(compared, 4 * (refused.size() + no_other.size())) << machine;
  fs::remove_all(dir);
}

INSTANTIATE_TEST_SUITE_P(Machines, ImageParams, testing::ValuesIn(machine_names()),
                         [](const testing::TestParamInfo<std::string>& i) {
                           std::string s = i.param;
                           for (char& c : s)
                             if (c == '-') c = '_';
                           return s;
                         });

}  // namespace
