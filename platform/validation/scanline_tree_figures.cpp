// Ullner's scan-line tree (seed 000 §3.3, L1062-L1667; note 000-ch3 §2.4-2.8): the T&C
// program's length against Fig. 3-16, the scan converter's segment time, the root bottleneck
// and how often merging processors meet intersecting segments. The frames are the thesis's 512
// lines at 30 frames a second (L1551), in both modes (a frame takes about a second).
#include <algorithm>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "platform/validation/figure_registry.hpp"

namespace rtsim::validation {

namespace {

constexpr const char* kTree = "ullner-scanline-tree";
constexpr double kMicro = 1e6;

RunRequest tree_run(std::string key, const std::string& scene, std::vector<std::string> params) {
  return machine_run_request(std::move(key), kTree, scene, 512, 512, params, 512.0 * 512.0);
}

/// builtin:ullner-mosaic-N split n levels, unpaced, on `lines` lines of 65.1 us (the frame rate
/// raised to keep 512 lines' line time, L1551): N columns give 2N visible segments a line.
RunRequest mosaic_run(int levels, int columns, int lines) {
  const double rate = 30.0 * 512.0 / lines;
  return machine_run_request("tree-mosaic-n" + std::to_string(levels), kTree,
                             "builtin:ullner-mosaic-" + std::to_string(columns), lines, lines,
                             {"pcp.paced=false", "pcp.frame_rate=" + format_number(rate) + " Hz",
                              "tree.split_levels=" + std::to_string(levels)},
                             16.0 * columns * lines);
}

/// Segments a line's time a run delivered at its strips' processors (unpaced: its bandwidth).
double segments_a_line(const RunResults& r, const std::string& key) {
  const double segments = stats_number(r, key, "scanline_tree.scan_out.root_segments");
  const double time = stats_number(r, key, "scanline_tree.scan_out.time_s");
  const double line = stats_number(r, key, "scanline_tree.scan_out.line_time_s");
  if (!(segments > 0.0 && time > 0.0)) throw MeasureError(key + ": the tree delivered nothing");
  return segments * line / time;
}

/// A run's share of merge passes by the stages they take (L1519): non-overlapping (1),
/// overlapping (2) and intersecting (5).
struct CaseShares {
  double apart = 0.0, overlapping = 0.0, intersecting = 0.0;
};
CaseShares case_shares(const RunResults& r, const std::string& key) {
  const auto passes = [&](const char* c) {
    return stats_number(r, key, std::string("scanline_tree.merge_passes.") + c);
  };
  const double apart = passes("apart"), intersects = passes("intersects");
  const double overlapping = passes("disappears") + passes("protrudes") + passes("hidden");
  const double total = apart + intersects + overlapping;
  if (!(total > 0.0)) throw MeasureError(key + ": no merge passes");
  return {apart / total, overlapping / total, intersects / total};
}

void add_scanline_tree_figures(Plan& plan, const PlanOptions&) {
  const std::string teapot = plan.add_run(tree_run("tree-teapot", "builtin:spd-teapot", {}));
  const std::string cubes = plan.add_run(tree_run("tree-cubes", "builtin:ullner-cubes", {}));
  // Ullner's own analytic scene (random squares, L608-L652): about 11 segments a line.
  const std::string random = plan.add_run(tree_run("tree-random", "builtin:ullner-random-100", {}));
  const std::string random_free =
      plan.add_run(tree_run("tree-random-free", "builtin:ullner-random-100", {"pcp.paced=false"}));
  const std::string workload = "builtin:spd-teapot (1000 polygons), 512 x 512";
  const std::string random_load =
      "builtin:ullner-random-100 (100 squares, 200 polygons), 512 x 512";

  // --- The T&C processors (L1325-L1336) ------------------------------------------------------
  plan.figures.push_back(Figure{
      .id = "ST1",
      .title = "The T&C program's instructions, counted from the program",
      .seed_ref = "seed 000 Fig. 3-16, L1325-L1334",
      .seed_text = "3652 instructions: vertex transformation 272, colour 153, clipping 1904, "
                   "perspective division 152, scan-conversion preprocessing 1171 (\"hand "
                   "compiling the programs, and then counting\")",
      .seed_value = 3652.0,
      .unit = "instructions",
      .tolerance = Tolerance::relative(
          0.15,
          "the thesis's instruction set and compiled code are not given; the model's are the "
          "processor L1274 describes and Figs. 3-10 to 3-15 written for it, with the leaving "
          "crossings the figures omit (L1210)"),
      .workload = workload + " (the program is the same for every lit scene)",
      .runs = {teapot},
      .measure =
          [teapot](const RunResults& r) {
            std::string parts;
            for (const char* t : {"vertex_transformation", "colour_computation", "clipping",
                                  "perspective_division", "scan_conversion_preprocessing"}) {
              if (!parts.empty()) parts += " / ";
              parts += std::to_string(static_cast<long>(
                  stats_number(r, teapot, std::string("scanline_tree.tc.tasks.") + t)));
            }
            return Measured{stats_number(r, teapot, "scanline_tree.tc.instructions"),
                            parts + " against 272 / 153 / 1904 / 152 / 1171"};
          },
      .figure_class = FigureClass::kDerived,
  });

  // --- The scan converters (L1348) -----------------------------------------------------------
  plan.figures.push_back(Figure{
      .id = "ST2",
      .title = "A segment over the scan converter's link",
      .seed_ref = "seed 000 L1348",
      .seed_text = "eleven 12-bit numbers, a wire each, \"at about 150 nanoseconds per bit ... a "
                   "little under two microseconds\" [D: 12 x 150 ns]",
      .seed_value = 1.8,
      .unit = "us",
      .tolerance = Tolerance::range(1.5, 2.0, "\"a little under two microseconds\""),
      .workload = workload,
      .runs = {teapot},
      .measure =
          [teapot](const RunResults& r) {
            const double bit = param_seconds(r, teapot, "scp.link.bit_time");
            const double lanes = param_number(r, teapot, "scp.link.lanes");
            const double bits_a_wire = std::ceil(132.0 / lanes);
            return Measured{bit * bits_a_wire * kMicro, "132 bits on the link's lanes"};
          },
      .figure_class = FigureClass::kDerived,
  });

  // --- The root bottleneck (L1551-L1557) -----------------------------------------------------
  plan.figures.push_back(Figure{
      .id = "ST3a",
      .title = "Segments the root delivers in a 512-line scan line's time",
      .seed_ref = "seed 000 L1551-L1553",
      .seed_text = "the root emits a segment \"every six microseconds or so\"; a line has about "
                   "65 us at 30 frames a second: \"only about ten or eleven segments\"",
      .seed_value = 10.5,
      .unit = "segments",
      .tolerance = Tolerance::relative(
          0.3,
          "the thesis's pace assumes the segments made by breaking balance those hidden "
          "(L1557); the model's root does the passes the scene gives it, several for some "
          "segments it sends"),
      .workload = random_load + "; pcp.paced = false (as fast as the tree delivers)",
      .runs = {random_free},
      .measure =
          [random_free](const RunResults& r) {
            const double segments =
                stats_number(r, random_free, "scanline_tree.scan_out.root_segments");
            const double time = stats_number(r, random_free, "scanline_tree.scan_out.time_s");
            const double line = stats_number(r, random_free, "scanline_tree.scan_out.line_time_s");
            if (!(segments > 0.0 && time > 0.0)) throw MeasureError("the root sent nothing");
            return Measured{segments * line / time,
                            "root segments / scan-out time x a line's time; " +
                                format_number(time / segments * kMicro) + " us a segment"};
          },
  });
  plan.figures.push_back(Figure{
      .id = "ST3b",
      .title = "A scene whose lines need more misses the frame",
      .seed_ref = "seed 000 L1553-L1555",
      .seed_text = "ten or eleven segments a line are \"fine for video games, but ... not "
                   "enough for most other applications\": the non-von Neumann bottleneck",
      .seed_value = 1.0,
      .seed_display = "> 1 frame",
      .unit = "frames",
      .tolerance = Tolerance::above(1.0,
                                    "the scan-out paced by the beam takes longer than a "
                                    "30th of a second"),
      .workload = workload + " (14 segments a line on average)",
      .runs = {teapot},
      .measure =
          [teapot](const RunResults& r) {
            const double time = stats_number(r, teapot, "scanline_tree.scan_out.time_s");
            const double late = stats_number(r, teapot, "scanline_tree.scan_out.late_lines");
            return Measured{time * 30.0, format_number(late) + " of 512 lines late"};
          },
      .figure_class = FigureClass::kQualitative,
  });

  // --- Merging (L1519) -----------------------------------------------------------------------
  plan.figures.push_back(Figure{
      .id = "ST4",
      .title = "Merge passes that find intersecting segments, the largest share of three scenes",
      .seed_ref = "seed 000 L1519",
      .seed_text = "\"intersections are relatively rare\": a merging processor's average time is "
                   "close to the 3 and 6 us of the other cases, not the 15 us of an intersection",
      .seed_value = 0.0,
      .seed_display = "rare",
      .unit = "",
      .tolerance = Tolerance::range(0.0, 0.05, "at most one pass in twenty"),
      .workload =
          "builtin:spd-teapot, builtin:ullner-cubes, builtin:ullner-random-100 at 512 x 512",
      .runs = {teapot, cubes, random},
      .measure =
          [teapot, cubes, random](const RunResults& r) {
            std::string detail;
            double most = 0.0;
            for (const auto& [key, name] : {std::pair{teapot, "teapot"}, std::pair{cubes, "cubes"},
                                            std::pair{random, "random squares"}}) {
              const CaseShares c = case_shares(r, key);
              most = std::max(most, c.intersecting);
              detail += (detail.empty() ? "" : "; ") + std::string(name) + " " +
                        format_number(100 * c.apart) + "% apart, " +
                        format_number(100 * c.overlapping) + "% overlapping, " +
                        format_number(100 * c.intersecting) + "% intersecting";
            }
            return Measured{most, detail};
          },
      .figure_class = FigureClass::kQualitative,
  });

  // --- Root splitting (L1561-L1637) ----------------------------------------------------------
  // Mosaics sized to each split's bandwidth (about 22 segments a line a root: 2^n x 11
  // columns), so each subtree's stream carries about a real-time line, as the seed assumes.
  const std::string unsplit = plan.add_run(mosaic_run(0, 22, 64));
  struct Split {
    int levels, columns, lines;
    const char* id;
    double seed;
  };
  std::vector<std::string> split_runs;
  for (const Split& s : {Split{1, 22, 64, "ST5a", 20}, Split{2, 44, 64, "ST5b", 40},
                         Split{4, 176, 64, "ST5c", 160}, Split{6, 704, 32, "ST5d", 640}}) {
    const std::string run = plan.add_run(mosaic_run(s.levels, s.columns, s.lines));
    split_runs.push_back(run);
    const double times = static_cast<double>(1 << s.levels);
    plan.figures.push_back(Figure{
        .id = s.id,
        .title = "The bandwidth of a root split " + std::to_string(s.levels) +
                 (s.levels == 1 ? " level" : " levels") + ", over the unsplit root's",
        .seed_ref = "seed 000 L1583-L1594, Figs. 3-23, 3-24",
        .seed_text = "replacing n levels increases the output by 2^n: \"about twenty\" segments "
                     "a line at n = 1, 40 at 2, 160 at 4 (Fig. 3-24), 640 at 6, over the root's "
                     "ten or eleven [D: " +
                     format_number(s.seed) + " / 10]",
        .seed_value = times,
        .unit = "x",
        .tolerance = Tolerance::range(
            0.6 * times, 1.05 * times,
            "the seed's 2^n holds \"if everything in the new root can run at full speed\" "
            "(L1583); with queues of a line's segments (L1637) the strips wait for each other "
            "line by line, so the model delivers less, and less as n grows; under 0.6 2^n "
            "splitting would not give most of what it promises"),
        .workload = "builtin:ullner-mosaic-" + std::to_string(s.columns) + " (" +
                    std::to_string(2 * s.columns) + " visible segments a line, none hidden), " +
                    std::to_string(s.lines) +
                    " lines of 65.1 us, pcp.paced = false; against builtin:ullner-mosaic-22 "
                    "unsplit",
        .runs = {unsplit, run},
        .measure =
            [unsplit, run, seed = s.seed](const RunResults& r) {
              const double root = segments_a_line(r, unsplit), split = segments_a_line(r, run);
              const double splitters =
                  stats_number(r, run, "scanline_tree.split.splitting_processors");
              const double extra =
                  stats_number(r, run, "scanline_tree.split.extra_merging_processors");
              return Measured{split / root,
                              format_number(split) +
                                  " segments a line against the unsplit "
                                  "root's " +
                                  format_number(root) + " (seed: " + format_number(seed) +
                                  " against 10.5; the model's non-overlapping pass is 3 us, "
                                  "the seed's pace 6); " +
                                  format_number(splitters) + " splitting and " +
                                  format_number(extra) + " extra merging processors"};
            },
    });
  }
  plan.figures.push_back(Figure{
      .id = "ST6",
      .title = "What a splitting processor's queue must hold, the same at every stage and "
               "every split",
      .seed_ref = "seed 000 L1633-L1637",
      .seed_text = "\"the amount of memory required for buffering segments does not depend upon "
                   "the position of the processor within the tree ... [or] the number of other "
                   "splitting processors\": about a scan line's segments",
      .seed_value = 1.0,
      .seed_display = "the same",
      .unit = "x",
      .tolerance = Tolerance::range(1.0, 1.5,
                                    "the largest stage's need over the smallest's, over the "
                                    "stages of the four splits"),
      .workload = "the runs of ST5a-d: the most segments one line brought to a splitting "
                  "processor, stage by stage",
      .runs = split_runs,
      .measure =
          [split_runs](const RunResults& r) {
            double lo = 0.0, hi = 0.0;
            std::string detail;
            for (const std::string& key : split_runs) {
              const nlohmann::json& tree = stats_of(r, key)["scanline_tree"];
              if (!tree.is_object() || !tree.contains("split"))
                throw MeasureError(key + ": no scanline_tree.split");
              const nlohmann::json& stages = tree["split"]["line_segments_max_by_stage"];
              if (!stages.is_array() || stages.empty())
                throw MeasureError(key + ": no splitting processors");
              detail += (detail.empty() ? "" : "; ");
              std::string row;
              for (const auto& v : stages) {
                const double need = v.get<double>();
                lo = lo > 0.0 ? std::min(lo, need) : need;
                hi = std::max(hi, need);
                row += (row.empty() ? "" : ", ") + format_number(need);
              }
              detail += row;
            }
            return Measured{hi / lo, "segments by stage: " + detail +
                                         " (a line's time over a 3 us pass is 21.7)"};
          },
  });
}

const RegisterFigures kRegistered(kTree, add_scanline_tree_figures);

}  // namespace

}  // namespace rtsim::validation
