#pragma once
// Classes of module instances: the PERTs' shell processors pert0.shell ... pert7.shell are one
// class, pert*.shell; an array's nodes node0 ... node255 are node*. A class with many instances
// would flood a table with columns whose names change meaning with the machine's size (node16
// is another node on a 4x4 array than on an 8x8), so stats.json also gives each class's
// aggregates (`module_classes`), and sweep tables and reports use them.
//
//   module_classes: {CLASS: {instances, KEY: {min, mean, max, sum, max_instance}}}
//
// KEY is each number a module of the class reports (`queue.mean_occupancy` for nested ones;
// arrays such as utilization_windows are left out), over the instances that report it.
// Used by MachineRun (stats.json) and the sweep's results table.
#include <cstddef>
#include <nlohmann/json.hpp>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace rtsim::modules {

/// A class of more instances than this is shown as its aggregates, not instance by instance, in
/// a sweep's results table and a run's report (a 16 x 16 array's nodes, links and queues as
/// instances were 19,000 columns, 2,688 report rows).
inline constexpr std::size_t kInstancesShownUpTo = 16;

/// The class of a module's name: the trailing digits of each dotted part become "*"
/// ("node12.link_e" -> "node*.link_e", "pert3.shell.bic" -> "pert*.shell.bic").
std::string instance_class(std::string_view name);

/// A module's numbers, by dotted key, in its order (nested objects flattened; arrays and
/// non-numbers left out).
std::vector<std::pair<std::string, double>> numeric_leaves(const nlohmann::ordered_json& module);

/// stats.json `module_classes` of stats.json `modules`: every class of two instances or more.
nlohmann::ordered_json class_aggregates(const nlohmann::ordered_json& modules);

}  // namespace rtsim::modules
