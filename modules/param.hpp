#pragma once
// A module's parameter as a typed definition (after VCML's property<T> and SCC's cci_param):
// its name relative to the module, default, bounds, unit, description and source are written
// once, in one constant, and the module declares and reads it through that constant, as the
// C++ type it uses. No parameter name is written twice:
//
//   static inline const modules::TimeParam kWriteTime{{.name = "write_time",
//       .default_value = "1 us", .description = "...", .source = "assumption: ..."}};
//   static void declare_params(const modules::ParamDecls& d) { d.add(kWriteTime); }
//   FrameBuffer(...) : write_time_(params_.get(kWriteTime)) {}     // an sc_time
//
// The kind follows the type: TimeParam (sc_time, exact in picoseconds; at least 0 s unless
// bounded otherwise), CountParam (std::size_t; at least 0), IntParam, RealParam, FlagParam,
// ChoiceParam (a string, `allowed` values), FrequencyParam (Hz), BitRateParam (bit/s) and
// DataSizeParam (bits).
// Used by the kit's modules and every machine's.
#include <cstdint>
#include <string>
#include <systemc>
#include <utility>

#include "params/registry.hpp"

namespace rtsim::modules {

/// A frequency read from a FrequencyParam, in Hz.
struct Frequency {
  double hz = 0.0;
};
/// A bit rate read from a BitRateParam, in bit/s.
struct BitRate {
  double bps = 0.0;
};
/// A size of data read from a DataSizeParam, in bits.
struct DataSize {
  double bits = 0.0;
  double bytes() const { return bits / 8.0; }
};

namespace detail {
/// The registry kind a type is read as, and the lower bound it has unless a spec gives one.
template <params::ParamKind Kind>
struct KindOf {
  static constexpr params::ParamKind kKind = Kind;
  static constexpr const char* kMin = "";
};
template <class T>
struct ParamKindOf;
template <>
struct ParamKindOf<sc_core::sc_time> : KindOf<params::ParamKind::kTime> {
  static constexpr const char* kMin = "0 s";
};
template <>
struct ParamKindOf<std::size_t> : KindOf<params::ParamKind::kInt> {
  static constexpr const char* kMin = "0";
};
template <>
struct ParamKindOf<std::int64_t> : KindOf<params::ParamKind::kInt> {};
template <>
struct ParamKindOf<double> : KindOf<params::ParamKind::kDouble> {};
template <>
struct ParamKindOf<bool> : KindOf<params::ParamKind::kBool> {};
template <>
struct ParamKindOf<std::string> : KindOf<params::ParamKind::kString> {};
template <>
struct ParamKindOf<Frequency> : KindOf<params::ParamKind::kFrequency> {};
template <>
struct ParamKindOf<BitRate> : KindOf<params::ParamKind::kBitRate> {};
template <>
struct ParamKindOf<DataSize> : KindOf<params::ParamKind::kDataSize> {};
}  // namespace detail

/// A parameter read as a T: `spec` with its kind set by T (and T's lower bound if it gives
/// none); its name is relative to the module that declares it.
template <class T>
class Param {
 public:
  /// (Defined in param.cpp, for the types below.)
  explicit Param(params::ParamSpec spec);
  const params::ParamSpec& spec() const { return spec_; }
  const std::string& name() const { return spec_.name; }

 private:
  params::ParamSpec spec_;
};

extern template class Param<sc_core::sc_time>;
extern template class Param<std::size_t>;
extern template class Param<std::int64_t>;
extern template class Param<double>;
extern template class Param<bool>;
extern template class Param<std::string>;
extern template class Param<Frequency>;
extern template class Param<BitRate>;
extern template class Param<DataSize>;

using TimeParam = Param<sc_core::sc_time>;
using CountParam = Param<std::size_t>;
using IntParam = Param<std::int64_t>;
using RealParam = Param<double>;
using FlagParam = Param<bool>;
using ChoiceParam = Param<std::string>;
using FrequencyParam = Param<Frequency>;
using BitRateParam = Param<BitRate>;
using DataSizeParam = Param<DataSize>;

}  // namespace rtsim::modules
