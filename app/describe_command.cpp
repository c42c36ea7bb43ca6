// `rtsim describe MACHINE`: the machine's module tree — each module with the parameters that set
// it and the statistics it reports — and its connections, as text and as a block diagram (DOT,
// and SVG when Graphviz's `dot` is installed). Architects look at the structure before they read
// numbers.
//
// The tree is the machine's own, not a description kept beside it: the machine is built for a
// small frame of its sample scene (or --scene), the SystemC hierarchy and the socket bindings
// are read at the end of elaboration, and the frame is run so that every statistics group the
// machine reports (stats.json `modules`) is known. Groups that are no SystemC module (a BIC, a
// queue inside a processor, the pipeline of the peripheral) hang under their parent's name.
#include <cxxabi.h>

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iostream>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <sstream>
#include <systemc>
#include <typeinfo>

#include "app/commands.hpp"
#include "app/configuration.hpp"
#include "app/output_set.hpp"
#include "app/scene_input.hpp"
#include "app/stats_json.hpp"
#include "common/input_error.hpp"
#include "common/seed_citation.hpp"
#include "common/spawn_logged.hpp"
#include "modules/removal_order.hpp"
#include "modules/wiring.hpp"
#include "platform/machine.hpp"
#include "platform/machine_registry.hpp"

namespace rtsim::app {

namespace {

/// "rtsim::platform::gaudet::ShellProcessor" -> "ShellProcessor"; templates keep their name.
std::string type_name(const sc_core::sc_object& o) {
  int status = 0;
  const char* mangled = typeid(o).name();
  std::unique_ptr<char, void (*)(void*)> d(abi::__cxa_demangle(mangled, nullptr, nullptr, &status),
                                           std::free);
  std::string n = status == 0 && d ? d.get() : mangled;
  const std::size_t lt = n.find('<');
  const std::size_t colon = n.rfind("::", lt == std::string::npos ? n.size() : lt);
  n = colon == std::string::npos ? n : n.substr(colon + 2);
  if (const auto t = n.find('<'); t != std::string::npos) n = n.substr(0, t);
  return n;
}

struct Node {
  std::string type;  ///< C++ class; "" for a statistics group that is no SystemC module
  std::vector<std::string> stats;
  std::vector<const params::ParamEntry*> params;
};

/// Reads the SystemC hierarchy and the TLM bindings at the end of elaboration.
class TreeReader : public sc_core::sc_module {
 public:
  std::map<std::string, Node> nodes;
  std::set<std::tuple<std::string, std::string, std::string>> edges;  ///< from, to, what
  std::map<std::string, std::vector<std::string>> rings;  ///< ring -> its modules in token order

  explicit TreeReader(const sc_core::sc_module_name& name) : sc_core::sc_module(name) {}

