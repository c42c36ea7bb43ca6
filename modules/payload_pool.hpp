#pragma once
// Generic payloads kept for reuse. Making a tlm_generic_payload allocates its extension array
// (a slot for every extension type the program registers) and destroying one walks and frees it:
// a payload made for each message or record hop cost ullner-array's load a tenth of its
// instructions. A payload is taken for one b_transport (or one nest of them) and given back after
// it; a thread blocked in a full queue keeps its own, so threads never share one. Used by
// send_message (modules/message_channel.hpp), write_words (modules/memory.hpp) and the array's
// broadcast.
#include <memory>
#include <tlm>
#include <vector>

namespace rtsim::modules {

class PayloadPool {
 public:
  static tlm::tlm_generic_payload* take() {
    auto& free = instance().free_;
    if (free.empty()) {
      instance().all_.push_back(std::make_unique<tlm::tlm_generic_payload>());
      return instance().all_.back().get();
    }
    tlm::tlm_generic_payload* gp = free.back();
    free.pop_back();
    return gp;
  }
  static void give_back(tlm::tlm_generic_payload* gp) { instance().free_.push_back(gp); }

 private:
  static PayloadPool& instance() {
    static PayloadPool pool;
    return pool;
  }
  std::vector<std::unique_ptr<tlm::tlm_generic_payload>> all_;
  std::vector<tlm::tlm_generic_payload*> free_;
};

/// A payload from the pool for a scope, given back at its end (whoever set an extension on it
/// clears it first: modules/extension_guard.hpp).
class PooledPayload {
 public:
  PooledPayload() : gp_(PayloadPool::take()) {}
  ~PooledPayload() { PayloadPool::give_back(gp_); }
  PooledPayload(const PooledPayload&) = delete;
  PooledPayload& operator=(const PooledPayload&) = delete;
  tlm::tlm_generic_payload& operator*() const { return *gp_; }
  tlm::tlm_generic_payload* operator->() const { return gp_; }

 private:
  tlm::tlm_generic_payload* gp_;
};

}  // namespace rtsim::modules
