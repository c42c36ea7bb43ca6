#include "modules/param.hpp"

namespace rtsim::modules {

template <class T>
Param<T>::Param(params::ParamSpec spec) : spec_(std::move(spec)) {
  spec_.kind = detail::ParamKindOf<T>::kKind;
  if (spec_.min.empty()) {
    // A swap, not an assignment: GCC 12 warns falsely (-Wrestrict) on assigning a short
    // literal to an empty string.
    std::string min(detail::ParamKindOf<T>::kMin);
    spec_.min.swap(min);
  }
}

template class Param<sc_core::sc_time>;
template class Param<std::size_t>;
template class Param<std::int64_t>;
template class Param<double>;
template class Param<bool>;
template class Param<std::string>;
template class Param<Frequency>;
template class Param<BitRate>;
template class Param<DataSize>;

}  // namespace rtsim::modules
