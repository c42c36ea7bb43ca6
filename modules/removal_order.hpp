#pragma once
// The order SystemC unregisters a machine's modules in when they are destroyed after the run.
// SystemC 2.3.4 finds a module it removes by looking from the front of its module registry and
// moves the last one into its place. A machine's modules are destroyed newest first (C++
// destroys in the reverse order of making), so each removal looked through every module still
// alive: quadratic, 2.4 G instructions (13% of the process) for the 28,000 modules of a 64 x 64
// ullner-array after its run, 0.15 G at 32 x 32.
//
// Modules made before all of a machine's others and destroyed before all of them fix that:
// removing the first moves the newest module to the front, and from then each removal finds its
// module within the first few and moves the next newest there. SystemC's kernel makes a module
// of its own when the simulation starts (after the machine's) and keeps it to the end: it takes
// the front once the first of them goes, so there are a few (kFront), each taking the place of
// one such module. RemovalOrder holds them; its Release, declared after the machine's last
// module, destroys them when the machine's modules start to go. Nothing else changes: they have
// no process, port or statistic, and `rtsim describe` leaves them out (kKind). Used by
// ullner-array (thousands of modules).
#include <array>
#include <memory>
#include <systemc>

namespace rtsim::modules {

class RemovalOrder {
 public:
  /// What its modules' kind() says, for whoever lists a machine's modules.
  static constexpr const char* kKind = "rtsim_removal_order";
  /// Its modules: the kernel's modules made after the machine's that this absorbs, plus one.
  static constexpr std::size_t kFront = 4;

  /// Makes its modules: before the machine's first module.
  RemovalOrder();
  ~RemovalOrder();
  RemovalOrder(const RemovalOrder&) = delete;
  RemovalOrder& operator=(const RemovalOrder&) = delete;

  /// Destroys its modules, first made first (once): the modules made after them are then each
  /// found among the first few.
  void release();

  /// Releases `order` when it goes out of scope: declare it after the machine's last module.
  class Release {
   public:
    explicit Release(RemovalOrder& order) : order_(order) {}
    ~Release() { order_.release(); }
    Release(const Release&) = delete;
    Release& operator=(const Release&) = delete;

   private:
    RemovalOrder& order_;
  };

 private:
  std::array<std::unique_ptr<sc_core::sc_module>, kFront> front_;
};

}  // namespace rtsim::modules
