#pragma once
// A module's parameters (DESIGN.md "The three layers", "Configuration"): every module of the
// kit and of a machine declares its own, named relative to itself, in a static
// `declare_params(const ParamDecls&, ...)` beside the constructor that reads them through
// `ModuleParams`. There is no second list of names or defaults anywhere: the defaults are the
// machine preset's, given once where the machine declares its module tree.
//
//   declare: under the module's class path   ("pert.shell.bic" -> pert.shell.bic.id_registers)
//   read:    under its instance path         ("pert3.shell.bic"); an instance's own value
//            (-p pert3.shell.bic.id_registers=2) wins over its class's (params::InstanceFamily)
//
// Used by every machine (gaudet-pert, ullner-peripheral, vax-750) and the next ones.
#include <cstdint>
#include <string>
#include <string_view>
#include <systemc>

#include "modules/param.hpp"
#include "params/registry.hpp"

namespace rtsim::modules {

/// Declaring: a module's class path in the registry.
class ParamDecls {
 public:
  /// `per_instance`: its parameters may be set per instance of its class (a module's); false
  /// for a machine's own, top-level ones (path "").
  ParamDecls(params::ParamRegistry& registry, std::string path, bool per_instance = true)
      : registry_(&registry), path_(std::move(path)), per_instance_(per_instance) {}
  /// A child module's path ("pert.shell" -> "pert.shell.bic"); its parameters are per instance.
  ParamDecls sub(std::string_view child) const;
  const std::string& path() const { return path_; }
  params::ParamRegistry& registry() const { return *registry_; }
  /// The same declarations marked as parameters the image depends on (ParamSpec::affects_image):
  /// those the machine's functional twin reads.
  ParamDecls affecting_image() const {
    ParamDecls d = *this;
    d.affects_image_ = true;
    return d;
  }

  /// `spec.name` is relative to the module.
  void declare(params::ParamSpec spec) const;
  /// Declares a typed parameter (modules/param.hpp), read back with ModuleParams::get.
  template <class T>
  void add(const Param<T>& p) const {
    declare(p.spec());
  }
  /// A time of at least 0 s ("400 ns").
  void time(std::string name, std::string value, std::string description, std::string source) const;
  /// An integer count in [min, max] of `unit`.
  void count(std::string name, std::string value, std::string min, std::string max,
             std::string unit, std::string description, std::string source) const;

 private:
  params::ParamRegistry* registry_;
  std::string path_;
  bool per_instance_;
  bool affects_image_ = false;
};

/// Reading: a module's instance path in the registry.
class ModuleParams {
 public:
  ModuleParams(const params::ParamRegistry& registry, std::string path)
      : registry_(&registry), path_(std::move(path)) {}
  ModuleParams sub(std::string_view child) const;
  const std::string& path() const { return path_; }
  const params::ParamRegistry& registry() const { return *registry_; }

  /// The value of a typed parameter this module declared (modules/param.hpp).
  sc_core::sc_time get(const TimeParam& p) const { return get_time(p.name()); }
  std::size_t get(const CountParam& p) const { return get_count(p.name()); }
  std::int64_t get(const IntParam& p) const { return get_int(p.name()); }
  double get(const RealParam& p) const { return get_double(p.name()); }
  bool get(const FlagParam& p) const { return get_bool(p.name()); }
  const std::string& get(const ChoiceParam& p) const { return get_string(p.name()); }
  Frequency get(const FrequencyParam& p) const { return {get_frequency_hz(p.name())}; }
  BitRate get(const BitRateParam& p) const { return {get_bitrate_bps(p.name())}; }
  DataSize get(const DataSizeParam& p) const {
    return {registry_->get_data_size_bits(full(p.name()))};
  }

  /// A parameter's full name ("array" + "subvolumes" -> "array.subvolumes"), for messages.
  std::string path_of(std::string_view name) const { return full(name); }
  /// Where its value was set ("default", "FILE:LINE", "-p"): for an error about it.
  std::string where_set(std::string_view name) const { return registry_->where_set(full(name)); }

  std::int64_t get_int(std::string_view name) const;
  /// An int parameter declared with min >= 0.
  std::size_t get_count(std::string_view name) const;
  double get_double(std::string_view name) const;
  bool get_bool(std::string_view name) const;
  const std::string& get_string(std::string_view name) const;
  /// Exact in picoseconds (the simulation's resolution).
  sc_core::sc_time get_time(std::string_view name) const;
  double get_frequency_hz(std::string_view name) const;
  double get_bitrate_bps(std::string_view name) const;

 private:
  std::string full(std::string_view name) const;
  const params::ParamRegistry* registry_;
  std::string path_;
};

}  // namespace rtsim::modules
