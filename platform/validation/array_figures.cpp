#include "platform/validation/array_figures.hpp"

#include <algorithm>
#include <numeric>
#include <string>
#include <vector>

#include "params/units.hpp"
#include "platform/validation/figure_registry.hpp"
#include "platform/validation/ullner_figures.hpp"

namespace rtsim::validation {

namespace {

// Seed values (seed 000 L891-L895).
constexpr double kPeripheralFetchBits = 20 * 32;  // "six hundred forty bits at once"
constexpr double kNodeFetchBits = 16;             // "a sixteen bit path to memory"
constexpr double kProcessorsToMatch = 40;         // L891
constexpr double kHundredSpeedUp = 2.5;           // "250% as fast", L891

RunRequest machine_run(std::string key, const char* machine, int side,
                       const std::vector<std::string>& params) {
  return machine_run_request(std::move(key), machine, "builtin:ullner-cubes", side, side, params,
                             40.0 * side * side);
}

/// Max / mean of the processors' busy fractions: 1 is perfect balance.
double imbalance(const RunResults& r, const std::string& key) {
  const nlohmann::json& s = stats_of(r, key);
  if (!s.contains("array") || !s["array"].contains("node_busy_fraction"))
    throw MeasureError("stats.json of run " + key + " has no array.node_busy_fraction");
  std::vector<double> b;
  for (const auto& row : s["array"]["node_busy_fraction"])
    for (const auto& x : row) b.push_back(x.get<double>());
  const double mean = std::accumulate(b.begin(), b.end(), 0.0) / static_cast<double>(b.size());
  if (!(mean > 0)) throw MeasureError("run " + key + ": no processor was busy");
  return *std::max_element(b.begin(), b.end()) / mean;
}

/// Where the eye's rays enter the array (Figs. 2-29, 2-30): the share of the processors at which
/// new rays became vision rays (nodeK.vision_rays_entered > 0), and the busiest one's count over
/// the mean.
struct Entry {
  double share, spread;
};
Entry entries(const RunResults& r, const std::string& key) {
  const nlohmann::json& s = stats_of(r, key);
  std::vector<double> n;
  for (const auto& [name, m] : s.at("modules").items())
    if (m.is_object() && m.contains("vision_rays_entered"))
      n.push_back(m["vision_rays_entered"].get<double>());
  const double total = std::accumulate(n.begin(), n.end(), 0.0);
  if (n.empty() || !(total > 0)) throw MeasureError("run " + key + ": no vision ray entered");
  const auto entered = std::count_if(n.begin(), n.end(), [](double x) { return x > 0; });
  return {static_cast<double>(entered) / static_cast<double>(n.size()),
          *std::max_element(n.begin(), n.end()) * static_cast<double>(n.size()) / total};
}

std::string entry_text(const Entry& e, const std::string& what) {
  return what + ": rays enter at " + format_number(100 * e.share) +
         "% of the processors, the busiest entry " + format_number(e.spread) + "x the mean";
}

/// The processors' mean share of the frame: CPU busy, intersection unit busy, memory busy (its
/// unit's fetches and the ports' copies), and the share the parameter fetches alone take (what
/// L891's estimate counts), from run `key`'s stats.json.
struct NodeAccounts {
  double cpu, unit, memory, fetch;
};
NodeAccounts node_accounts(const RunResults& r, const std::string& key) {
  const nlohmann::json& s = stats_of(r, key);
  const double frame = stats_number(r, key, "simulated_time_s");
  const double cycle = param_seconds(r, key, "node.memory_cycle");
  const auto& classes = s.at("module_classes");
  const double cpu = classes.at("node*").at("utilization").at("mean").get<double>();
  const double unit = classes.at("node*.pipeline").at("utilization").at("mean").get<double>();
  double memory = 0, words = 0, nodes = 0;
  for (const auto& [name, m] : s.at("modules").items()) {
    if (name.rfind("node", 0) != 0 || !m.contains("memory_busy_s")) continue;
    memory += m["memory_busy_s"].get<double>();
    ++nodes;
  }
  for (const auto& [name, m] : s.at("modules").items())
    if (name.ends_with(".pipeline") && m.contains("words_fetched"))
      words += m["words_fetched"].get<double>();
  if (!(nodes > 0 && frame > 0)) throw MeasureError("run " + key + ": no processor accounts");
  // Two 16-bit transfers a 32-bit word (L835, L891).
  return {cpu, unit, memory / nodes / frame, 2 * cycle * words / nodes / frame};
}

std::string accounts_text(const NodeAccounts& a) {
  return "processors' mean share of the frame: CPU " + format_number(100 * a.cpu) + "%, unit " +
         format_number(100 * a.unit) + "%, memory " + format_number(100 * a.memory) +
         "%, of it parameter fetches " + format_number(100 * a.fetch) + "%";
}

}  // namespace

namespace {
/// The processor's timing the thesis leaves open (L835-L854): what the array's frame times
/// rest on.
std::vector<AssumptionRef> node_assumptions() {
  return {{.param = "node.clock"},
          {.param = "node.cpu_memory_share",
           .values = {"0.3", "0.9"},
           .why = "a share of the CPU's time, at most 1: half the default, and every "
                  "instruction slot a bus cycle"},
          {.param = "node.pipeline.stage_time"},
          {.param = "node.link.bit_time"},
          {.param = "node.credit_quiet_time"}};
}

/// What the busiest processor's share over the mean rests on.
std::vector<AssumptionRef> balance_assumptions() {
  return {{.param = "node.cpu_memory_share",
           .values = {"0.3", "0.9"},
           .why = "a share of the CPU's time, at most 1: half the default, and every "
                  "instruction slot a bus cycle"},
          {.param = "node.credit_quiet_time"},
          {.param = "node.cycles.message"}};
}

/// V19: the array's processor against the peripheral's host.
std::vector<AssumptionRef> v19_assumptions() {
  auto a = node_assumptions();
  a.push_back({.param = "node.cycles.subvolume"});
  a.push_back({.param = "host.word_time"});
  a.push_back({.param = "host.clock"});
  return a;
}

void add_array_figures(Plan& plan, const PlanOptions& options) {
  const int side = options.quick ? 32 : 64;
  const std::string size = std::to_string(side) + "x" + std::to_string(side);
  // ullner-cubes' eye looks most along y: depth along y is the eye in front (Fig. 2-29), along
  // x the eye to the side of the processors' columns (Fig. 2-30).
  const std::string front = plan.add_run(machine_run("array-front", kArrayMachine, side, {}));
  const std::string side_straight =
      plan.add_run(machine_run("array-side", kArrayMachine, side, {"array.depth_axis=x"}));
  const std::string side_torus = plan.add_run(machine_run(
      "array-side-torus", kArrayMachine, side, {"array.depth_axis=x", "array.mapping=torus"}));
  const std::string peripheral = plan.add_run(
      machine_run("array-peripheral", kUllnerMachine, side, {"peripheral.grid.divisions=8"}));
  // The peripheral with a host that keeps up (the thesis's bandwidth comparison is of the two
  // machines' fetches, not of the host), and the array at L891's 40 and 100 processors.
  const std::string fast_peripheral =
      plan.add_run(machine_run("array-peripheral-fast-host", kUllnerMachine, side,
                               {"peripheral.grid.divisions=8", "host.clock=\"100 GHz\"",
                                "host.ray_link.bit_rate=\"1 Gbit/s\""}));
  const std::string array40 =
      plan.add_run(machine_run("array-40", kArrayMachine, side, {"array.rows=5", "array.cols=8"}));
  const std::string array100 = plan.add_run(
      machine_run("array-100", kArrayMachine, side, {"array.rows=10", "array.cols=10"}));

  // V17a-b: the bandwidth arithmetic of L891 on the runs' own parameters (derived).
  auto processors_to_match = [front, peripheral](const RunResults& r) {
    const double node = kNodeFetchBits / param_seconds(r, front, "node.memory_cycle");
    const double per =
        kPeripheralFetchBits / param_seconds(r, peripheral, "peripheral.intersect_interval");
    return per / node;
  };
  plan.figures.push_back(Figure{
      .id = "V17a",
      .title = "Array processors whose fetch bandwidth matches the peripheral's",
      .seed_ref = "seed 000 L891",
      .seed_text = "the peripheral fetches 640 bits at once, a processor's memory path is 16 bits: "
                   "\"about forty processors\" match it",
      .seed_value = kProcessorsToMatch,
      .unit = "processors",
      .tolerance = Tolerance::relative(
          1e-6,
          "arithmetic on the runs' parameters: 640 bits per peripheral.intersect_interval "
          "over 16 bits per node.memory_cycle (both 1/3 us, as L891 supposes)"),
      .workload = "the parameters of the V18 and V19 runs",
      .runs = {front, peripheral},
      .measure =
          [processors_to_match](const RunResults& r) {
            return Measured{processors_to_match(r),
                            "(640 bits / intersect interval) / (16 bits / memory cycle)"};
          },
      .figure_class = FigureClass::kDerived,
  });
  plan.figures.push_back(Figure{
      .id = "V17b",
      .title = "100 array processors against the peripheral, fetch bandwidth",
      .seed_ref = "seed 000 L891",
      .seed_text = "\"an array of 100 processors would be 250% as fast as the original ray "
                   "tracing peripheral\" (ignoring the other memory demands and early rejection, "
                   "L893)",
      .seed_value = kHundredSpeedUp,
      .unit = "x",
      .tolerance = Tolerance::relative(1e-6, "the same arithmetic: 100 / V17a"),
      .workload = "as V17a",
      .runs = {front, peripheral},
      .measure =
          [processors_to_match](const RunResults& r) {
            return Measured{100.0 / processors_to_match(r), "100 / V17a"};
          },
      .figure_class = FigureClass::kDerived,
  });
  // V17c-d: the same comparison simulated. L893 warns that the estimate "ignores the fact that
  // there are other demands placed on the component processors beyond mere parameter fetching";
  // the note says which, from the processors' own accounts.
  const std::string why_open =
      "L891 assumes \"every processor in the array is kept busy\" fetching parameters; "
      "simulated, the processors' memories fetch for a small share of the frame and their CPUs' "
      "other work (messages, software routing, shading: L893's \"other demands\") takes more; "
      "the rest of the frame they wait (latency, imbalance). The note measures each";
  for (const auto& [id, run, n, seed] :
       {std::tuple{"V17c", array40, 40, 1.0}, std::tuple{"V17d", array100, 100, kHundredSpeedUp}}) {
    plan.figures.push_back(Figure{
        .id = id,
        .title = std::string("Array of ") + std::to_string(n) +
                 " processors against the peripheral, simulated",
        .seed_ref = "seed 000 L891-L893",
        .seed_text = n == 40 ? "forty processors \"equal\" the peripheral's fetch performance"
                             : "\"an array with a hundred processors would be 250% as fast\"",
        .seed_value = seed,
        .unit = "x",
        .tolerance = Tolerance::relative(
            0.25, "the estimate is a bandwidth bound; within a quarter the fetches set the pace"),
        .workload = "builtin:ullner-cubes at " + size + ": ullner-peripheral (grid 8, host at " +
                    "100 GHz and 1 Gbit/s: it keeps up) against ullner-array (" +
                    (n == 40 ? "5 x 8" : "10 x 10") + ", straight)",
        .runs = {run, fast_peripheral},
        .measure =
            [run, fast_peripheral](const RunResults& r) {
              const double p = stats_number(r, fast_peripheral, "simulated_time_s");
              const double a = stats_number(r, run, "simulated_time_s");
              return Measured{p / a, "frame " + format_number(p) + " s on the peripheral, " +
                                         format_number(a) + " s on the array; " +
                                         accounts_text(node_accounts(r, run))};
            },
        .open = why_open,
        .assumptions = node_assumptions(),
    });
  }

  const std::string workload = "builtin:ullner-cubes at " + size + ", 8 x 8 processors";
  plan.figures.push_back(Figure{
      .id = "V18a",
      .title = "Array, eye to the side, straight mapping: load piles onto an edge",
      .seed_ref = "seed 000 L862",
      .seed_text = "with the eye to the side \"the processors on that edge of the array receive "
                   "all of the vision rays\" (Fig. 2-30), where the eye in front spreads them "
                   "(Fig. 2-29)",
      .seed_value = 1.0,
      .seed_display = "imbalance side / front > 1",
      .unit = "",
      .tolerance = Tolerance::above(
          1.0,
          "qualitative: the busiest processor's share over the mean grows when the view "
          "runs across the columns"),
      .workload = workload + "; depth along y (eye in front) and along x (eye to the side)",
      .runs = {front, side_straight},
      .measure =
          [front, side_straight](const RunResults& r) {
            const double f = imbalance(r, front), s = imbalance(r, side_straight);
            return Measured{
                s / f, "max/mean busy: side " + format_number(s) + ", front " + format_number(f)};
          },
      .figure_class = FigureClass::kQualitative,
      .assumptions = balance_assumptions(),
  });
  plan.figures.push_back(Figure{
      .id = "V18b",
      .title = "Array, eye to the side: the skewed torus restores the balance",
      .seed_ref = "seed 000 L866-L881",
      .seed_text = "skewing the mapping (Figs. 2-31, 2-32) spreads a side view's rays over the "
                   "processors; the torus is needed for any viewpoint",
      .seed_value = 1.0,
      .seed_display = "imbalance torus / straight < 1",
      .unit = "",
      .tolerance = Tolerance::range(
          0.0, 1.0, "qualitative: the torus's max/mean busy is below the straight mapping's"),
      .workload = workload + ", depth along x; straight and torus mappings",
      .runs = {side_straight, side_torus},
      .measure =
          [side_straight, side_torus](const RunResults& r) {
            const double s = imbalance(r, side_straight), t = imbalance(r, side_torus);
            return Measured{t / s, "max/mean busy: torus " + format_number(t) + ", straight " +
                                       format_number(s)};
          },
      .figure_class = FigureClass::kQualitative,
      .assumptions = balance_assumptions(),
  });
  // V19's assumption: each compute stage of the intersection unit takes node.pipeline.stage_time
  // (333 ns). L839 says its throughput is limited by the fetches (t's 4 words: 8 transfers, 2.67
  // us at the least), so a stage is no slower than that; L723's shift-and-add operation takes
  // about 5 us, so each stage interleaves two units or more. Both bounds are run: the note shows
  // how far the figure moves.
  const std::string fetch_bound = plan.add_run(machine_run(
      "array-stage-2.667us", kArrayMachine, side, {"node.pipeline.stage_time=\"2.667 us\""}));
  const std::string one_unit = plan.add_run(
      machine_run("array-stage-5us", kArrayMachine, side, {"node.pipeline.stage_time=\"5 us\""}));
  // And the MC68000's own bus traffic (node.cpu_memory_share 0.6, an assumption): without it.
  const std::string no_cpu_traffic = plan.add_run(
      machine_run("array-cpu-share-0", kArrayMachine, side, {"node.cpu_memory_share=0"}));
  // V18c-g: where the vision rays enter the array, on a scene whose eye is exactly in front of
  // the modelling cube (builtin:ullner-sheets-lit-1000: the eye on the axis through the middle
  // of the y = 0 face, looking along +y), as Figs. 2-29 to 2-32 draw it. Depth along y is the eye
  // in front; along x the rays cross the columns (the eye to the side), along z the rows (the
  // eye above).
  const std::string sheets = "builtin:ullner-sheets-lit-1000";
  auto sheets_run = [&](const char* key, std::vector<std::string> params) {
    return plan.add_run(
        machine_run_request(key, kArrayMachine, sheets, side, side, params, 40.0 * side * side));
  };
  const std::string in_front = sheets_run("array-sheets-front", {"array.depth_axis=y"});
  const std::string to_side = sheets_run("array-sheets-side", {"array.depth_axis=x"});
  const std::string side_skew =
      sheets_run("array-sheets-side-skew", {"array.depth_axis=x", "array.mapping=skew"});
  const std::string above_skew =
      sheets_run("array-sheets-above-skew", {"array.depth_axis=z", "array.mapping=skew"});
  const std::string above_torus =
      sheets_run("array-sheets-above-torus", {"array.depth_axis=z", "array.mapping=torus"});
  const std::string sheets_workload = sheets + " at " + size + ", 8 x 8 processors";
  const double edge = 1.0 / 8;  // one column (or row) of the 8 x 8 array
  struct EntryFigure {
    const char* id;
    const char* title;
    const char* ref;
    const char* text;
    std::string run;
    const char* setup;
    double at_least;  ///< the share the rays must spread over (0: onto one edge at most)
  };
  for (const EntryFigure& f : std::vector<EntryFigure>{
           {"V18c", "Eye in front: the vision rays enter at every processor", "seed 000 L862",
            "\"if the scene is viewed from the front, vision rays will be distributed uniformly "
            "to processors throughout the array\" (Fig. 2-29)",
            in_front, "depth along y (the eye in front), straight", 0.9},
           {"V18d", "Eye to the side, straight: only the edge's processors receive them",
            "seed 000 L862",
            "\"those processors along the corresponding edge of the array will be forced to "
            "handle all of the vision rays, while the other processors remain idle\" (Fig. 2-30)",
            to_side, "depth along x (the eye to the side), straight", 0.0},
           {"V18e", "Eye to the side, skewed: the array is uniformly flooded again",
            "seed 000 L866-L876",
            "\"If the viewing position is off to the right of the modeling space, processors in "
            "the array will be uniformly flooded with vision rays\" (Fig. 2-31)",
            side_skew, "depth along x, skew", 0.9},
           {"V18f", "Eye above, skewed: all the rays pass through the top layer",
            "seed 000 L876-L879",
            "\"but if the eye is above the modeling space, all of the vision rays will have to "
            "pass "
            "through the top layer of processors\"",
            above_skew, "depth along z (the eye above), skew", 0.0},
           {"V18g", "Eye above, torus: the rays spread again", "seed 000 L879-L881",
            "shifting the layers down as well (Fig. 2-32) handles \"an arbitrary viewing "
            "position\"",
            above_torus, "depth along z, torus", 0.25}}) {
    plan.figures.push_back(Figure{
        .id = f.id,
        .title = f.title,
        .seed_ref = f.ref,
        .seed_text = f.text,
        .seed_value = f.at_least > 0 ? 1.0 : edge,
        .seed_display = f.at_least > 0 ? "rays enter across the array" : "one edge: 1/8",
        .unit = "",
        .tolerance =
            f.at_least >= 0.9
                ? Tolerance::range(0.9, 1.0,
                                   "qualitative: \"uniformly\", nearly every processor is an "
                                   "entry point")
            : f.at_least > 0
                ? Tolerance::range(f.at_least, 1.0,
                                   "qualitative: more than two edges' processors are entry points "
                                   "(one edge is 1/8; the alternating torus gives half, "
                                   "docs/validation.md)")
                : Tolerance::range(0.0, edge,
                                   "qualitative: no more than one edge's processors (1/8) are "
                                   "entry points"),
        .workload = sheets_workload + "; " + f.setup,
        .runs = {f.run},
        .measure =
            [run = f.run](const RunResults& r) {
              const Entry e = entries(r, run);
              return Measured{e.share, entry_text(e, "share of processors where rays enter")};
            },
        // Where the rays enter follows from the view and the mapping alone: no timing
        // assumption enters.
        .figure_class = FigureClass::kQualitative,
    });
  }

  plan.figures.push_back(Figure{
      .id = "V19",
      .title = "Array against the peripheral, \"if built today\"",
      .seed_ref = "seed 000 L895",
      .seed_text = "\"If built today, a ray tracing array might be just a few times faster than "
                   "the original ray tracing peripheral\"",
      .seed_value = 0.0,
      .seed_display = "a few times: [2, 10]",
      .unit = "x",
      .tolerance = Tolerance::range(
          2.0, 10.0,
          "\"a few times\"; the peripheral at its best grid (8 per axis here) with "
          "its default host, the array with its default processors (node.pipeline.stage_time "
          "333 ns and node.cpu_memory_share 0.6: assumptions, their sensitivity in the "
          "note)"),
      .workload = "builtin:ullner-cubes at " + size +
                  ": ullner-peripheral (grid 8) against ullner-array (8 x 8, straight)",
      .runs = {front, peripheral, fetch_bound, one_unit, no_cpu_traffic},
      .measure =
          [front, peripheral, fetch_bound, one_unit, no_cpu_traffic](const RunResults& r) {
            const double p = stats_number(r, peripheral, "simulated_time_s");
            const double a = stats_number(r, front, "simulated_time_s");
            return Measured{
                p / a, "frame " + format_number(p) + " s on the peripheral, " + format_number(a) +
                           " s on the array (stage 333 ns); with a 2.667 us stage (the fetch "
                           "bound of L839) " +
                           format_number(p / stats_number(r, fetch_bound, "simulated_time_s")) +
                           "x, with a 5 us stage (one shift-and-add unit, L723) " +
                           format_number(p / stats_number(r, one_unit, "simulated_time_s")) +
                           "x; without the CPU's bus traffic " +
                           format_number(p / stats_number(r, no_cpu_traffic, "simulated_time_s")) +
                           "x"};
          },
      .open = "with the MC68000's own bus cycles holding the shared memory (L839; "
              "node.cpu_memory_share 0.6, an assumption) the array is about twice the "
              "peripheral, at the edge of \"a few times\": on the quick frame just under it, on "
              "the full one just over (docs/validation.md)",
      .assumptions = v19_assumptions(),
  });
}

const RegisterFigures kRegistered(kArrayMachine, add_array_figures);

}  // namespace

}  // namespace rtsim::validation
