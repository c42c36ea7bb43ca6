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

  /// `spec.name` is relative to the module.
  void declare(params::ParamSpec spec) const;
  /// A time of at least 0 s ("400 ns").
  void time(std::string name, std::string value, std::string description, std::string source) const;
  /// An integer count in [min, max] of `unit`.
  void count(std::string name, std::string value, std::string min, std::string max,
             std::string unit, std::string description, std::string source) const;

 private:
  params::ParamRegistry* registry_;
  std::string path_;
  bool per_instance_;
};

/// Reading: a module's instance path in the registry.
class ModuleParams {
 public:
  ModuleParams(const params::ParamRegistry& registry, std::string path)
      : registry_(&registry), path_(std::move(path)) {}
  ModuleParams sub(std::string_view child) const;
  const std::string& path() const { return path_; }
  const params::ParamRegistry& registry() const { return *registry_; }

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
