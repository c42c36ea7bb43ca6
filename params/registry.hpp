#pragma once
// The parameter registry: every tunable value of a run, named by its SystemC hierarchical name
// ("pert0.shell.bic.id_registers"), with its default, unit, description and source (a seed line or
// "assumption: <why>"). Values are layered: the declared defaults, then config files (TOML), then
// `-p name=value` overrides; each value remembers where it was last set.
//
//   ParamRegistry params;
//   params.declare({.name = "peripheral.grid.divisions", .kind = ParamKind::kInt,
//                   .default_value = "11", .min = "1", .max = "256", .unit = "cells per axis",
//                   .description = "grid subdivisions along each axis",
//                   .source = "seed 000 L654"});
//   params.load_toml_file("machine.toml");            // [peripheral.grid] divisions = 8
//   params.apply_override("peripheral.grid.divisions=16");
//   params.get_int("peripheral.grid.divisions");       // 16, where_set "-p"
//
// Bad input (config files, -p) throws rtsim::InputError naming file, line, the parameter, what
// was expected and the closest known names. Misuse by code (undeclared name, wrong getter, bad
// declaration) throws std::logic_error.
#include <cstddef>
#include <cstdint>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

namespace rtsim::params {

enum class ParamKind { kInt, kDouble, kBool, kString, kTime, kFrequency, kBitRate, kDataSize };

/// "int", "double", "bool", "string", "time", "frequency", "bitrate", "datasize".
std::string_view kind_name(ParamKind kind);

/// A value as stored. Unit kinds hold a double in their SI base unit (s, Hz, bit/s, bit).
using ParamValue = std::variant<bool, std::int64_t, double, std::string>;

/// What code declares. Default and bounds are text written as in a config file ("400 ns", "11",
/// "true", "scanline") and are parsed by the kind when declared.
struct ParamSpec {
  std::string name{};  ///< dot-separated segments of letters, digits and '_'
  ParamKind kind = ParamKind::kInt;
  std::string default_value{};
  std::string min{};                   ///< inclusive lower bound, "" for none (numbers and units)
  std::string max{};                   ///< inclusive upper bound, "" for none
  std::vector<std::string> allowed{};  ///< strings only: the allowed values; empty allows any
  std::string unit{};                  ///< int/double only: what is counted ("pixels", "words")
  std::string description{};
  std::string source{};  ///< "seed 000 L654" or "assumption: <why>"
  /// The name's first segment is a class of modules (declare_family): the parameter may also be
  /// set for one instance, whose name replaces the class ("pert3.shell.bic.id_registers" beside
  /// "pert.shell.bic.id_registers"); the instance's value wins.
  bool per_instance = false;
  /// The image depends on it: the machine's functional twin (or the scene's generation) reads
  /// it. Any other parameter leaves the image byte-identical (DESIGN.md "Deterministic";
  /// tests/image_params_test.cpp), so a sweep renders the image once for the points that differ
  /// only in others (docs/sweeps.md).
  bool affects_image = false;
};

/// Modules of one class that share its parameters (DESIGN.md "Configuration"): a parameter
/// declared under the class ("pert.shell.clock") sets every instance, an instance's name
/// ("pert3.shell.clock") sets that one only.
struct InstanceFamily {
  std::string cls{};  ///< the class's first name segment: "pert", "broadcast"
  /// Named instances ("shade_bus", "shell_bus"); empty: numbered ones, cls0, cls1, ...
  std::vector<std::string> members{};
  /// Numbered instances: the int parameter that says how many are built ("pert_count").
  std::string count_param{};
};

/// One row of `rtsim list params` and of the parameter snapshot in stats.json.
struct ParamEntry {
  std::string name{};
  ParamKind kind = ParamKind::kInt;
  ParamValue value{};          ///< typed; unit kinds in `unit`
  std::string value_text{};    ///< as a user would write it: "400 ns", "11", "true"
  std::string default_text{};  ///< the default, written the same way
  std::string unit{};          ///< the declared unit; for unit kinds the SI base unit ("s")
  std::string description{};
  std::string source{};
  std::string where_set{};     ///< "default", "FILE:LINE" or "-p"
  std::string instance_of{};   ///< an instance's own value: the class parameter it overrides
  bool per_instance = false;   ///< a module's (ParamSpec::per_instance)
  bool affects_image = false;  ///< ParamSpec::affects_image
  std::string min_text{};      ///< the inclusive bounds, written as values are; "" for none
  std::string max_text{};
  std::vector<std::string> allowed{};  ///< strings: the values allowed (empty: any)
};

namespace detail {
/// The registry's record of one declared parameter (bounds and default parsed once).
struct Param {
  ParamSpec spec;
  ParamValue default_value{};
  ParamValue value{};
  std::optional<ParamValue> min{};
  std::optional<ParamValue> max{};
  std::string where_set = "default";
  mutable bool read = false;  ///< a getter asked for it (unread())
  std::string instance_of{};  ///< an instance's own value: the class parameter's name
};
}  // namespace detail

class ParamRegistry {
 public:
  /// Adds a parameter at its default. std::logic_error for a malformed or duplicate name, a name
  /// that is a prefix of another (TOML could not hold both), an `allowed` list or bound the kind
  /// does not take, or a default or bound that does not parse or is out of range.
  void declare(ParamSpec spec);

