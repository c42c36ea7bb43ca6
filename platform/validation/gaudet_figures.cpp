#include "platform/validation/gaudet_figures.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "platform/validation/figure_registry.hpp"
#include "platform/validation/vax_figures.hpp"

namespace rtsim::validation {
namespace {

constexpr double kMicro = 1e6;
// Per-ray figures need a few thousand rays, not a big image.
constexpr int kSideFull = 64, kSideQuick = 40;

struct PertRun {
  std::string scene;  // "412"
  std::string mode = "adaptive";
  std::string order = "breadth";
  int n = 1;
  std::string key() const {
    return "pert-" + scene + "-" + mode + "-" + order + "-n" + std::to_string(n);
  }
};

RunRequest pert_request(const PertRun& p, int side) {
  RunRequest r;
  r.key = p.key();
  r.args = {"run",
            "--machine",
            kGaudetMachine,
            "--scene",
            "builtin:npp-" + p.scene,
            "--width",
            std::to_string(side),
            "--height",
            std::to_string(side),
            "-q",
            "-p",
            "pert_count=" + std::to_string(p.n),
            "-p",
            "broadcast.mode=" + p.mode,
            "-p",
            "broadcast.order=" + p.order};
  r.cost_hint = side * side * (p.mode == "non-adaptive" ? 3.0 : 1.0) * (1.0 + p.n / 16.0);
  return r;
}

RunRequest vax_request(const std::string& scene, int side) {
  RunRequest r;
  r.key = "vax-shells-" + scene;
  r.args = {"run",
            "--machine",
            kVaxMachine,
            "--scene",
            "builtin:npp-" + scene,
            "--width",
            std::to_string(side),
            "--height",
            std::to_string(side),
            "-q",
            "-p",
            "vax.search=shells"};
  r.cost_hint = side * side * 0.5;
  return r;
}

double us(const RunResults& r, const std::string& key, const std::string& path) {
  return stats_number(r, key, path) * kMicro;
}
double shell_latency(const RunResults& r, const std::string& key) {
  return us(r, key, "gaudet.shell.latency_per_ray_s");
}
double shell_total(const RunResults& r, const std::string& key) {
  return us(r, key, "gaudet.shell.processing_per_ray_s") + shell_latency(r, key);
}
/// PrimProcessor average time per ray, Fig. 6-9: processing and waiting for the bus.
double prim_time(const RunResults& r, const std::string& key) {
  return us(r, key, "gaudet.prim.processing_per_ray_s") +
         us(r, key, "gaudet.prim.latency_per_ray_s");
}
double speedup(const RunResults& r, const std::string& vax, const std::string& pert) {
  return stats_number(r, vax, "simulated_time_s") / stats_number(r, pert, "simulated_time_s");
}

/// Least-squares slope of y against x.
double slope(const std::vector<double>& x, const std::vector<double>& y) {
  double mx = 0, my = 0;
  for (std::size_t i = 0; i < x.size(); ++i) mx += x[i], my += y[i];
  mx /= static_cast<double>(x.size());
  my /= static_cast<double>(x.size());
  double sxy = 0, sxx = 0;
  for (std::size_t i = 0; i < x.size(); ++i)
    sxy += (x[i] - mx) * (y[i] - my), sxx += (x[i] - mx) * (x[i] - mx);
  return sxx > 0 ? sxy / sxx : 0.0;
}

std::string join(const std::vector<double>& v) {
  std::string s;
  for (std::size_t i = 0; i < v.size(); ++i) {
    if (i) s += '/';
    s += format_number(v[i]);
  }
  return s;
}

}  // namespace

std::vector<int> gaudet_pert_counts(bool quick) {
  if (quick) return {1, 8, 64};
  return {1, 2, 4, 8, 16, 32, 64};
}

namespace {

/// The quad-tree scenes of Figs. 6-9 and 6-11 (builtin:npp-404..420).
constexpr const char* kQuadScenes[] = {"404", "408", "412", "416", "420"};

/// What every figure of gaudet-pert shares: the frame and how a PERT run is added to the plan
/// (Plan::add_run keeps one run per key, and --only keeps the runs its figures name).
struct GaudetPlan {
  GaudetPlan(Plan&, const PlanOptions& options)
      : quick(options.quick),
        side(quick ? kSideQuick : kSideFull),
        size(std::to_string(side) + "x" + std::to_string(side)) {}
  std::string add(Plan& plan, const PertRun& p) const {
    return plan.add_run(pert_request(p, side));
  }
  bool quick;
  int side;
  std::string size;
};

/// P6..P9: speed-ups over the VAX-11/750 and the multi-PERT curves, whose runs the figures and
/// gaudet-speedup.csv share (added in the same order by each).
struct SpeedUpCurves : GaudetPlan {
  SpeedUpCurves(Plan& plan, const PlanOptions& options) : GaudetPlan(plan, options) {
    ns = gaudet_pert_counts(quick);
    curve_scenes = quick ? std::vector<std::string>{"412", "820"}
                         : std::vector<std::string>{"412", "816", "820"};
    for (const auto& s : curve_scenes) {
      curve_runs.push_back(plan.add_run(vax_request(s, side)));
      for (const char* m : {"direct", "non-adaptive", "adaptive"})
        for (int n : ns) curve_runs.push_back(add(plan, PertRun{s, m, "breadth", n}));
    }
  }
  std::vector<int> ns;
  std::vector<std::string> curve_scenes, curve_runs;
  std::string vax412 = "vax-shells-412";
};

/// What the ShellProcessor's processing and latency rest on besides the calibrated cycles.
std::vector<AssumptionRef> shell_assumptions() {
  return {{.param = "pert.shell.rays_in_flight"},
          {.param = "pert.shell.bic.id_registers"},
          {.param = "pert.memory.first_access"},
          {.param = "pert.queue.shell_to_prim"}};
}

/// A PERT against the VAX: the VAX's box test (the thesis measured only T_i) and the PERT's
/// memory and load.
std::vector<AssumptionRef> against_vax_assumptions() {
  return {{.param = "vax.box_test_time"},
          {.param = "pert.memory.first_access"},
          {.param = "control.load_word_time"},
          {.param = "pert.shade.rays_in_flight"}};
}

void add_p1_test_scenes(Plan& plan, const PlanOptions&) {
  // ---- P1: Fig. 6-1, the test scenes (seed 001 L980-L989) ----
  struct Counts {
    const char* scene;
    double shells, shell_packets, prims, prim_packets;
  };
  const Counts fig6_1[] = {{"204", 126, 63, 256, 64},
                           {"408", 84, 21, 512, 64},
                           {"812", 72, 9, 768, 64},
                           {"816", 72, 9, 1024, 64},
                           {"820", 72, 9, 1280, 64}};
  char letter = 'a';
  for (const Counts& c : fig6_1) {
    // Counts do not depend on the image: the smallest one will do.
    RunRequest req = pert_request(PertRun{c.scene}, 4);
    req.key = std::string("pert-counts-") + c.scene;
    req.cost_hint = 1;
    const std::string key = plan.add_run(req);
    std::ostringstream seed;
    seed << c.shells << "/" << c.shell_packets << "/" << c.prims << "/" << c.prim_packets;
    plan.figures.push_back(Figure{
        .id = std::string("P1") + letter++,
        .title = std::string("Scene ") + c.scene + ": shells/shell packets/prims/prim packets",
        .seed_ref = "seed 001 L980-L989",
        .seed_text = "Fig. 6-1, characteristics of the test scenes",
        .seed_value = 4,
        .seed_display = seed.str(),
        .unit = "counts equal",
        .tolerance = Tolerance::absolute(0, "structural counts of a complete tree: exact"),
        .workload = std::string("builtin:npp-") + c.scene + " (any size)",
        .runs = {key},
        .measure =
            [key, c](const RunResults& r) {
              const double got[] = {stats_number(r, key, "scene_stats.shells"),
                                    stats_number(r, key, "scene_stats.shell_packets"),
                                    stats_number(r, key, "scene_stats.prims"),
                                    stats_number(r, key, "scene_stats.prim_packets")};
              const double want[] = {c.shells, c.shell_packets, c.prims, c.prim_packets};
              Measured m;
              for (int i = 0; i < 4; ++i) m.value += got[i] == want[i] ? 1 : 0;
              m.note = "simulated " + join({got[0], got[1], got[2], got[3]});
              return m;
            },
    });
  }
  // Counts of the tree the firmware builds from the scene: no timing assumption enters.
  plan.classify({"P1"}, FigureClass::kMeasured);
}

void add_p2_p3_shell_latency_by_tree(Plan& plan, const PlanOptions& options) {
  const GaudetPlan g(plan, options);
  const auto& size = g.size;
  const auto add = [&](const PertRun& p) { return g.add(plan, p); };
  // ---- P2, P3: Fig. 6-10, ShellProcessor per ray on binary/quad/oct trees (L1025-L1030) ----
  const std::string k212 = add(PertRun{"212"}), k412 = add(PertRun{"412"}),
                    k812 = add(PertRun{"812"});
  const std::string tree_workload = "builtin:npp-212, -412, -812 at " + size +
                                    ", 1 PERT, adaptive, breadth-first (the order of Fig. 6-11's "
                                    "best, whose 412 latency Fig. 6-10 repeats)";
  const struct {
    const char* id;
    const char* tree;
    std::string key;
    double processing, latency;
  } fig6_10[] = {{"P2a", "binary (212)", k212, 467.8, 124.9},
                 {"P2b", "quad (412)", k412, 523.9, 5.0},
                 {"P2c", "oct (812)", k812, 690.5, 0.5}};
  for (const auto& f : fig6_10) {
    const std::string key = f.key;
    const double thesis_latency = f.latency;
    plan.figures.push_back(Figure{
        .id = f.id,
        .title = std::string("ShellProcessor processing per ray, ") + f.tree,
        .seed_ref = "seed 001 L1025-L1030",
        .seed_text = "Fig. 6-10: processing 467.8/523.9/690.5 us per ray (binary/quad/oct)",
        .seed_value = f.processing,
        .unit = "us",
        .tolerance = Tolerance::relative(
            0.12,
            "the SJ16/FPU cycles per operation are calibrated on these three figures together "
            "(one set for all processors); the thesis's camera and lights are lost, so the "
            "boxes tested per ray differ by tree as our view makes them"),
        .workload = tree_workload,
        .runs = {key},
        .measure =
            [key, thesis_latency](const RunResults& r) {
              Measured m;
              m.value = us(r, key, "gaudet.shell.processing_per_ray_s");
              m.note = "latency (emerges from the bus) " + format_number(shell_latency(r, key)) +
                       " us per ray, thesis " + format_number(thesis_latency) + " us; starved " +
                       format_number(us(r, key, "gaudet.shell.starved_per_ray_s")) +
                       " us per ray (not latency); " +
                       format_number(stats_number(r, key, "gaudet.shell.box_tests_per_ray")) +
                       " boxes tested per ray";
              return m;
            },
    });
  }
  // P3: the latency is not calibrated, it emerges from the bus model (with the open
  // assumptions chosen in docs/validation.md's sensitivity table), so magnitudes are judged,
  // not values: binary > quad > oct, binary over 3x quad, quad within 2x of 5.0 us, oct
  // under 2 us.
  auto latency_ratio = [&](std::string id, std::string trees, std::string seed_text, double thesis,
                           double bound, std::string why, const std::string& more,
                           const std::string& less) {
    return Figure{
        .id = std::move(id),
        .title = "ShellProcessor latency per ray, " + trees,
        .seed_ref = "seed 001 L1015, L1025-L1030",
        .seed_text = std::move(seed_text),
        .seed_value = thesis,
        .seed_display = "> " + format_number(bound) + " (thesis " + format_number(thesis) + ")",
        .unit = "ratio",
        .tolerance = Tolerance::above(bound, std::move(why)),
        .workload = tree_workload,
        .runs = {more, less},
        .measure =
            [more, less](const RunResults& r) {
              return Measured{shell_latency(r, more) / shell_latency(r, less),
                              "latency " + format_number(shell_latency(r, more)) + " and " +
                                  format_number(shell_latency(r, less)) + " us per ray"};
            },
    };
  };
  plan.figures.push_back(latency_ratio(
      "P3a", "binary over quad",
      "latency 124.9 us (binary) against 5.0 (quad): more, smaller packets to wait for",
      124.9 / 5.0, 3,
      "the latency is not calibrated: a magnitude, not a value (binary well above quad; the "
      "thesis's ratio is 25)",
      k212, k412));
  plan.figures.push_back(latency_ratio("P3b", "quad over oct",
                                       "latency 5.0 us (quad) against 0.5 (oct)", 10, 1,
                                       "the latency is not calibrated: only the direction of "
                                       "the thesis's ratio of 10 (P3e bounds oct's latency)",
                                       k412, k812));
  plan.figures.push_back(Figure{
      .id = "P3c",
      .title = "Quad tree best: total per ray over the better of binary and oct",
      .seed_ref = "seed 001 L1015",
      .seed_text = "totals 592.7/528.9/691.0 us: \"the quad tree is the best\"",
      .seed_value = 528.9 / 592.7,
      .seed_display = "< 1 (thesis 0.89)",
      .unit = "ratio",
      .tolerance = Tolerance::range(0, 0.9999, "quad must be strictly the fastest"),
      .workload = tree_workload,
      .runs = {k212, k412, k812},
      .measure =
          [k212, k412, k812](const RunResults& r) {
            const double b = shell_total(r, k212), q = shell_total(r, k412),
                         o = shell_total(r, k812);
            return Measured{q / std::min(b, o),
                            "totals " + join({b, q, o}) + " us per ray (thesis 592.7/528.9/691.0)"};
          },
  });

  auto latency_value = [&](std::string id, std::string tree, double thesis, Tolerance tolerance,
                           const std::string& key) {
    return Figure{
        .id = std::move(id),
        .title = "ShellProcessor latency per ray, " + tree,
        .seed_ref = "seed 001 L1025-L1030",
        .seed_text = "Fig. 6-10: latency 124.9/5.0/0.5 us per ray (binary/quad/oct)",
        .seed_value = thesis,
        .unit = "us",
        .tolerance = std::move(tolerance),
        .workload = tree_workload,
        .runs = {key},
        .measure =
            [key](const RunResults& r) {
              return Measured{shell_latency(r, key),
                              "starved " +
                                  format_number(us(r, key, "gaudet.shell.starved_per_ray_s")) +
                                  " us per ray (not latency)"};
            },
    };
  };
  plan.figures.push_back(latency_value(
      "P3d", "quad (412)", 5.0,
      Tolerance::range(2.5, 10,
                       "within 2x of the thesis: the latency emerges from the bus and from "
                       "assumptions the thesis leaves open (rays in flight, ID registers; "
                       "docs/validation.md)"),
      k412));
  plan.figures.push_back(latency_value(
      "P3e", "oct (812)", 0.5,
      Tolerance::range(0, 2,
                       "under 2 us: far below one oct packet's transfer (26.4 us), so nearly "
                       "every packet must be hidden behind processing, as the thesis's 0.5 says"),
      k812));
  // The processing is calibrated on P2's three figures together (one set of cycles); the
  // latency emerges from the bus and from what the thesis leaves open.
  plan.classify({"P2", "P3d", "P3e"}, FigureClass::kMeasured, shell_assumptions());
  plan.classify({"P3a", "P3b", "P3c"}, FigureClass::kQualitative, shell_assumptions());
}

void add_p4_broadcast_order(Plan& plan, const PlanOptions& options) {
  const GaudetPlan g(plan, options);
  const auto& size = g.size;
  const auto add = [&](const PertRun& p) { return g.add(plan, p); };
  // ---- P4: Fig. 6-11, broadcast order (L1032-L1039) ----
  const double thesis_breadth[] = {5.1, 4.7, 5.0, 5.1, 4.9};
  const double thesis_depth[] = {11.4, 11.4, 12.0, 12.1, 11.9};
  const double thesis_random[] = {11.4, 11.3, 12.0, 11.9, 11.7};
  std::vector<std::string> breadth, depth, random;
  for (const char* s : kQuadScenes) {
    breadth.push_back(add(PertRun{s, "adaptive", "breadth"}));
    depth.push_back(add(PertRun{s, "adaptive", "depth"}));
    random.push_back(add(PertRun{s, "adaptive", "random"}));
  }
  const std::string order_workload = "builtin:npp-404..420 at " + size +
                                     ", 1 PERT, adaptive, broadcast.order breadth/depth/random";
  auto order_figure = [&](std::string id, std::string what, const std::vector<std::string>& other,
                          const double* thesis_other) {
    double thesis = 0, thesis_b = 0;
    for (int i = 0; i < 5; ++i) thesis += thesis_other[i], thesis_b += thesis_breadth[i];
    std::vector<std::string> runs = breadth;
    runs.insert(runs.end(), other.begin(), other.end());
    return Figure{
        .id = std::move(id),
        .title = "ShellProcessor latency, " + what + " over breadth-first (mean of 404..420)",
        .seed_ref = "seed 001 L1019, L1032-L1039",
        .seed_text =
            "Fig. 6-11: breadth-first 4.7-5.1 us per ray, depth-first 11.4-12.1, random "
            "11.3-12.0",
        .seed_value = thesis / thesis_b,
        .seed_display = "> 1.3 (thesis " + format_number(thesis / thesis_b) + ")",
        .unit = "ratio",
        .tolerance = Tolerance::above(1.3, "\"well below\": the thesis's ratio is 2.4"),
        .workload = order_workload,
        .runs = runs,
        .measure =
            [b = breadth, other](const RunResults& r) {
              double sb = 0, so = 0;
              std::vector<double> vb, vo;
              for (std::size_t i = 0; i < b.size(); ++i) {
                vb.push_back(shell_latency(r, b[i]));
                vo.push_back(shell_latency(r, other[i]));
                sb += vb.back();
                so += vo.back();
              }
              return Measured{so / sb, "breadth " + join(vb) + " us, other " + join(vo) + " us"};
            },
        .open =
            "Fig. 6-11's order effect is not reproduced: no setting of streaming, the root "
            "packet, rays in flight, ID registers, posting or box-test time gives it; the "
            "request behaviour it needs is not in the seed (docs/validation.md, open figure "
            "P4)",
    };
  };
  plan.figures.push_back(order_figure("P4a", "depth-first", depth, thesis_depth));
  plan.figures.push_back(order_figure("P4b", "random", random, thesis_random));
  plan.classify({"P4"}, FigureClass::kQualitative,
                {{.param = "pert.shell.rays_in_flight"},
                 {.param = "pert.shell.bic.id_registers"},
                 {.param = "pert.shade.rays_in_flight"}});
}

void add_p5_prim_time_by_mode(Plan& plan, const PlanOptions& options) {
  const GaudetPlan g(plan, options);
  const auto& size = g.size;
  const auto add = [&](const PertRun& p) { return g.add(plan, p); };
  // ---- P5: Fig. 6-9, PrimProcessor time per ray by broadcast mode (L1011) ----
  // Adaptive breadth-first: Fig. 6-11's runs too (P4).
  std::vector<std::string> breadth, nonadaptive, direct;
  for (const char* s : kQuadScenes) {
    breadth.push_back(add(PertRun{s, "adaptive", "breadth"}));
    nonadaptive.push_back(add(PertRun{s, "non-adaptive", "breadth"}));
    direct.push_back(add(PertRun{s, "direct", "breadth"}));
  }
  const std::string mode_workload =
      "builtin:npp-404..420 at " + size + ", 1 PERT, adaptive / non-adaptive / direct";
  std::vector<std::string> all_modes = breadth;
  all_modes.insert(all_modes.end(), nonadaptive.begin(), nonadaptive.end());
  all_modes.insert(all_modes.end(), direct.begin(), direct.end());
  plan.figures.push_back(Figure{
      .id = "P5a",
      .title = "PrimProcessor latency per ray (time per ray over direct memory's) against prim "
               "data-set size: non-adaptive slope over adaptive slope",
      .seed_ref = "seed 001 L1011 (Fig. 6-9, graph lost)",
      .seed_text = "\"the latency of non-adaptive broadcasting increases dramatically\" with the "
                   "data set; \"the adaptive curve increases slowly\"; the gap to direct memory is "
                   "the broadcasting overhead",
      .seed_value = 0,
      .seed_display = "> 3 (qualitative)",
      .unit = "ratio",
      .tolerance = Tolerance::above(3,
                                    "\"dramatically\" against \"slowly\": at least 3 times "
                                    "steeper"),
      .workload = mode_workload,
      .runs = all_modes,
      .measure =
          [a = breadth, na = nonadaptive, d = direct](const RunResults& r) {
            std::vector<double> x, ya, yn;
            for (std::size_t i = 0; i < a.size(); ++i) {
              x.push_back(stats_number(r, a[i], "gaudet.buses.prim.data_set_words"));
              ya.push_back(prim_time(r, a[i]) - prim_time(r, d[i]));
              yn.push_back(prim_time(r, na[i]) - prim_time(r, d[i]));
            }
            const double sa = slope(x, ya), sn = slope(x, yn);
            return Measured{sa > 0 ? sn / sa : std::numeric_limits<double>::infinity(),
                            "overhead over direct memory: adaptive " + join(ya) +
                                " us, non-adaptive " + join(yn) + " us per ray"};
          },
  });
  plan.figures.push_back(Figure{
      .id = "P5b",
      .title = "Direct memory is the floor: smallest adaptive over direct time per ray",
      .seed_ref = "seed 001 L1011",
      .seed_text = "the gap between the adaptive and direct-memory curves is the broadcasting "
                   "overhead",
      .seed_value = 0,
      .seed_display = "> 1 (qualitative)",
      .unit = "ratio",
      .tolerance = Tolerance::above(1, "broadcasting can only add latency"),
      .workload = mode_workload,
      .runs = all_modes,
      .measure =
          [a = breadth, d = direct](const RunResults& r) {
            double lo = std::numeric_limits<double>::infinity();
            std::vector<double> yd;
            for (std::size_t i = 0; i < a.size(); ++i) {
              yd.push_back(prim_time(r, d[i]));
              lo = std::min(lo, prim_time(r, a[i]) / yd.back());
            }
            return Measured{lo, "direct " + join(yd) + " us per ray"};
          },
  });
  plan.classify({"P5"}, FigureClass::kQualitative,
                {{.param = "pert.memory.first_access"}, {.param = "control.load_word_time"}});
}

void add_p6_one_pert_over_the_vax(Plan& plan, const PlanOptions& options) {
  const SpeedUpCurves curves(plan, options);
  // A single PERT had each processor's data in its own memory (L806): direct memory, no
  // broadcasting. The adaptive single PERT is printed beside it.
  const std::string one = PertRun{"412", "direct", "breadth", 1}.key();
  const std::string one_adaptive = PertRun{"412"}.key();
  const auto& size = curves.size;
  const auto& vax412 = curves.vax412;
  plan.figures.push_back(Figure{
      .id = "P6",
      .title = "One PERT against the VAX-11/750 (scene 412, each processor's data in its own "
               "memory)",
      .seed_ref = "seed 001 L1141 (after [CHIL85]), L806",
      .seed_text = "\"a single PERT runs 20 times faster than a VAX/750\"",
      .seed_value = 20,
      .unit = "x",
      .tolerance = Tolerance::relative(
          0.3,
          "[CHIL85]'s workload and microcode timings are not in the thesis; both machines "
          "here run the same search on the same scene (vax.search = shells)"),
      .workload = "builtin:npp-412 at " + size +
                  ": vax-750 with vax.search=shells, and "
                  "gaudet-pert with 1 PERT, broadcast.mode=direct (L806: a single PERT's "
                  "processors hold their data in their own memories)",
      .runs = {vax412, one, one_adaptive},
      .measure =
          [vax412, one, one_adaptive](const RunResults& r) {
            return Measured{speedup(r, vax412, one),
                            "with broadcasting (adaptive): " +
                                format_number(speedup(r, vax412, one_adaptive)) + "x"};
          },
  });
  plan.classify({"P6"}, FigureClass::kMeasured, against_vax_assumptions());
}

void add_p7_eight_perts_over_the_vax(Plan& plan, const PlanOptions& options) {
  const SpeedUpCurves curves(plan, options);
  const auto& size = curves.size;
  const auto& vax412 = curves.vax412;
  const std::string eight = PertRun{"412", "adaptive", "breadth", 8}.key();
  plan.figures.push_back(Figure{
      .id = "P7",
      .title = "Eight PERTs against the VAX-11/750 (scene 412, adaptive)",
      .seed_ref = "seed 001 L1135, L1143; prediction L1045",
      .seed_text = "\"two orders of magnitude improvement over a VAX/750 with only 8 PERTs\"",
      .seed_value = 100,
      .unit = "x",
      .tolerance = Tolerance::relative(0.4, "an order of magnitude claim (\"about 100\")"),
      .workload = "builtin:npp-412 at " + size + ", 8 PERTs, adaptive",
      .runs = {vax412, eight},
      .measure =
          [vax412, eight](const RunResults& r) {
            // The thesis's own prediction (L1045): time = (processing/ray + latency/ray +
            // pipelinewait/ray) x rays, rays = totalrays / n (L1047), for the PrimProcessor, with
            // latency/ray from the expected average latency (L1105): eal for each ray that
            // fetches packets.
            const auto prim = [&](const char* k) {
              return stats_number(r, eight, std::string("gaudet.prim.") + k);
            };
            const double rays = prim("rays");
            const double latency = prim("eal.eal_s") * prim("rays_with_packets") / rays;
            const double predicted_s =
                (prim("processing_per_ray_s") + latency + prim("pipeline_wait_per_ray_s")) * rays /
                8.0;
            const double vax_s = stats_number(r, vax412, "simulated_time_s");
            return Measured{speedup(r, vax412, eight),
                            "the thesis's prediction from this run (L1045 with eal, "
                            "PrimProcessor): " +
                                format_number(vax_s / predicted_s) + "x"};
          },
  });
  plan.classify({"P7"}, FigureClass::kMeasured, against_vax_assumptions());
}

void add_p8_first_packet_latency(Plan& plan, const PlanOptions& options) {
  const SpeedUpCurves curves(plan, options);
  const auto& size = curves.size;
  char letter = 'a';
  for (int n : {8, 64}) {
    const std::string key = PertRun{"412", "adaptive", "breadth", n}.key();
    plan.figures.push_back(Figure{
        .id = std::string("P8") + letter++,
        .title = "First-packet latency over the worst-case eal, " + std::to_string(n) + " PERTs",
        .seed_ref = "seed 001 L1064-L1099, L1105",
        .seed_text = "eal = sum P(n+i) L(n+i), a worst case: real results \"should be "
                     "significantly better\"",
        .seed_value = 1,
        .seed_display = "<= 1",
        .unit = "ratio",
        .tolerance = Tolerance::range(0, 1,
                                      "the analysis is a worst case (all requests at "
                                      "once, none shared)"),
        .workload = "builtin:npp-412 at " + size + ", " + std::to_string(n) + " PERTs, adaptive",
        .runs = {key},
        .measure =
            [key](const RunResults& r) {
              const double measured = us(r, key, "gaudet.prim.first_packet_latency_s");
              const double eal = us(r, key, "gaudet.prim.eal.eal_s");
              return Measured{measured / eal,
                              "measured " + format_number(measured) + " us, eal " +
                                  format_number(eal) + " us (p/r " +
                                  format_number(stats_number(r, key, "gaudet.prim.eal.p") /
                                                stats_number(r, key, "gaudet.prim.eal.r")) +
                                  ")"};
            },
    });
  }
  plan.classify({"P8"}, FigureClass::kQualitative,
                {{.param = "pert.memory.first_access"}, {.param = "pert.queue.shell_to_prim"}});
}

void add_p9_speed_up_curves(Plan& plan, const PlanOptions& options) {
  const SpeedUpCurves curves(plan, options);
  const auto& quick = curves.quick;
  const auto& size = curves.size;
  const auto& curve_runs = curves.curve_runs;
  auto efficiency = [](const RunResults& r, const std::string& s, const std::string& mode, int n) {
    const double t1 = stats_number(r, PertRun{s, mode, "breadth", 1}.key(), "simulated_time_s");
    const double tn = stats_number(r, PertRun{s, mode, "breadth", n}.key(), "simulated_time_s");
    return t1 / tn / n;
  };
  const int mid = quick ? 8 : 16;
  char letter = 'a';
  for (const char* m : {"direct", "non-adaptive"}) {
    const std::string mode = m;
    plan.figures.push_back(Figure{
        .id = std::string("P9") + letter++,
        .title = "Speed-up is near-linear with " + mode +
                 (mode == "direct" ? " memory" : " broadcasting") + ": efficiency at " +
                 std::to_string(mid) + " PERTs (scene 412)",
        .seed_ref = "seed 001 L1103-L1107",
        .seed_text = "Figs. 6-12..6-14: the direct-memory and non-adaptive curves are linear",
        .seed_value = 1,
        .seed_display = ">= 0.8",
        .unit = "",
        .tolerance = Tolerance::range(0.8, 1.05,
                                      "linear up to the static scanline split's load "
                                      "imbalance"),
        .workload =
            "builtin:npp-412 at " + size + ", " + mode + ", 1.." + std::to_string(mid) + " PERTs",
        .runs = curve_runs,
        .measure = [efficiency, mode,
                    mid](const RunResults& r) { return Measured{efficiency(r, "412", mode, mid)}; },
    });
  }
  plan.figures.push_back(Figure{
      .id = "P9c",
      .title = "Adaptive broadcasting bends as the cycle saturates: adaptive over direct "
               "speed-up at 64 PERTs (scene 412)",
      .seed_ref = "seed 001 L1047-L1049, L1105-L1107",
      .seed_text = "adaptive latency per ray grows with n; the adaptive curve bends toward the "
                   "non-adaptive line",
      .seed_value = 0,
      .seed_display = "< 0.9 (qualitative)",
      .unit = "ratio",
      .tolerance = Tolerance::range(0, 0.9, "a visible bend, not a straight line"),
      .workload = "builtin:npp-412 at " + size + ", 64 PERTs, adaptive and direct",
      .runs = curve_runs,
      .measure =
          [](const RunResults& r) {
            const double a = stats_number(r, PertRun{"412", "adaptive", "breadth", 64}.key(),
                                          "simulated_time_s");
            const double d =
                stats_number(r, PertRun{"412", "direct", "breadth", 64}.key(), "simulated_time_s");
            return Measured{d / a};
          },
  });
  plan.classify({"P9"}, FigureClass::kQualitative,
                {{.param = "pert.memory.first_access"},
                 {.param = "control.load_word_time"},
                 {.param = "pert.shade.rays_in_flight"}});
}

void add_speedup_csv(Plan& plan, const PlanOptions& options) {
  const SpeedUpCurves curves(plan, options);
  const auto& curve_scenes = curves.curve_scenes;
  const auto& curve_runs = curves.curve_runs;
  const auto& ns = curves.ns;
  plan.artifacts.push_back(Artifact{
      .file_name = "gaudet-speedup.csv",
      .runs = curve_runs,
      .contents =
          [curve_scenes, ns](const RunResults& r) {
            std::ostringstream o;
            o.precision(10);
            o << "scene,mode,pert_count,frame_s,vax_frame_s,speedup_over_vax\n";
            for (const auto& s : curve_scenes) {
              const double vax = stats_number(r, "vax-shells-" + s, "simulated_time_s");
              for (const char* m : {"direct", "non-adaptive", "adaptive"})
                for (int n : ns) {
                  const double t =
                      stats_number(r, PertRun{s, m, "breadth", n}.key(), "simulated_time_s");
                  o << s << "," << m << "," << n << "," << t << "," << vax << "," << vax / t
                    << "\n";
                }
            }
            return o.str();
          },
  });
}

// In the order `rtsim validate` lists them.
const RegisterFigures kP1TestScenes(kGaudetMachine, add_p1_test_scenes);
const RegisterFigures kP2P3ShellLatencyByTree(kGaudetMachine, add_p2_p3_shell_latency_by_tree);
const RegisterFigures kP4BroadcastOrder(kGaudetMachine, add_p4_broadcast_order);
const RegisterFigures kP5PrimTimeByMode(kGaudetMachine, add_p5_prim_time_by_mode);
const RegisterFigures kP6OnePertOverTheVax(kGaudetMachine, add_p6_one_pert_over_the_vax);
const RegisterFigures kP7EightPertsOverTheVax(kGaudetMachine, add_p7_eight_perts_over_the_vax);
const RegisterFigures kP8FirstPacketLatency(kGaudetMachine, add_p8_first_packet_latency);
const RegisterFigures kP9SpeedUpCurves(kGaudetMachine, add_p9_speed_up_curves);
const RegisterFigures kSpeedupCsv(kGaudetMachine, add_speedup_csv);

}  // namespace

}  // namespace rtsim::validation
