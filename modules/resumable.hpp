#pragma once
// A processor's program as a C++20 coroutine that an SC_METHOD or an event queue runs: the
// program keeps the shape of a thread's loop (it waits in the middle of a function, several
// calls deep), but it has no stack of its own. Where a thread would wait(), the program
// co_awaits a wait that asks to be run again -- SystemC to trigger its method (next_trigger), or
// a WakeQueue to wake it (modules/wake_queue.hpp) -- and suspends; the next activation resumes
// it where it stopped. A thread's wait is a switch of stacks through SystemC's scheduler; a
// program on a queue that runs ahead of SystemC is resumed by a function call (gaudet-pert's
// PERT processors wait some 450,000 times a frame at 1 PERT).
//
// `Resumable` is a function of the program that may wait: calling it makes its frame, and
// `co_await`ing it runs it to its end, resuming the caller then (symmetric transfer: no stack
// grows however deep the calls). Frames come from a free list by size (FramePool): a program
// calls such functions tens of times a ray.
//
// `ResumableHost` holds a program and the point where it waits: the method (or the queue's
// client) calls resume() at each activation. A wait is an awaitable whose await_suspend calls
// host.suspended(h) and then asks for the next activation (next_trigger in the method's
// context, or the queue's wake_at). An exception in the program (simulated time running out)
// leaves resume(), as a thread's would leave its thread.
// Used through modules/resumable_process.hpp by gaudet-pert's PERT processors and Broadcast
// Processors (pert_processor.hpp, broadcast_processor.hpp).
#include <coroutine>
#include <cstddef>
#include <exception>
#include <new>
#include <utility>

namespace rtsim::modules {

/// Coroutine frames by size, reused: a frame freed is the next of its size made (a list through
/// the free frames themselves, by size class). Programs run in SystemC's thread only (one
/// simulation a process).
class FramePool {
 public:
  static void* get(std::size_t n) {
    const std::size_t c = (n + kGrain - 1) / kGrain;
    if (c >= kClasses || free_[c] == nullptr) return fresh(c, n);
    Free* f = free_[c];
    free_[c] = f->next;
    return f;
  }
  static void put(void* p, std::size_t n) noexcept {
    const std::size_t c = (n + kGrain - 1) / kGrain;
    if (c >= kClasses) {
      ::operator delete(p);
      return;
    }
    free_[c] = new (p) Free{free_[c]};
  }

 private:
  struct Free {
    Free* next;
  };
  static constexpr std::size_t kGrain = 64;
  static constexpr std::size_t kClasses = 64;  ///< frames up to 4 KiB are pooled
  /// A frame of `n` bytes (size class `c`) from the heap.
  static void* fresh(std::size_t c, std::size_t n);
  inline static Free* free_[kClasses] = {};
};

class [[nodiscard]] Resumable {
 public:
  struct promise_type {
    std::coroutine_handle<> caller;
    std::exception_ptr error;
    Resumable get_return_object() {
      return Resumable(std::coroutine_handle<promise_type>::from_promise(*this));
    }
    std::suspend_always initial_suspend() noexcept { return {}; }
    struct Final {
      bool await_ready() noexcept { return false; }
      std::coroutine_handle<> await_suspend(std::coroutine_handle<promise_type> h) noexcept {
        const std::coroutine_handle<> c = h.promise().caller;
        return c ? c : std::noop_coroutine();
      }
      void await_resume() noexcept {}
    };
    Final final_suspend() noexcept { return {}; }
    void return_void() noexcept {}
    void unhandled_exception() noexcept { error = std::current_exception(); }
    static void* operator new(std::size_t n) { return FramePool::get(n); }
    static void operator delete(void* p, std::size_t n) noexcept { FramePool::put(p, n); }
  };
  using Handle = std::coroutine_handle<promise_type>;

  Resumable() = default;
  explicit Resumable(Handle h) : h_(h) {}
  Resumable(Resumable&& o) noexcept : h_(std::exchange(o.h_, {})) {}
  Resumable& operator=(Resumable&& o) noexcept {
    if (this != &o) {
      if (h_) h_.destroy();
      h_ = std::exchange(o.h_, {});
    }
    return *this;
  }
  Resumable(const Resumable&) = delete;
  Resumable& operator=(const Resumable&) = delete;
  ~Resumable() {
    if (h_) h_.destroy();
  }

  // Awaited: runs to its end, then the caller goes on (an exception passes to the caller).
  bool await_ready() const noexcept { return false; }
  std::coroutine_handle<> await_suspend(std::coroutine_handle<> caller) noexcept {
    h_.promise().caller = caller;
    return h_;
  }
  void await_resume() const {
    if (h_.promise().error) std::rethrow_exception(h_.promise().error);
  }

  Handle handle() const { return h_; }

 private:
  Handle h_;
};

/// The program an SC_METHOD runs, and where it waits.
class ResumableHost {
 public:
  /// Elaboration: the program (not started: the method's first activation starts it).
  void start(Resumable program) {
    program_ = std::move(program);
    at_ = program_.handle();
  }
  /// The method's activation: runs the program until it waits again or ends. Returns whether it
  /// resumed a wait (the first activation starts it instead).
  bool resume() {
    const bool from_wait = started_;
    started_ = true;
    if (!at_) return from_wait;  // ended: nothing triggers the method again
    const std::coroutine_handle<> h = std::exchange(at_, {});
    h.resume();
    if (program_.handle().done()) {
      at_ = {};
      if (program_.handle().promise().error)
        std::rethrow_exception(program_.handle().promise().error);
    }
    return from_wait;
  }
  /// A wait's await_suspend: the program goes on from `h` at the next activation.
  void suspended(std::coroutine_handle<> h) { at_ = h; }
  bool ended() const { return program_.handle() && program_.handle().done(); }

 private:
  Resumable program_;
  std::coroutine_handle<> at_;
  bool started_ = false;
};

}  // namespace rtsim::modules
