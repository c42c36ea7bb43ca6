#pragma once
// A processor's program (modules/resumable.hpp) and what runs it: an SC_METHOD of the module
// that owns it, or, once the module has joined one as its client, a WakeQueue
// (modules/wake_queue.hpp). The module's waits ask it for their next activation (run_at); its
// method calls resume_in_method(), its Client::woken() resume_from_queue(). Either way a return
// from a wait counts as an activation of the module's process "run" (modules/activations.hpp).
// Used by gaudet-pert's PERT processors and Broadcast Processors.
#include <coroutine>
#include <cstdint>
#include <systemc>
#include <utility>

#include "modules/activations.hpp"
#include "modules/resumable.hpp"
#include "modules/sim_time.hpp"
#include "modules/wake_queue.hpp"

namespace rtsim::modules {

class ResumableProcess {
 public:
  /// Elaboration: the program (started at its first activation).
  void start(Resumable program) { host_.start(std::move(program)); }
  /// Elaboration: it runs on `queue` as the client `client` (the module), its activations
  /// counted under `owner`'s "run", as its method's would be.
  void join(WakeQueue& queue, WakeQueue::Client& client, const sc_core::sc_object& owner) {
    queue_ = &queue;
    client_ = queue.add(client);
    activations_ = &activation_count(owner, "run");
  }
  bool on_queue() const { return queue_ != nullptr; }

  /// The method's activation: the program goes on until it waits again.
  void resume_in_method() {
    if (host_.resume()) count_activation();
  }
  /// The queue's activation (Client::woken).
  void resume_from_queue() {
    if (host_.resume()) ++*activations_;
  }
  /// A wait's await_suspend: the program goes on from `h` at its next activation.
  void suspended(std::coroutine_handle<> h) { host_.suspended(h); }
  /// Its next activation at `t` (absolute, now or later): the queue's wake, or the method's
  /// next_trigger (a delay handed to SystemC counts from SystemC's own time, sim_time.hpp).
  void run_at(const sc_core::sc_time& t) {
    if (queue_ != nullptr)
      queue_->wake_at(client_, t);
    else
      sc_core::next_trigger(t - systemc_now());
  }
  /// In its method: its next activation when `e` fires.
  void run_on(const sc_core::sc_event& e) { sc_core::next_trigger(e); }
  /// On the queue: its pending wake, if any, is dropped (WakeQueue::cancel).
  void cancel() { queue_->cancel(client_); }

  /// co_await: the program stops here until the activation asked for (run_at, run_on, or a
  /// listener's wake on the queue).
  struct Suspend {
    ResumableProcess& process;
    bool await_ready() const noexcept { return false; }
    void await_suspend(std::coroutine_handle<> h) { process.suspended(h); }
    void await_resume() const noexcept {}
  };
  Suspend suspend() { return {*this}; }

 private:
  ResumableHost host_;
  WakeQueue* queue_ = nullptr;
  std::size_t client_ = 0;
  std::uint64_t* activations_ = nullptr;
};

}  // namespace rtsim::modules