  bool contains(std::string_view name) const;
  /// Whether the image depends on `name` (ParamSpec::affects_image; an instance's name answers
  /// for its class). false for an undeclared name.
  bool affects_image(std::string_view name) const;

  /// The class path of a module's instance path ("pert3.shell" -> "pert.shell", "shell_bus" ->
  /// "broadcast"); the path itself if its first segment is no family's member.
  std::string class_path(std::string_view path) const;
  /// Declares a class of modules whose per_instance parameters may be set per instance.
  void declare_family(InstanceFamily family);
  /// After every layer is applied: InputError for a value set on a numbered instance the run
  /// does not build (pert5.* with pert_count = 4), naming where it was set.
  void check_instances() const;

  /// Who reads this registry (a machine's name, "the functional renderer") and the names that
  /// exist elsewhere (another machine, the functional renderer) but that it does not read.
  /// Setting one of those from a config file or -p is an InputError saying it is not used, with
  /// the closest names that are (or `listing`, the command that lists them): a value nobody
  /// reads must not pass for a setting.
  void set_user(std::string user, std::string listing,
                std::vector<std::string> names_used_elsewhere);
  std::size_t size() const { return params_.size(); }

  /// Layers a TOML config on top. Nested tables and dotted keys are the same name:
  /// `[peripheral.grid] divisions = 11` sets "peripheral.grid.divisions". Numbers for int and
  /// double kinds, true/false for bool, strings for string kinds and for values with units.
  /// Everything is checked before anything is set, so a bad file changes nothing.
  void load_toml_file(const std::string& path);
  /// The same for text in memory; `origin` names it in errors and where_set ("preset x" -> "preset
  /// x:12").
  void load_toml_string(std::string_view text, const std::string& origin);
  /// `-p name=value`: the value is read by the parameter's kind; it may be quoted ('x' or "x").
  void apply_override(std::string_view assignment);

  // Typed getters. std::logic_error if the name is undeclared or has another kind. An instance's
  // name ("pert3.shell.clock") gives its own value if one was set, else its class's.
  std::int64_t get_int(std::string_view name) const;
  double get_double(std::string_view name) const;
  bool get_bool(std::string_view name) const;
  const std::string& get_string(std::string_view name) const;
  double get_time_s(std::string_view name) const;
  std::int64_t get_time_ps(std::string_view name) const;  ///< exact: checked when set
  double get_frequency_hz(std::string_view name) const;
  double get_bitrate_bps(std::string_view name) const;
  double get_data_size_bits(std::string_view name) const;
  /// "default", "FILE:LINE" or "-p".
  /// The value `name` reads, written as list() writes it: one text per value, so "1 us" and
  /// "1000 ns" give the same text (a sweep compares its points by it).
  std::string value_text(std::string_view name) const;
  const std::string& where_set(std::string_view name) const;

  /// Every parameter, sorted by name: each class parameter once, and the instance values set.
  std::vector<ParamEntry> list() const;

  /// The declared parameters no getter has read yet, sorted. After a run, a machine that
  /// declares only what it reads leaves this empty (tests/unused_param_test.cpp checks it).
  std::vector<std::string> unread() const;

 private:
  const detail::Param& find(std::string_view name, ParamKind kind) const;
  /// The value `name` reads: its own, an instance's set value, or its class's; nullptr if none.
  const detail::Param* resolve(std::string_view name) const;
  static bool is_member(const InstanceFamily& f, std::string_view first_segment);
  /// The class parameter `name` is an instance of ("pert3.x" -> "pert.x"), or "".
  std::string class_of(std::string_view name) const;
  detail::Param& find_for_input(std::string_view name, const std::string& file, std::size_t line);

  std::map<std::string, detail::Param, std::less<>> params_;
  std::string user_;
  std::string listing_ = "rtsim list params";
  std::vector<std::string> used_elsewhere_;  ///< sorted
  std::vector<InstanceFamily> families_;
};

}  // namespace rtsim::params
