// The parameter registry: declarations, layering (defaults < TOML < -p), where each value was set,
// and the messages a user sees for every kind of bad input.
#include <gtest/gtest.h>

#include <algorithm>
#include <iostream>
#include <random>
#include <stdexcept>
#include <string>

#include "common/input_error.hpp"
#include "common/suggest.hpp"
#include "params/registry.hpp"

namespace rtsim::params {
namespace {

using namespace std::string_literals;

const std::string kDataDir = std::string(RTSIM_TEST_DATA_DIR) + "/params/";

// A small machine's worth of parameters, one of each kind.
ParamRegistry make_registry() {
  ParamRegistry r;
  r.declare({.name = "peripheral.grid.divisions",
             .kind = ParamKind::kInt,
             .default_value = "11",
             .min = "1",
             .max = "256",
             .unit = "cells per axis",
             .description = "grid subdivisions along each axis",
             .source = "seed 000 L654"});
  r.declare({.name = "peripheral.grid.enabled",
             .kind = ParamKind::kBool,
             .default_value = "true",
             .description = "use the grid auxiliary processor",
             .source = "assumption: the seed's preferred configuration"});
  r.declare({.name = "render.order",
             .kind = ParamKind::kString,
             .default_value = "scanline",
             .allowed = {"scanline", "tiled", "hilbert"},
             .description = "pixel order",
             .source = "assumption: test"});
  r.declare({.name = "render.label",
             .kind = ParamKind::kString,
             .default_value = "none",
             .description = "free text",
             .source = "assumption: test"});
  r.declare({.name = "render.gamma",
             .kind = ParamKind::kDouble,
             .default_value = "2.2",
             .min = "0.1",
             .max = "10",
             .description = "display gamma",
             .source = "assumption: sRGB-like"});
  r.declare({.name = "vax.fp_add_time",
             .kind = ParamKind::kTime,
             .default_value = "400 ns",
             .min = "0 s",
             .description = "floating-point add",
             .source = "assumption: test"});
  r.declare({.name = "vax.clock",
             .kind = ParamKind::kFrequency,
             .default_value = "5 MHz",
             .description = "processor clock",
             .source = "assumption: test"});
  r.declare({.name = "link.rate",
             .kind = ParamKind::kBitRate,
             .default_value = "5 Gbit/s",
             .description = "serial link rate",
             .source = "assumption: test"});
  r.declare({.name = "memory.size",
             .kind = ParamKind::kDataSize,
             .default_value = "64 KiB",
             .description = "node memory",
             .source = "assumption: test"});
  for (const char* pert : {"pert0", "pert1", "pert2"}) {
    r.declare({.name = std::string(pert) + ".shell.bic.id_registers",
               .kind = ParamKind::kInt,
               .default_value = "16",
               .min = "1",
               .description = "ID registers in the bus interface controller",
               .source = "assumption: test"});
  }
  return r;
}

// The InputError a call throws; fails the test if it throws nothing or something else.
template <typename F>
InputError input_error_of(F&& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e;
  }
  ADD_FAILURE() << "expected an InputError";
  return InputError("", 0, "none");
}

InputError toml_error(const std::string& text) {
  ParamRegistry r = make_registry();
  return input_error_of([&] { r.load_toml_string(text, "test.toml"); });
}

InputError override_error(const std::string& assignment) {
  ParamRegistry r = make_registry();
  return input_error_of([&] { r.apply_override(assignment); });
}

TEST(ParamRegistry, DefaultsAreReadByTypedGetters) {
  const ParamRegistry r = make_registry();
  EXPECT_EQ(r.size(), 12u);
  EXPECT_EQ(r.get_int("peripheral.grid.divisions"), 11);
  EXPECT_TRUE(r.get_bool("peripheral.grid.enabled"));
  EXPECT_EQ(r.get_string("render.order"), "scanline");
  EXPECT_DOUBLE_EQ(r.get_double("render.gamma"), 2.2);
  EXPECT_DOUBLE_EQ(r.get_time_s("vax.fp_add_time"), 400e-9);
  EXPECT_EQ(r.get_time_ps("vax.fp_add_time"), 400'000);
  EXPECT_DOUBLE_EQ(r.get_frequency_hz("vax.clock"), 5e6);
  EXPECT_DOUBLE_EQ(r.get_bitrate_bps("link.rate"), 5e9);
  EXPECT_DOUBLE_EQ(r.get_data_size_bits("memory.size"), 64.0 * 1024 * 8);
  EXPECT_EQ(r.where_set("vax.clock"), "default");
  EXPECT_TRUE(r.contains("vax.clock"));
  EXPECT_FALSE(r.contains("vax"));
}

TEST(ParamRegistry, ListIsSortedByNameWithEveryColumn) {
  const std::vector<ParamEntry> rows = make_registry().list();
  ASSERT_EQ(rows.size(), 12u);
  for (std::size_t i = 1; i < rows.size(); ++i) EXPECT_LT(rows[i - 1].name, rows[i].name);
  EXPECT_EQ(rows.front().name, "link.rate");
  EXPECT_EQ(rows.back().name, "vax.fp_add_time");

  const ParamEntry& time = rows.back();
  EXPECT_EQ(time.kind, ParamKind::kTime);
  EXPECT_EQ(std::get<double>(time.value), 400e-9);
  EXPECT_EQ(time.value_text, "400 ns");
  EXPECT_EQ(time.default_text, "400 ns");
  EXPECT_EQ(time.unit, "s");
  EXPECT_EQ(time.description, "floating-point add");
  EXPECT_EQ(time.where_set, "default");

  const ParamEntry& grid = rows[2];
  EXPECT_EQ(grid.name, "peripheral.grid.divisions");
  EXPECT_EQ(std::get<std::int64_t>(grid.value), 11);
  EXPECT_EQ(grid.unit, "cells per axis");
  EXPECT_EQ(grid.source, "seed 000 L654");
  EXPECT_EQ(kind_name(grid.kind), "int");
}

TEST(ParamRegistry, LayersDefaultsThenFileThenOverride) {
  ParamRegistry r = make_registry();
  const std::string path = kDataDir + "layered.toml";
  r.load_toml_file(path);
  EXPECT_EQ(r.get_int("peripheral.grid.divisions"), 8);
  EXPECT_EQ(r.where_set("peripheral.grid.divisions"), path + ":6");
  EXPECT_EQ(r.get_string("render.order"), "tiled");
  EXPECT_EQ(r.where_set("render.order"), path + ":3");
  EXPECT_EQ(r.get_time_ps("vax.fp_add_time"), 333'333);
  EXPECT_DOUBLE_EQ(r.get_frequency_hz("vax.clock"), 750e3);
  EXPECT_EQ(r.where_set("vax.clock"), path + ":10");
  EXPECT_EQ(r.where_set("render.gamma"), "default");

  r.apply_override("peripheral.grid.divisions=16");
  EXPECT_EQ(r.get_int("peripheral.grid.divisions"), 16);
  EXPECT_EQ(r.where_set("peripheral.grid.divisions"), "-p");
  EXPECT_EQ(r.where_set("render.order"), path + ":3");  // untouched by the override

  const std::vector<ParamEntry> rows = r.list();
  const auto grid = std::find_if(rows.begin(), rows.end(), [](const ParamEntry& e) {
    return e.name == "peripheral.grid.divisions";
  });
  ASSERT_NE(grid, rows.end());
  EXPECT_EQ(grid->value_text, "16");
  EXPECT_EQ(grid->default_text, "11");
  EXPECT_EQ(grid->where_set, "-p");
}

TEST(ParamRegistry, LaterLayersWin) {
  ParamRegistry r = make_registry();
  r.load_toml_string("vax.clock = \"1 MHz\"", "first.toml");
  r.load_toml_string("\n\nvax.clock = \"2 MHz\"", "second.toml");
  EXPECT_DOUBLE_EQ(r.get_frequency_hz("vax.clock"), 2e6);
  EXPECT_EQ(r.where_set("vax.clock"), "second.toml:3");
}

TEST(ParamRegistry, NestedTablesDottedKeysAndInlineTablesAreTheSameName) {
  const char* forms[] = {
      "[peripheral.grid]\ndivisions = 5\n",
      "peripheral.grid.divisions = 5\n",
      "[peripheral]\ngrid.divisions = 5\n",
      "[peripheral]\n[peripheral.grid]\ndivisions = 5\n",
      "peripheral = { grid = { divisions = 5 } }\n",
      "\"peripheral\".'grid'.divisions = 5\n",
  };
  for (const char* text : forms) {
    ParamRegistry r = make_registry();
    r.load_toml_string(text, "form.toml");
    EXPECT_EQ(r.get_int("peripheral.grid.divisions"), 5) << text;
  }
}

TEST(ParamRegistry, TomlValuesAreReadByKind) {
  ParamRegistry r = make_registry();
  r.load_toml_string(
      "render.gamma = 2\n"  // an integer is a fine double
      "render.label = 'scan line 1'\n"
      "peripheral.grid.enabled = false\n"
      "link.rate = \"10 Mbit/s\"\n"
      "memory.size = \"4 bytes\"\n"
      "vax.fp_add_time = \"5.6 \u00b5s\"\n",
      "kinds.toml");
  EXPECT_DOUBLE_EQ(r.get_double("render.gamma"), 2.0);
  EXPECT_EQ(r.get_string("render.label"), "scan line 1");
  EXPECT_FALSE(r.get_bool("peripheral.grid.enabled"));
  EXPECT_DOUBLE_EQ(r.get_bitrate_bps("link.rate"), 10e6);
  EXPECT_DOUBLE_EQ(r.get_data_size_bits("memory.size"), 32.0);
  EXPECT_EQ(r.get_time_ps("vax.fp_add_time"), 5'600'000);
}

TEST(ParamRegistry, OverridesTakeQuotedOrBareValues) {
  ParamRegistry r = make_registry();
  r.apply_override("render.order=\"hilbert\"");
  EXPECT_EQ(r.get_string("render.order"), "hilbert");
  r.apply_override("render.order='tiled'");
  EXPECT_EQ(r.get_string("render.order"), "tiled");
  r.apply_override("render.order=scanline");
  EXPECT_EQ(r.get_string("render.order"), "scanline");
  r.apply_override("render.label=a=b");  // only the first '=' separates
  EXPECT_EQ(r.get_string("render.label"), "a=b");
  r.apply_override("render.label=");
  EXPECT_EQ(r.get_string("render.label"), "");
  r.apply_override(" vax.fp_add_time = 1 us ");
  EXPECT_EQ(r.get_time_ps("vax.fp_add_time"), 1'000'000);
  r.apply_override("vax.fp_add_time=\"250 ns\"");
  EXPECT_EQ(r.get_time_ps("vax.fp_add_time"), 250'000);
  r.apply_override("vax.fp_add_time=2ms");
  EXPECT_EQ(r.get_time_ps("vax.fp_add_time"), 2'000'000'000);
  r.apply_override("peripheral.grid.enabled=false");
  EXPECT_FALSE(r.get_bool("peripheral.grid.enabled"));
  r.apply_override("render.gamma=1e0");
  EXPECT_DOUBLE_EQ(r.get_double("render.gamma"), 1.0);
  r.apply_override("peripheral.grid.divisions=256");
  EXPECT_EQ(r.get_int("peripheral.grid.divisions"), 256);
}

TEST(ParamRegistry, TomlSyntaxErrorsGiveTheLine) {
  const std::string path = kDataDir + "syntax_error.toml";
  ParamRegistry r = make_registry();
  const InputError e = input_error_of([&] { r.load_toml_file(path); });
  EXPECT_EQ(e.file(), path);
  EXPECT_EQ(e.line(), 3u);
  EXPECT_FALSE(e.message().empty());
  EXPECT_EQ(r.get_int("peripheral.grid.divisions"), 11);  // nothing applied
  std::cout << "toml++ says: " << e.what() << "\n";

  const InputError missing = input_error_of([&] { r.load_toml_file(kDataDir + "absent.toml"); });
  EXPECT_EQ(missing.file(), kDataDir + "absent.toml");
  EXPECT_EQ(missing.line(), 0u);
  EXPECT_EQ(missing.message(), "cannot open config file: no such file");

  EXPECT_EQ(toml_error("a = 1\na = 2\n").line(), 2u);  // redefinition is a TOML error
}

TEST(ParamRegistry, UnknownNamesSuggestTheClosest) {
  const std::string path = kDataDir + "misspelled.toml";
  ParamRegistry r = make_registry();
  const InputError e = input_error_of([&] { r.load_toml_file(path); });
  EXPECT_EQ(e.file(), path);
  EXPECT_EQ(e.line(), 5u);
  EXPECT_EQ(e.message(),
            "unknown parameter 'peripheral.gird.divisions'; did you mean "
            "'peripheral.grid.divisions'?");
  EXPECT_EQ(std::string(e.what()),
            path +
                ":5: unknown parameter 'peripheral.gird.divisions'; did you mean "
                "'peripheral.grid.divisions'?");
  EXPECT_EQ(r.get_int("peripheral.grid.divisions"), 11);  // line 2 was not applied either

  EXPECT_EQ(toml_error("[peripheral.grid]\ndivison = 11").message(),
            "unknown parameter 'peripheral.grid.divison'; did you mean "
            "'peripheral.grid.divisions'?");
  // The right leaf under a wrong path is found by its last segment, the nearest path first.
  EXPECT_EQ(toml_error("\n[pert1.bic]\nid_registers = 4").message(),
            "unknown parameter 'pert1.bic.id_registers'; did you mean "
            "'pert1.shell.bic.id_registers', 'pert0.shell.bic.id_registers' or "
            "'pert2.shell.bic.id_registers'?");
  EXPECT_EQ(toml_error("\n[pert1.bic]\nid_registers = 4").line(), 3u);
  EXPECT_EQ(toml_error("divisions = 3").message(),
            "unknown parameter 'divisions'; did you mean 'peripheral.grid.divisions'?");
  EXPECT_EQ(toml_error("vax.clok = '5 MHz'").message(),
            "unknown parameter 'vax.clok'; did you mean 'vax.clock'?");
  EXPECT_EQ(toml_error("zzzz.qqqq = 1").message(),
            "unknown parameter 'zzzz.qqqq'; `rtsim list params` lists them all");
  // A value where a table of parameters is expected is just an unknown name.
  EXPECT_EQ(toml_error("vax = 3").message(),
            "unknown parameter 'vax'; `rtsim list params` lists them all");

  const InputError o = override_error("peripheral.grid.divison=11");
  EXPECT_EQ(o.file(), "");
  EXPECT_EQ(o.line(), 0u);
  EXPECT_EQ(std::string(o.what()),
            "unknown parameter 'peripheral.grid.divison'; did you mean "
            "'peripheral.grid.divisions'?");
}

TEST(ParamRegistry, WrongTypeOrRangeNamesTheParameterAndWhatItTakes) {
  struct Case {
    const char* toml;
    const char* message;
  };
  const Case cases[] = {
      {"peripheral.grid.divisions = \"eleven\"",
       "parameter 'peripheral.grid.divisions' expects an integer from 1 to 256; got a string "
       "\"eleven\""},
      {"peripheral.grid.divisions = 300",
       "parameter 'peripheral.grid.divisions' expects an integer from 1 to 256; got 300"},
      {"peripheral.grid.divisions = 0",
       "parameter 'peripheral.grid.divisions' expects an integer from 1 to 256; got 0"},
      {"peripheral.grid.divisions = 1.5",
       "parameter 'peripheral.grid.divisions' expects an integer from 1 to 256; got a float"},
      {"peripheral.grid.divisions = [1, 2]",
       "parameter 'peripheral.grid.divisions' expects an integer from 1 to 256; got an array"},
      {"peripheral.grid.divisions = 1979-05-27",
       "parameter 'peripheral.grid.divisions' expects an integer from 1 to 256; got a date"},
      {"pert0.shell.bic.id_registers = -1",
       "parameter 'pert0.shell.bic.id_registers' expects an integer of at least 1; got -1"},
      {"peripheral.grid.enabled = 1",
       "parameter 'peripheral.grid.enabled' expects true or false; got an integer 1"},
      {"peripheral.grid.enabled = \"yes\"",
       "parameter 'peripheral.grid.enabled' expects true or false; got a string \"yes\""},
      {"render.gamma = 20.5", "parameter 'render.gamma' expects a number from 0.1 to 10; got 20.5"},
      {"render.gamma = nan", "parameter 'render.gamma' expects a number from 0.1 to 10; got nan"},
      {"render.gamma = true",
       "parameter 'render.gamma' expects a number from 0.1 to 10; got a boolean true"},
      {"render.label = 3", "parameter 'render.label' expects a string; got an integer 3"},
      {"render.order = \"scanlin\"",
       "parameter 'render.order' expects one of: scanline, tiled, hilbert; got \"scanlin\" "
       "(did you mean \"scanline\"?)"},
      {"render.order = \"zigzag\"",
       "parameter 'render.order' expects one of: scanline, tiled, hilbert; got \"zigzag\""},
      {"vax.fp_add_time = 400",
       "parameter 'vax.fp_add_time': \"400\" has no unit; expected a time such as \"400 ns\"; "
       "units: ps, ns, us, \u00b5s, ms, s"},
      {"vax.fp_add_time = 4.5",
       "parameter 'vax.fp_add_time': \"4.5\" has no unit; expected a time such as \"400 ns\"; "
       "units: ps, ns, us, \u00b5s, ms, s"},
      {"vax.fp_add_time = \"5 MHz\"",
       "parameter 'vax.fp_add_time': \"5 MHz\" is a frequency; expected a time such as "
       "\"400 ns\"; units: ps, ns, us, \u00b5s, ms, s"},
      {"vax.fp_add_time = \"0.5 ps\"",
       "parameter 'vax.fp_add_time': 0.5 ps is not a whole number of picoseconds"},
      {"vax.fp_add_time = \"-1 ns\"",
       "parameter 'vax.fp_add_time' expects a time of at least 0 s; got -1 ns"},
      {"vax.fp_add_time = true",
       "parameter 'vax.fp_add_time' expects a time of at least 0 s; got a boolean true"},
      {"vax.clock = \"5 ns\"",
       "parameter 'vax.clock': \"5 ns\" is a time; expected a frequency such as \"5 MHz\"; "
       "units: Hz, kHz, MHz, GHz"},
      {"memory.size = \"64 kB\"",
       "parameter 'memory.size': \"64 kB\" has an unknown unit \"kB\"; expected a data size "
       "such as \"64 KiB\"; units: bit, bits, B, byte, bytes, KiB, MiB, GiB"},
  };
  for (const Case& c : cases) {
    const InputError e = toml_error(std::string("\n\n") + c.toml);
    EXPECT_EQ(e.message(), c.message) << c.toml;
    EXPECT_EQ(e.file(), "test.toml") << c.toml;
    EXPECT_EQ(e.line(), 3u) << c.toml;
  }
}

TEST(ParamRegistry, AFailedFileChangesNothing) {
  const std::string path = kDataDir + "bad_range.toml";
  ParamRegistry r = make_registry();
  const InputError e = input_error_of([&] { r.load_toml_file(path); });
  EXPECT_EQ(std::string(e.what()),
            path +
                ":4: parameter 'peripheral.grid.divisions' expects an integer from 1 to 256; "
                "got 300");
  EXPECT_TRUE(r.get_bool("peripheral.grid.enabled"));  // line 3 is valid but not applied
  EXPECT_EQ(r.where_set("peripheral.grid.enabled"), "default");
}

TEST(ParamRegistry, TheFirstProblemInFileOrderIsReported) {
  // toml++ keeps keys sorted; the report must still follow the file.
  const InputError e = toml_error("zeta.unknown = 1\nalpha.unknown = 2\n");
  EXPECT_EQ(e.line(), 1u);
  EXPECT_NE(e.message().find("'zeta.unknown'"), std::string::npos);
}

TEST(ParamRegistry, BadOverridesSayWhatIsExpected) {
  EXPECT_EQ(override_error("peripheral.grid.divisions").message(),
            "-p expects name=value (e.g. -p peripheral.grid.divisions=11), got "
            "'peripheral.grid.divisions'");
  EXPECT_EQ(override_error("=5").message(),
            "-p expects name=value (e.g. -p peripheral.grid.divisions=11), got '=5'");
  EXPECT_EQ(override_error("peripheral.grid.divisions=eleven").message(),
            "parameter 'peripheral.grid.divisions' expects an integer from 1 to 256; got "
            "\"eleven\"");
  EXPECT_EQ(override_error("peripheral.grid.divisions=11.0").message(),
            "parameter 'peripheral.grid.divisions' expects an integer from 1 to 256; got "
            "\"11.0\"");
  EXPECT_EQ(override_error("peripheral.grid.divisions=99999999999999999999").message(),
            "parameter 'peripheral.grid.divisions' expects an integer from 1 to 256; got "
            "\"99999999999999999999\"");
  EXPECT_EQ(override_error("peripheral.grid.enabled=yes").message(),
            "parameter 'peripheral.grid.enabled' expects true or false; got \"yes\"");
  EXPECT_EQ(override_error("render.gamma=inf").message(),
            "parameter 'render.gamma' expects a number from 0.1 to 10; got \"inf\"");
  EXPECT_EQ(override_error("render.order=Tiled").message(),
            "parameter 'render.order' expects one of: scanline, tiled, hilbert; got \"Tiled\" "
            "(did you mean \"tiled\"?)");
  EXPECT_EQ(override_error("vax.fp_add_time=400").message(),
            "parameter 'vax.fp_add_time': \"400\" has no unit; expected a time such as \"400 ns\"; "
            "units: ps, ns, us, \u00b5s, ms, s");
  const InputError e = override_error("link.rate=5 Gbps");
  EXPECT_EQ(e.file(), "");
  EXPECT_EQ(e.line(), 0u);
}

TEST(ParamRegistry, MisuseByCodeIsALogicErrorNotInputError) {
  const ParamRegistry r = make_registry();
  EXPECT_THROW(r.get_int("peripheral.grid.division"), std::logic_error);
  EXPECT_THROW(r.get_double("peripheral.grid.divisions"), std::logic_error);  // an int
  EXPECT_THROW(r.get_time_s("vax.clock"), std::logic_error);
  EXPECT_THROW(r.where_set("nope"), std::logic_error);
  try {
    r.get_string("vax.clock");
    ADD_FAILURE() << "no error";
  } catch (const std::logic_error& e) {
    EXPECT_EQ(std::string(e.what()),
              "parameter 'vax.clock' is declared as frequency, read as string");
  }

  const auto declare_error = [](ParamSpec spec) {
    ParamRegistry reg = make_registry();
    try {
      reg.declare(std::move(spec));
    } catch (const std::logic_error& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_EQ(declare_error({.name = "vax.clock", .kind = ParamKind::kInt, .default_value = "1"}),
            "declaring parameter 'vax.clock': already declared");
  EXPECT_EQ(declare_error({.name = "vax..x", .default_value = "1"}),
            "declaring parameter 'vax..x': use dot-separated segments of letters, digits and '_'");
  EXPECT_EQ(declare_error({.name = "", .default_value = "1"}),
            "declaring parameter '': use dot-separated segments of letters, digits and '_'");
  EXPECT_EQ(declare_error({.name = "a-b", .default_value = "1"}),
            "declaring parameter 'a-b': use dot-separated segments of letters, digits and '_'");
  EXPECT_EQ(declare_error({.name = "vax.clock.divider", .default_value = "1"}),
            "declaring parameter 'vax.clock.divider': 'vax.clock' is a parameter");
  EXPECT_EQ(declare_error({.name = "peripheral.grid", .default_value = "1"}),
            "declaring parameter 'peripheral.grid': 'peripheral.grid.divisions' is a parameter "
            "below it");
  EXPECT_EQ(declare_error({.name = "x", .kind = ParamKind::kTime, .default_value = "400"}),
            "declaring parameter 'x': parameter 'x': \"400\" has no unit; expected a time such as "
            "\"400 ns\"; units: ps, ns, us, \u00b5s, ms, s");
  EXPECT_EQ(declare_error({.name = "x", .default_value = "0", .min = "1"}),
            "declaring parameter 'x': parameter 'x' expects an integer of at least 1; got 0");
  EXPECT_EQ(declare_error({.name = "x", .default_value = "1", .allowed = {"a"}}),
            "declaring parameter 'x': only strings take allowed values");
  EXPECT_EQ(
      declare_error({.name = "x", .kind = ParamKind::kBool, .default_value = "true", .max = "1"}),
      "declaring parameter 'x': strings and bools take no bounds");
  EXPECT_EQ(
      declare_error(
          {.name = "x", .kind = ParamKind::kString, .default_value = "d", .allowed = {"a", "b"}}),
      "declaring parameter 'x': parameter 'x' expects one of: a, b; got \"d\"");
  EXPECT_EQ(
      declare_error({.name = "x", .kind = ParamKind::kTime, .default_value = "1 ns", .unit = "ns"}),
      "declaring parameter 'x': the value's unit is given with it");
  EXPECT_EQ(declare_error({.name = "x_1.y2", .default_value = "1"}), "no error");
}

// DESIGN.md "Configuration": a class name sets every instance, an instance name one, and the
// more specific wins; an instance the run does not build is an error, not a silent no-op.
ParamRegistry make_family_registry() {
  ParamRegistry r;
  r.declare({.name = "pert_count", .kind = ParamKind::kInt, .default_value = "2", .min = "1"});
  r.declare({.name = "pert.shell.clock",
             .kind = ParamKind::kFrequency,
             .default_value = "5 MHz",
             .per_instance = true});
  r.declare({.name = "pert.mode", .kind = ParamKind::kString, .default_value = "a"});
  r.declare({.name = "broadcast.word_time",
             .kind = ParamKind::kTime,
             .default_value = "400 ns",
             .per_instance = true});
  r.declare_family({.cls = "pert", .count_param = "pert_count"});
  r.declare_family({.cls = "broadcast", .members = {"shade_bus", "shell_bus"}});
  return r;
}

TEST(ParamRegistry, AnInstanceNameSetsOneInstanceAndWinsOverItsClass) {
  ParamRegistry r = make_family_registry();
  r.load_toml_string("[pert1.shell]\nclock = \"4 MHz\"\n[pert.shell]\nclock = \"6 MHz\"\n",
                     "m.toml");
  r.apply_override("shell_bus.word_time=500 ns");
  EXPECT_DOUBLE_EQ(r.get_frequency_hz("pert0.shell.clock"), 6e6);  // the class's
  EXPECT_DOUBLE_EQ(r.get_frequency_hz("pert1.shell.clock"), 4e6);  // its own
  EXPECT_EQ(r.where_set("pert1.shell.clock"), "m.toml:2");
  EXPECT_EQ(r.where_set("pert0.shell.clock"), "m.toml:4");
  EXPECT_EQ(r.get_time_ps("shell_bus.word_time"), 500'000);
  EXPECT_EQ(r.get_time_ps("shade_bus.word_time"), 400'000);
  // Listed once per class, plus each instance value that was set.
  std::vector<std::string> names;
  for (const auto& e : r.list()) names.push_back(e.name);
  EXPECT_EQ(names,
            (std::vector<std::string>{"broadcast.word_time", "pert.mode", "pert.shell.clock",
                                      "pert1.shell.clock", "pert_count", "shell_bus.word_time"}));
  EXPECT_NO_THROW(r.check_instances());
  // Reading an instance counts as reading its class.
  EXPECT_EQ(r.unread(), (std::vector<std::string>{"pert.mode", "pert_count"}));
}

TEST(ParamRegistry, InstanceNamesOnlyWhereTheClassAllowsThem) {
  ParamRegistry r = make_family_registry();
  // Not per instance, not a member, not a number, a leading zero: unknown names.
  for (const char* bad : {"pert1.mode=b", "prim_bus.word_time=1 us", "pertx.shell.clock=1 MHz",
                          "pert01.shell.clock=1 MHz"}) {
    try {
      r.apply_override(bad);
      ADD_FAILURE() << bad << " was accepted";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("unknown parameter"), std::string::npos) << e.what();
    }
  }
  // A bad value for an instance is reported like any other, and changes nothing.
  EXPECT_THROW(r.apply_override("pert1.shell.clock=fast"), InputError);
  EXPECT_DOUBLE_EQ(r.get_frequency_hz("pert1.shell.clock"), 5e6);
}

TEST(ParamRegistry, AnInstanceTheRunDoesNotBuildIsAnError) {
  ParamRegistry r = make_family_registry();
  r.apply_override("pert2.shell.clock=4 MHz");
  try {
    r.check_instances();
    ADD_FAILURE() << "pert2 with pert_count = 2 was accepted";
  } catch (const InputError& e) {
    const std::string m = e.what();
    std::cout << m << "\n";
    EXPECT_NE(m.find("pert2"), std::string::npos) << m;
    EXPECT_NE(m.find("pert_count is 2"), std::string::npos) << m;
  }
  r.apply_override("pert_count=3");
  EXPECT_NO_THROW(r.check_instances());
}

TEST(Suggest, EditDistanceCountsAdjacentSwapsAsOne) {
  EXPECT_EQ(edit_distance("", "abc"), 3u);
  EXPECT_EQ(edit_distance("abc", "abc"), 0u);
  EXPECT_EQ(edit_distance("kitten", "sitting"), 3u);
  EXPECT_EQ(edit_distance("grid", "gird"), 1u);  // a transposition
  EXPECT_EQ(edit_distance("ca", "abc"), 3u);     // optimal string alignment: no edit of a swap
  EXPECT_EQ(edit_distance("divisions", "divison"), 2u);
}

TEST(Suggest, OnlyReasonablyCloseNamesAreOffered) {
  const std::vector<std::string_view> names = {"a.clock", "b.clock", "a.clack", "a.lock", "zz"};
  // "a.clack" is two edits from "a.clokc": too far for 7 characters; "b.clock" is found by its
  // last segment, one edit away.
  EXPECT_EQ(closest_names("a.clokc", names), (std::vector<std::string>{"a.clock", "b.clock"}));
  EXPECT_EQ(closest_names("a.clokc", names, 1), (std::vector<std::string>{"a.clock"}));
  EXPECT_EQ(closest_names("q", names), (std::vector<std::string>{}));  // "zz" is 2 edits
  EXPECT_EQ(closest_names("x", {"y"}), (std::vector<std::string>{}));  // not a total rewrite
  EXPECT_EQ(closest_names("c.d.clock", names),
            (std::vector<std::string>{"a.clock", "b.clock", "a.clack"}));  // by last segment
}

// Found by fuzzing the config reader: a megabyte-long unknown name took seconds to refuse, two
// edit distances of a megabyte by thirty bytes per declared parameter. Names too far in length
// to be close are now skipped before any distance is computed; the suggestions are unchanged.
TEST(Suggest, AHugeUnknownNameIsRefusedWithoutComputingDistances) {
  const std::vector<std::string_view> names = {"a.clock", "b.clock", "shade.ambient"};
  const std::string huge(4'000'000, 'a');
  EXPECT_EQ(closest_names(huge, names), (std::vector<std::string>{}));
  EXPECT_EQ(closest_names(huge + ".clock", names),
            (std::vector<std::string>{"a.clock", "b.clock"}));  // by last segment, as before
  EXPECT_EQ(closest_names("shade.ambeint", names), (std::vector<std::string>{"shade.ambient"}));
}

TEST(ParamRegistry, ThousandsOfParametersStayUsable) {
  ParamRegistry r;
  for (int pert = 0; pert < 64; ++pert) {
    for (int reg = 0; reg < 64; ++reg) {
      r.declare({.name = "pert" + std::to_string(pert) + ".shell.bic.reg" + std::to_string(reg),
                 .default_value = std::to_string(reg)});
    }
  }
  EXPECT_EQ(r.size(), 4096u);
  EXPECT_EQ(r.get_int("pert63.shell.bic.reg17"), 17);
  ParamRegistry copy = r;
  const InputError e = input_error_of([&] { copy.apply_override("pert63.shel.bic.reg17=1"); });
  // Every pert has a reg17; the one a single edit away comes first.
  EXPECT_TRUE(e.message().starts_with(
      "unknown parameter 'pert63.shel.bic.reg17'; did you mean 'pert63.shell.bic.reg17', "))
      << e.message();
  EXPECT_EQ(r.list().size(), 4096u);
}

// Malformed TOML must end in InputError (or load, if the damage happens to be valid), never in a
// crash or another exception. Each snippet is cut at every byte and has every byte replaced by
// each of a set of troublesome characters; then random strings over a TOML-ish alphabet.
TEST(ParamRegistry, MalformedTomlNeverCrashes) {
  const std::string snippets[] = {
      "[peripheral.grid]\ndivisions = 11\nenabled = true\n",
      "vax.fp_add_time = \"333.333 ns\" # comment\nvax.clock = '5 MHz'\n",
      "peripheral = { grid = { divisions = 5 } }\nrender.order = \"\"\"tiled\"\"\"\n",
      "render.gamma = 2.5e0\nrender.label = \"a\\tb \\u00e9\"\n[pert0.shell.bic]\nid_registers = 4",
  };
  const std::string replacements = "\"'[]{}=.,#\n\\\0\xff\xc3 -+e_"s;  // with a NUL
  const ParamRegistry prototype = make_registry();
  std::size_t loaded = 0, rejected = 0;
  const auto attempt = [&](const std::string& text) {
    ParamRegistry r = prototype;
    try {
      r.load_toml_string(text, "fuzz.toml");
      ++loaded;
    } catch (const InputError& e) {
      ++rejected;
      EXPECT_FALSE(e.message().empty());
    } catch (const std::exception& e) {
      ADD_FAILURE() << "unexpected " << e.what() << " for: " << text;
    }
  };
  for (const std::string& s : snippets) {
    for (std::size_t cut = 0; cut <= s.size(); ++cut) attempt(s.substr(0, cut));
    for (std::size_t i = 0; i < s.size(); ++i) {
      for (char c : replacements) {
        std::string mutated = s;
        mutated[i] = c;
        attempt(mutated);
      }
    }
  }
  std::mt19937 rng(1983);  // fixed seed: the same strings every run
  const std::string alphabet = "ab.=[]{}\"' \n#0123456789,\\tfrue-+:";
  for (int n = 0; n < 3000; ++n) {
    std::string text(rng() % 40, ' ');
    for (char& c : text) c = alphabet[rng() % alphabet.size()];
    attempt(text);
  }
  std::cout << "fuzz: " << loaded << " loaded, " << rejected << " rejected with InputError\n";
  EXPECT_GT(rejected, 1000u);
}

TEST(ParamRegistry, MalformedOverridesNeverCrash) {
  std::mt19937 rng(1985);
  const std::string alphabet = "render.order=tiled \"'\\0xvax.fp_add_time1us";
  const ParamRegistry prototype = make_registry();
  for (int n = 0; n < 3000; ++n) {
    std::string text(rng() % 30, ' ');
    for (char& c : text) c = alphabet[rng() % alphabet.size()];
    ParamRegistry r = prototype;
    try {
      r.apply_override(text);
    } catch (const InputError&) {
    } catch (const std::exception& e) {
      ADD_FAILURE() << "unexpected " << e.what() << " for: " << text;
    }
  }
}

}  // namespace
}  // namespace rtsim::params
