#include "modules/module_params.hpp"

#include "modules/sim_time.hpp"

namespace rtsim::modules {

namespace {
std::string join(const std::string& path, std::string_view name) {
  return path.empty() ? std::string(name) : path + "." + std::string(name);
}
}  // namespace

ParamDecls ParamDecls::sub(std::string_view child) const {
  ParamDecls d{*registry_, join(path_, child)};
  d.affects_image_ = affects_image_;
  return d;
}

void ParamDecls::declare(params::ParamSpec spec) const {
  spec.name = join(path_, spec.name);
  spec.per_instance = per_instance_;
  spec.affects_image = spec.affects_image || affects_image_;
  registry_->declare(std::move(spec));
}

void ParamDecls::time(std::string name, std::string value, std::string description,
                      std::string source) const {
  declare({.name = std::move(name),
           .kind = params::ParamKind::kTime,
           .default_value = std::move(value),
           .min = "0 s",
           .description = std::move(description),
           .source = std::move(source)});
}

void ParamDecls::count(std::string name, std::string value, std::string min, std::string max,
                       std::string unit, std::string description, std::string source) const {
  declare({.name = std::move(name),
           .kind = params::ParamKind::kInt,
           .default_value = std::move(value),
           .min = std::move(min),
           .max = std::move(max),
           .unit = std::move(unit),
           .description = std::move(description),
           .source = std::move(source)});
}

ModuleParams ModuleParams::sub(std::string_view child) const {
  return {*registry_, join(path_, child)};
}

std::string ModuleParams::full(std::string_view name) const { return join(path_, name); }

std::int64_t ModuleParams::get_int(std::string_view name) const {
  return registry_->get_int(full(name));
}
std::size_t ModuleParams::get_count(std::string_view name) const {
  return static_cast<std::size_t>(std::max<std::int64_t>(0, registry_->get_int(full(name))));
}
double ModuleParams::get_double(std::string_view name) const {
  return registry_->get_double(full(name));
}
bool ModuleParams::get_bool(std::string_view name) const { return registry_->get_bool(full(name)); }
const std::string& ModuleParams::get_string(std::string_view name) const {
  return registry_->get_string(full(name));
}
sc_core::sc_time ModuleParams::get_time(std::string_view name) const {
  return from_ps(registry_->get_time_ps(full(name)));
}
double ModuleParams::get_bitrate_bps(std::string_view name) const {
  return registry_->get_bitrate_bps(full(name));
}
double ModuleParams::get_frequency_hz(std::string_view name) const {
  return registry_->get_frequency_hz(full(name));
}

}  // namespace rtsim::modules
