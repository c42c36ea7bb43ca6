// `rtsim list scenes|machines|params`.
#include <algorithm>
#include <iomanip>
#include <iostream>

#include "app/cli.hpp"
#include "app/commands.hpp"
#include "app/configuration.hpp"
#include "common/input_error.hpp"
#include "platform/machine.hpp"
#include "scenes/scene_loader.hpp"

namespace rtsim::app {
namespace {

void list_scenes() {
  std::cout << "Built-in scenes (use as --scene builtin:NAME):\n";
  // The names' column as wide as the longest name and two spaces.
  std::size_t width = 0;
  for (const auto& info : scenes::builtin_scenes()) width = std::max(width, info.name.size());
  for (const auto& info : scenes::builtin_scenes())
    std::cout << "  " << std::left << std::setw(static_cast<int>(width + 2)) << info.name
              << info.description << "\n";
  std::cout << "Files: .nff (Haines' Neutral File Format) and .bpt (bicubic Bezier patches).\n";
}

void list_machines() {
  std::cout << "Machines (rtsim run --machine NAME; rtsim list params --machine NAME):\n";
  for (const platform::Machine* m : platform::machines())
    std::cout << "  " << std::left << std::setw(20) << m->name() << m->description() << "\n";
  std::cout << "  " << std::left << std::setw(20) << "(none)"
            << "rtsim render: the functional renderer, firmware with no timing\n";
}

void list_params(const ListArgs& args) {
  const platform::Machine* machine =
      args.machine.empty() ? nullptr : &platform::find_machine(args.machine);
  const auto registry = build_registry(args.config, machine);
  const auto entries = registry.list();
  if (args.format == "markdown") {
    std::cout << "| name | default | unit | description | source |\n|---|---|---|---|---|\n";
    for (const auto& e : entries)
      std::cout << "| `" << e.name << "` | `" << e.default_text << "` | " << e.unit << " | "
                << e.description << " | " << e.source << " |\n";
    return;
  }
  std::size_t name_w = 4, value_w = 5;
  for (const auto& e : entries) {
    name_w = std::max(name_w, e.name.size());
    value_w = std::max(value_w, e.value_text.size());
  }
  std::cout << std::left << std::setw(static_cast<int>(name_w + 2)) << "name"
            << std::setw(static_cast<int>(value_w + 2)) << "value"
            << "set by\n";
  for (const auto& e : entries) {
    std::cout << std::left << std::setw(static_cast<int>(name_w + 2)) << e.name
              << std::setw(static_cast<int>(value_w + 2)) << e.value_text << e.where_set << "\n"
              << "    " << e.description << "\n"
              << "    default " << e.default_text << (e.unit.empty() ? "" : " (" + e.unit + ")")
              << "; source: " << e.source << "\n";
  }
}

}  // namespace

int run_list(const ListArgs& args) {
  if (args.what == "scenes") list_scenes();
  if (args.what == "machines") list_machines();
  if (args.what == "params") list_params(args);
  return kExitOk;
}

}  // namespace rtsim::app
