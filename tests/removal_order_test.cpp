// The order SystemC unregisters a machine's modules in after the run (modules/removal_order.hpp):
// with a RemovalOrder made before them and released before they go, the module destroyed next
// (the newest still alive) is always among the first few of SystemC's list, where SystemC's
// search from the front finds it at once; without one it is the last of the list, behind every
// other. SystemC's list of top-level objects keeps and removes its entries as its module registry
// does (appended when made; the last moved into a removed one's place), so this reads the order
// from it.
#include "modules/removal_order.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <memory>
#include <optional>
#include <string>
#include <systemc>
#include <vector>

#include "tests/systemc_test_support.hpp"

namespace {

using rtsim::modules::RemovalOrder;

struct Part : sc_core::sc_module {
  explicit Part(const sc_core::sc_module_name& n) : sc_core::sc_module(n) {}
};

/// Where `m` stands in SystemC's list of top-level objects (its size if it is not there).
std::size_t place_of(const sc_core::sc_object* m) {
  const auto& all = sc_core::sc_get_top_level_objects();
  return static_cast<std::size_t>(std::find(all.begin(), all.end(), m) - all.begin());
}

/// Makes `n` modules (after `order`, if given), runs the simulation and destroys them newest
/// first; returns the place in SystemC's list of each as it was destroyed.
std::vector<std::size_t> places_when_destroyed(bool with_order, int n) {
  std::optional<RemovalOrder> order;
  if (with_order) order.emplace();
  std::vector<std::unique_ptr<Part>> parts;
  for (int i = 0; i < n; ++i)
    parts.push_back(std::make_unique<Part>(("part" + std::to_string(i)).c_str()));
  sc_core::sc_start();  // SystemC makes a module of its own here, after these
  if (order) order->release();
  std::vector<std::size_t> places;
  while (!parts.empty()) {
    places.push_back(place_of(parts.back().get()));
    parts.pop_back();
  }
  return places;
}

TEST(RemovalOrder, TheNewestModuleIsAlwaysAmongTheFirst) {
  EXPECT_EQ(rtsim::test::run_in_child([] {
              const std::vector<std::size_t> places = places_when_destroyed(true, 200);
              for (std::size_t k = 0; k < places.size(); ++k)
                EXPECT_LE(places[k], RemovalOrder::kFront) << "the " << k << "th destroyed";
              // Its own modules are gone, and listed under their kind until then.
              for (const auto* o : sc_core::sc_get_top_level_objects())
                EXPECT_NE(std::string(o->kind()), RemovalOrder::kKind) << o->name();
              return 0;
            }),
            0);
}

TEST(RemovalOrder, WithoutItTheNewestIsBehindEveryOther) {
  // What it fixes: SystemC's search from the front looked through all the others each time.
  EXPECT_EQ(rtsim::test::run_in_child([] {
              const std::vector<std::size_t> places = places_when_destroyed(false, 200);
              EXPECT_GE(places.front(), 199u);
              EXPECT_GE(places[100], 99u);
              return 0;
            }),
            0);
}

TEST(RemovalOrder, ItsReleaseGoesWithItsScope) {
  EXPECT_EQ(rtsim::test::run_in_child([] {
              RemovalOrder order;
              const auto count_own = [] {
                return std::count_if(sc_core::sc_get_top_level_objects().begin(),
                                     sc_core::sc_get_top_level_objects().end(),
                                     [](const sc_core::sc_object* o) {
                                       return std::string(o->kind()) == RemovalOrder::kKind;
                                     });
              };
              EXPECT_EQ(count_own(), static_cast<long>(RemovalOrder::kFront));
              { const RemovalOrder::Release release{order}; }
              EXPECT_EQ(count_own(), 0);
              order.release();  // a second time changes nothing
              EXPECT_EQ(count_own(), 0);
              return 0;
            }),
            0);
}

}  // namespace
