#pragma once
// A generic payload on the stack carrying an extension on the stack: the payload's destructor
// frees every extension still set on it, so an exception that unwinds both (a time overflow deep
// in a chain of modules) would free memory that was never allocated. The guard clears the
// extension when it goes out of scope, however that happens.
#include <tlm>

namespace rtsim::modules {

template <class Extension>
class ClearExtensionOnExit {
 public:
  ClearExtensionOnExit(tlm::tlm_generic_payload& gp, Extension& ext) : gp_(gp), ext_(ext) {}
  ~ClearExtensionOnExit() {
    if (gp_.template get_extension<Extension>()) gp_.clear_extension(&ext_);
  }
  ClearExtensionOnExit(const ClearExtensionOnExit&) = delete;
  ClearExtensionOnExit& operator=(const ClearExtensionOnExit&) = delete;

 private:
  tlm::tlm_generic_payload& gp_;
  Extension& ext_;
};

}  // namespace rtsim::modules