 private:
  void end_of_elaboration() override {
    std::map<const sc_core::sc_interface*, std::string> exported;  // interface -> its module
    std::vector<std::pair<std::string, const sc_core::sc_interface*>> bound;
    std::vector<const sc_core::sc_object*> todo;
    // Neither this reader nor the module that only orders the others' removal
    // (modules/removal_order.hpp) is part of the machine.
    for (const auto* o : sc_core::sc_get_top_level_objects())
      if (o != this && std::string_view(o->kind()) != modules::RemovalOrder::kKind)
        todo.push_back(o);
    while (!todo.empty()) {
      const sc_core::sc_object* o = todo.back();
      todo.pop_back();
      const std::string owner = o->get_parent_object() ? o->get_parent_object()->name() : "";
      if (dynamic_cast<const sc_core::sc_module*>(o)) {
        nodes[o->name()].type = type_name(*o);
      } else if (const auto* p = dynamic_cast<const sc_core::sc_port_base*>(o)) {
        // Initiator to target only (a target socket's backward port points the other way).
        if (std::string_view(o->kind()) == "tlm_initiator_socket")
          if (auto* i = const_cast<sc_core::sc_port_base*>(p)->get_interface())
            bound.emplace_back(owner, i);
      } else if (const auto* e = dynamic_cast<const sc_core::sc_export_base*>(o)) {
        if (std::string_view(o->kind()) == "tlm_target_socket")
          if (auto* i = const_cast<sc_core::sc_export_base*>(e)->get_interface())
            exported[i] = owner;
      }
      for (const auto* c : o->get_child_objects()) todo.push_back(c);
    }
    for (const auto& [from, i] : bound)
      if (const auto it = exported.find(i); it != exported.end())
        edges.emplace(from, it->second, "TLM");
    for (const auto& c : modules::wiring()) edges.emplace(c.from, c.to, c.what);
    for (const auto& s : modules::ring_stops()) {
      auto& order = rings[s.ring];
      if (order.size() <= s.position) order.resize(s.position + 1);
      order[s.position] = s.module;
    }
  }
};

std::string parent_of(const std::string& name) {
  const std::size_t dot = name.rfind('.');
  return dot == std::string::npos ? "" : name.substr(0, dot);
}

std::string leaf_of(const std::string& name) { return name.substr(name.rfind('.') + 1); }

std::string dot_id(const std::string& name) { return "\"" + name + "\""; }

/// A class of numbered siblings (node0 ... node4095, pert0 ... pert1023) with more than this many
/// instances is drawn as its first kDrawnInstances and one box that counts the rest: Graphviz
/// lays out a 64x64 array's 4096 nodes for minutes, and nobody reads such a picture. Up to 64
/// (the thesis's 8 x 8 array) every instance is drawn. The text tree lists every module.
constexpr std::size_t kMaxDrawnClassSize = 64;
constexpr std::size_t kDrawnInstances = 8;

/// "node12" -> {"node", 12}; a name without a number -> {name, npos}.
std::pair<std::string, std::size_t> instance_of(const std::string& leaf) {
  std::size_t digits = leaf.size();
  while (digits > 0 && std::isdigit(static_cast<unsigned char>(leaf[digits - 1]))) --digits;
  if (digits == leaf.size() || digits == 0 || leaf.size() - digits > 9)
    return {leaf, std::string::npos};
  return {leaf.substr(0, digits), std::stoul(leaf.substr(digits))};
}

std::string dot_escape(std::string s) {
  std::string out;
  for (char c : s) {
    if (c == '"' || c == '\\') out += '\\';
    out += c;
  }
  return out;
}

/// A machine's modules as describe prints and draws them.
struct ModuleTree {
  std::map<std::string, Node> nodes;                                  ///< by hierarchical name
  std::set<std::tuple<std::string, std::string, std::string>> edges;  ///< from, to, what
  std::map<std::string, std::vector<std::string>> rings;  ///< ring -> its modules in token order
  modules::UnitSchema units;                              ///< of a run's stats.json (`units`)
  std::vector<params::ParamEntry> entries;
  std::vector<const params::ParamEntry*> machine_params;  ///< those of no one module
  std::map<std::string, std::string> class_paths;         ///< module -> class path
};

/// Builds the machine on a tiny frame and reads its hierarchy, bindings, statistics and
/// parameters: each parameter belongs to the deepest module whose class path holds it
/// (pert.shell.clock: pert0.shell's, for every PERT); the rest are the machine's own.
ModuleTree read_tree(const platform::Machine& machine, const params::ParamRegistry& registry,
                     scenes::Scene& scene) {
  platform::FunctionalTwin twin = machine.make_twin(scene, registry);
  TreeReader reader("rtsim_describe");
  platform::RunOptions opts;
  opts.width = 4;  // a frame just large enough that every module works
  opts.height = 4;
  const platform::RunResult result = machine.run(scene, twin, registry, opts);
  ModuleTree tree;
  tree.nodes = reader.nodes;
  tree.edges = reader.edges;
  tree.rings = reader.rings;
  tree.units = run_units(result.units);
  auto& nodes = tree.nodes;
  if (result.stats.contains("modules"))
    for (const auto& [name, group] : result.stats["modules"].items()) {
      Node& n = nodes[name];
      for (const auto& [key, value] : group.items())
        if (key != "utilization_windows") n.stats.push_back(key);
    }
  // Every node's ancestors exist (a statistics group's parent may be no module: "pert0.queue").
  for (auto it = nodes.begin(); it != nodes.end(); ++it)
    for (std::string p = parent_of(it->first); !p.empty(); p = parent_of(p)) nodes[p];
  tree.entries = registry.list();
  for (const auto& [name, n] : nodes) tree.class_paths[name] = registry.class_path(name);
  for (const auto& e : tree.entries) {
    if (!e.instance_of.empty()) continue;  // an instance's value: shown with its class's
    if (!e.per_instance) {  // the machine's own (pert_count, broadcast.mode, render.*)
      tree.machine_params.push_back(&e);
      continue;
    }
    // The deepest class path that holds it; of equal instances the first (pert0 for pert.*).
    std::string best;
    std::size_t best_len = 0;
    for (const auto& [name, cls] : tree.class_paths) {
      if (!e.name.starts_with(cls + ".") || cls.size() <= best_len) continue;
      best = name;
      best_len = cls.size();
    }
    if (best.empty())
      tree.machine_params.push_back(&e);
    else
      nodes[best].params.push_back(&e);
  }
  return tree;
}

/// The text tree, indented by depth, then the machine's parameters and the connections.
std::string tree_text(const platform::Machine& machine, const std::string& scene_spec,
                      const ModuleTree& tree) {
  std::ostringstream text;
  text << machine.name() << ": " << cite_seeds(machine.description()) << "\n";
  text << "Module tree (built for " << scene_spec
       << "); parameters by the name that sets every instance, with their values; "
          "statistics as stats.json `modules` reports them.\n\n";
  for (const auto& [name, n] : tree.nodes) {
    const std::size_t depth = static_cast<std::size_t>(std::count(name.begin(), name.end(), '.'));
    const std::string indent(2 * depth, ' ');
    text << indent << leaf_of(name) << "  [" << (n.type.empty() ? "statistics group" : n.type)
         << "]  " << name << "\n";
    for (const auto* p : n.params)
      text << indent << "    param " << p->name << " = " << p->value_text << "\n";
    if (!n.stats.empty()) {
      text << indent << "    stats";
      for (const auto& st : n.stats) text << " " << st;
      text << "\n";
    }
  }
  text << "\nMachine parameters:";
  for (const auto* p : tree.machine_params) text << " " << p->name;
  text << "\n\nConnections:\n";
  for (const auto& [from, to, what] : tree.edges)
    text << "  " << from << " -> " << to << "  (" << what << ")\n";
  for (const auto& [ring, order] : tree.rings) {
    text << "\nRing " << ring << ", in the token's order:";
    for (const auto& m : order) text << " " << m << " ->";
    text << " " << (order.empty() ? std::string() : order.front()) << "\n";
  }
  // What every number of its stats.json is in (`*` stands for any characters; a module's
  // digits are its class's; docs/stats.md).
  text << "\nUnits of stats.json's numbers (stats.json `units`):\n";
  std::size_t width = 0;
  for (const auto& [pattern, unit] : tree.units.entries()) width = std::max(width, pattern.size());
  for (const auto& [pattern, unit] : tree.units.entries())
    text << "  " << pattern << std::string(width + 2 - pattern.size(), ' ')
         << modules::unit_name(unit) << "\n";
  return text.str();
}

/// The columns of a class of numbered top-level modules wired as a mesh (ullner-array's nodes:
/// node k linked to k + 1 and to k + C), or 0. C is the most frequent link between instances
/// other than a neighbour's number, and divides their count.
std::size_t mesh_columns(const std::string& stem, std::size_t count,
                         const std::set<std::tuple<std::string, std::string, std::string>>& edges) {
  const auto index = [&](const std::string& name) -> std::optional<std::size_t> {
    const auto [s, k] = instance_of(name.substr(0, name.find('.')));
    if (s != stem || k == std::string::npos) return std::nullopt;
    return k;
  };
  std::map<std::size_t, std::size_t> by_step;  // |j - i| -> links
  for (const auto& [from, to, what] : edges) {
    const auto i = index(from), j = index(to);
    if (i && j && *i != *j) ++by_step[*i > *j ? *i - *j : *j - *i];
  }
  if (!by_step.contains(1)) return 0;
  std::size_t columns = 0, most = 0;
  for (const auto& [step, links] : by_step)
    if (step > 1 && links > most && count % step == 0) {
      columns = step;
      most = links;
    }
  return columns;
}

/// A diagram's title as DOT label text, broken into lines of at most about 100 characters so
/// that it does not set the picture's width.
std::string title_lines(const std::string& title) {
  constexpr std::size_t kLine = 100;
  std::string out, line;
  std::istringstream words(title);
  for (std::string w; words >> w;) {
    if (!line.empty() && line.size() + 1 + w.size() > kLine) {
      out += dot_escape(line) + "\\n";
      line.clear();
    }
    line += (line.empty() ? "" : " ") + w;
  }
  return out + dot_escape(line);
}

/// The block diagram in DOT: a cluster per module with children, a box per module without. A
/// mesh of modules is drawn as its grid, a box per module, its modules' insides named once.
std::string tree_dot(const platform::Machine& machine, const ModuleTree& tree) {
  const auto& nodes = tree.nodes;
  std::ostringstream dot;
  dot << "digraph " << dot_id(machine.name()) << " {\n  rankdir=LR;\n  compound=true;\n"
      << "  node [shape=box, style=rounded, fontname=\"Helvetica\", fontsize=10];\n"
      << "  label=\"" << title_lines(machine.name() + ": " + cite_seeds(machine.description()))
      << "\";\n  labelloc=t;\n";
  // Large classes: the instances past the first few are not drawn (kMaxDrawnClassSize); one
  // box per class says how many more there are.
  std::map<std::pair<std::string, std::string>, std::vector<std::pair<std::size_t, std::string>>>
      classes;  // (parent, stem) -> (number, name)
  for (const auto& [name, n] : nodes)
    if (const auto [stem, number] = instance_of(leaf_of(name)); number != std::string::npos)
      classes[{parent_of(name), stem}].emplace_back(number, name);
  std::set<std::string> hidden;
  std::map<std::string, std::vector<std::string>> more;  // parent -> boxes counting the rest
  for (auto& [key, members] : classes) {
    if (members.size() <= kMaxDrawnClassSize) continue;
    std::sort(members.begin(), members.end());
    for (std::size_t i = kDrawnInstances; i < members.size(); ++i) hidden.insert(members[i].second);
    more[key.first].push_back(std::to_string(members.size() - kDrawnInstances) + " more " +
                              key.second + " (" + leaf_of(members[kDrawnInstances].second) +
                              " ... " + leaf_of(members.back().second) + ")");
  }
  // Meshes: the instances of a top-level class wired to their neighbours, laid out as a grid.
  struct Mesh {
    std::vector<std::string> members;  // by number
    std::size_t columns = 0;
  };
  std::map<std::string, Mesh> meshes;         // stem -> mesh
  std::map<std::string, std::string> folded;  // an instance of a mesh -> its stem
  for (auto& [key, members] : classes) {
    if (!key.first.empty() || members.size() < 4 || members.size() > kMaxDrawnClassSize) continue;
    const std::size_t columns = mesh_columns(key.second, members.size(), tree.edges);
    if (columns == 0) continue;
    std::sort(members.begin(), members.end());
    Mesh& m = meshes[key.second];
    m.columns = columns;
    for (const auto& [number, name] : members) {
      m.members.push_back(name);
      folded[name] = key.second;
    }
  }
  // Rings: the modules on a ring drawn as boxes round it in the token's order, their insides
  // named once (a ring's members of one kind hold the same).
  std::map<std::string, std::string> ring_of;  // a module on a ring -> the ring
  for (const auto& [ring, order] : tree.rings)
    for (const auto& m : order)
      if (!m.empty() && m.find('.') == std::string::npos && nodes.contains(m)) ring_of[m] = ring;
  // The instance of a mesh or a ring a module is, or is inside; "" for none.
  const auto mesh_instance = [&](const std::string& name) -> std::string {
    const std::string top = name.substr(0, name.find('.'));
    return folded.contains(top) || ring_of.contains(top) ? top : std::string();
  };
  // What the instances of one mesh or ring (those `in_group` accepts) hold, named once and sorted:
  // "frame_buffer, in_e, link_e, ...".
  const auto parts_inside = [&](const auto& in_group) {
    std::set<std::string> inside;
    for (const auto& [name, n] : nodes)
      if (const std::string inst = mesh_instance(name);
          !inst.empty() && inst != name && in_group(inst))
        inside.insert(name.substr(inst.size() + 1));
    std::string parts;
    for (const auto& p : inside) parts += (parts.empty() ? "" : ", ") + p;
    return parts;
  };
  const auto drawn = [&](std::string name) {
    if (const std::string inst = mesh_instance(name); !inst.empty() && inst != name) return false;
    for (; !name.empty(); name = parent_of(name))
      if (hidden.contains(name)) return false;
    return true;
  };
  std::set<std::string> has_children;
  for (const auto& [name, n] : nodes)
    if (!parent_of(name).empty() && drawn(name)) has_children.insert(parent_of(name));
  std::size_t more_boxes = 0;
  const auto emit_more = [&](const std::string& parent, const std::string& pad) {
    if (const auto it = more.find(parent); it != more.end())
      for (const auto& text : it->second)
        dot << pad << dot_id("more_" + std::to_string(more_boxes++)) << " [label=\""
            << dot_escape(text) << "\", style=\"rounded,dotted\"];\n";
  };
  std::function<void(const std::string&, int)> emit = [&](const std::string& name, int depth) {
    const Node& n = nodes.at(name);
    const std::string pad(2 * static_cast<std::size_t>(depth) + 2, ' ');
    // DOT's "\n" breaks a label's line; the parts are escaped first.
    std::string label =
        dot_escape(leaf_of(name)) + "\\n" + (n.type.empty() ? "(statistics)" : n.type);
    for (const auto* p : n.params)
      label += "\\n" + dot_escape(p->name.substr(tree.class_paths.at(name).size() + 1) + " = " +
                                  p->value_text);
    if (has_children.contains(name) && mesh_instance(name).empty()) {
      dot << pad << "subgraph " << dot_id("cluster_" + name) << " {\n"
          << pad << "  label=\"" << label << "\";\n"
          << pad << "  style=rounded;\n"
          << pad << "  " << dot_id(name) << " [shape=point, style=invis];\n";
      for (const auto& [child, c] : nodes)
        if (parent_of(child) == name && drawn(child)) emit(child, depth + 1);
      emit_more(name, pad + "  ");
      dot << pad << "}\n";
    } else {
      dot << pad << dot_id(name) << " [label=\"" << label << "\""
          << (n.type.empty() ? ", style=\"rounded,dashed\"" : "") << "];\n";
    }
  };
  for (const auto& [name, n] : nodes)
    if (parent_of(name).empty() && drawn(name)) emit(name, 0);
  emit_more("", "  ");
  for (const auto& [stem, m] : meshes) {
    // With rankdir=LR a rank is a column of the picture: column c holds c, c + C, c + 2C, ...
    for (std::size_t c = 0; c < m.columns; ++c) {
      dot << "  { rank=same;";
      for (std::size_t k = c; k < m.members.size(); k += m.columns)
        dot << " " << dot_id(m.members[k]);
      dot << " }\n";
    }
    const std::string parts = parts_inside([&](const std::string& inst) {
      const auto it = folded.find(inst);  // a ring's node is an instance too, of no mesh
      return it != folded.end() && it->second == stem;
    });
    dot << "  " << dot_id(stem + "_inside") << " [label=\""
        << dot_escape(std::to_string(m.members.size() / m.columns) + " x " +
                      std::to_string(m.columns) + " " + stem + "s, each holding: " + parts +
                      " (rtsim describe lists them)")
        << "\", shape=note, style=\"\"];\n";
  }
  for (const auto& [ring, order] : tree.rings) {
    std::vector<std::string> stops;
    for (const auto& m : order)
      if (ring_of.contains(m) && drawn(m)) stops.push_back(m);
    const std::size_t n = stops.size();
    if (n < 2) continue;
    // A racetrack: the first half left to right along the top, the second back along the
    // bottom (with rankdir=LR a rank is a column: stop k shares its column with stop n-1-k).
    for (std::size_t k = 0; k < n / 2; ++k)
      dot << "  { rank=same; " << dot_id(stops[k]) << " " << dot_id(stops[n - 1 - k]) << " }\n";
    for (std::size_t k = 0; k < n; ++k) {
      const bool top = k + 1 < (n + 1) / 2;
      dot << "  " << dot_id(stops[k]) << " -> " << dot_id(stops[(k + 1) % n])
          << " [color=royalblue, penwidth=1.5" << (top ? "" : ", constraint=false")
          << (k == 0 ? ", label=\"" + dot_escape(leaf_of(ring)) + " (token ring)\", fontsize=8"
                     : std::string())
          << "];\n";
    }
    const std::string parts = parts_inside([&](const std::string& inst) {
      const auto it = ring_of.find(inst);
      return it != ring_of.end() && it->second == ring;
    });
    dot << "  " << dot_id(ring + "_stops") << " [label=\""
        << dot_escape(std::to_string(n) + " nodes on " + leaf_of(ring) + ", in the token's order" +
                      (parts.empty() ? std::string() : "; each holding: " + parts) +
                      " (rtsim describe lists them)")
        << "\", shape=note, style=\"\"];\n";
  }
  std::set<std::pair<std::string, std::string>> drawn_edges;
  for (const auto& [from_name, to_name, what] : tree.edges) {
    // A ring's channel delivers to every node over the ring: drawn as the ring, above.
    if (nodes.contains(from_name) && nodes.at(from_name).type == "RingChannel" &&
        ring_of.contains(to_name.substr(0, to_name.find('.'))))
      continue;
    // An edge to or from inside a mesh instance is drawn to or from the instance, once.
    std::string from = from_name, to = to_name;
    if (const std::string i = mesh_instance(from); !i.empty()) from = i;
    if (const std::string i = mesh_instance(to); !i.empty()) to = i;
    if (from == to || !nodes.contains(from) || !nodes.contains(to) || !drawn(from) || !drawn(to))
      continue;
    const bool in_mesh =
        folded.contains(from) && folded.contains(to) && folded.at(from) == folded.at(to);
    if (in_mesh) {
      // Within a mesh: east and south links only (their reverse and the wrap-around links
      // would cross the grid), a south link inside its column.
      const Mesh& m = meshes.at(folded.at(from));
      const auto i = instance_of(from).second, j = instance_of(to).second;
      const bool east = j == i + 1 && i / m.columns == j / m.columns;
      const bool south = j == i + m.columns;
      if (!east && !south) continue;
    }
    if (!drawn_edges.emplace(from, to).second) continue;
    if (in_mesh) {  // a link both ways: one line, no label
      dot << "  " << dot_id(from) << " -> " << dot_id(to) << " [dir=none, color=gray40];\n";
      continue;
    }
    dot << "  " << dot_id(from) << " -> " << dot_id(to) << " [label=\"" << what << "\"";
    if (has_children.contains(from) && mesh_instance(from).empty())
      dot << ", ltail=" << dot_id("cluster_" + from);
    if (has_children.contains(to) && mesh_instance(to).empty())
      dot << ", lhead=" << dot_id("cluster_" + to);
    dot << ", fontsize=8];\n";
  }
  dot << "}\n";
  return dot.str();
}

/// Writes NAME.dot and, with Graphviz, NAME.svg into `out_dir`: together or not at all. `dot`
/// runs with no shell between it and the user's path, and Ctrl-C reaches it as it reaches
/// rtsim (common/spawn_logged.hpp).
void write_diagram(const std::string& out_dir, const std::string& machine_name,
                   const std::string& dot_text) {
  OutputSet out(out_dir, OutputSet::Folder::Shared);
  const std::string dot_name = machine_name + ".dot";
  const std::string svg_name = machine_name + ".svg";
  {
    std::ofstream f(out.stage(dot_name), std::ios::binary);
    f << dot_text;
    if (!f) throw std::runtime_error("cannot write " + out.staged_path(dot_name).string());
  }
  std::string error;
  const std::filesystem::path log = out.staged_path("dot.log");
  const pid_t pid = spawn_logged({"dot", "-Tsvg", "-o", out.staged_path(svg_name).string(),
                                  out.staged_path(dot_name).string()},
                                 log, /*search_path=*/true, error);
  const int status = pid < 0 ? -1 : wait_for_child(pid, error);
  const bool no_dot = pid < 0 || (WIFEXITED(status) && WEXITSTATUS(status) == 127);
  if (no_dot) {
    std::cerr << "no SVG: Graphviz's `dot` is not installed (Debian: apt install graphviz)\n";
  } else if (status < 0 || !WIFEXITED(status) || WEXITSTATUS(status) != 0) {
    throw std::runtime_error("dot failed on " + dot_name + (error.empty() ? "" : ": " + error) +
                             last_lines_of_file(log, 3));
  } else {
    out.stage(svg_name);
  }
  out.commit();
  std::cerr << "wrote " << (out.dir() / dot_name).string() << "\n";
  if (!no_dot) std::cerr << "wrote " << (out.dir() / svg_name).string() << "\n";
}

}  // namespace

int run_describe(const DescribeArgs& args) {
  const platform::Machine& machine = platform::find_machine(args.machine);
  auto registry = build_registry(args.config, &machine);
  const std::string scene_spec = args.scene.empty() ? machine.sample_scene() : args.scene;
  scenes::Scene scene = load_scene_with_seed(scene_spec, registry);
  const ModuleTree tree = read_tree(machine, registry, scene);
  std::cout << tree_text(machine, scene_spec, tree);
  if (!args.out_dir.empty()) write_diagram(args.out_dir, machine.name(), tree_dot(machine, tree));
  return 0;
}

}  // namespace rtsim::app
