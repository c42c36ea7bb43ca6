// Mueller's sort-first architecture (seed 004 L454-L602; note 004 "Paper 4"): the coherence
// study's migration table (L570-L577) on the stand-in for its PLB head, spun as the study spun
// it, and the way migration grows with the region count (L597).
#include <string>
#include <vector>

#include "platform/validation/figure_registry.hpp"

namespace rtsim::validation {

namespace {

constexpr const char* kSortFirst = "sort-first";

/// The PLB test (L570-L572): builtin:plb-head at the screen's centre, spun 4.5 degrees a frame,
/// 80 frames (20 in quick mode), on an N x N partition. The resolution is irrelevant to the
/// study (L568); 256 x 256 keeps a region of the 16 x 16 partition 16 pixels wide.
RunRequest plb_run(int side, bool quick) {
  const int frames = quick ? 20 : 80;
  return machine_run_request(
      "sf-plb-" + std::to_string(side), kSortFirst, "builtin:plb-head", 256, 256,
      {"regions=" + std::to_string(side), "frames=" + std::to_string(frames), "camera.spin=4.5"},
      6e4 * frames * (1.0 + side / 8.0));
}

double mean_migrated(const RunResults& r, const std::string& key) {
  return stats_number(r, key, "sort_first.migrated_percent.mean");
}

std::string table_note(const RunResults& r, const std::string& key) {
  const auto n = [&](const char* k) {
    return format_number(stats_number(r, key, std::string("sort_first.migrated_percent.") + k));
  };
  return "mean " + n("mean") + "%, high " + n("high") + ", std-dev " + n("std_dev") + ", 95-% " +
         n("p95") + " over " + n("frames") + " frames after the first";
}

void add_sort_first_figures(Plan& plan, const PlanOptions& options) {
  struct Grid {
    int side;
    const char* id;
    double mean, high, sd, p95;
  };
  const std::vector<Grid> grids = {{4, "SF1a", 4.06, 5.19, 0.54, 5.07},
                                   {8, "SF1b", 8.80, 10.30, 0.70, 9.92},
                                   {16, "SF1c", 18.07, 20.80, 1.05, 20.06}};
  std::vector<std::string> keys;
  const std::string workload_tail =
      " frames of builtin:plb-head (59,536 triangles, the "
      "stand-in for the 59,592-polygon scan) spun 4.5 degrees a "
      "frame at the screen's centre, 256 x 256";
  const std::string frames = options.quick ? "20" : "80";
  for (const Grid& g : grids) {
    const std::string key = plan.add_run(plb_run(g.side, options.quick));
    keys.push_back(key);
    const std::string grid = std::to_string(g.side) + "x" + std::to_string(g.side);
    plan.figures.push_back(Figure{
        .id = g.id,
        .title = "Primitives migrated a frame on a " + grid + " partition, the PLB head spun",
        .seed_ref = "seed 004 L570-L577 (PLB head table), L560-L568 (setup)",
        .seed_text = "PLB head, 59,592 polygons, 80 frames, 4.5 degrees an iteration, " + grid +
                     " regions: mean " + format_number(g.mean) + " %, high " +
                     format_number(g.high) + ", std-dev " + format_number(g.sd) + ", 95-% " +
                     format_number(g.p95),
        .seed_value = g.mean,
        .unit = "%",
        .tolerance = Tolerance::relative(
            0.3,
            "the stand-in is not the scan: how many of its triangles lie on region borders "
            "depends on their screen size and on where the surface is, which a head-like "
            "ellipsoid matches only roughly; the spin, the placement, the count and the "
            "classification are the study's. Twice the spin (9 degrees) roughly doubles the "
            "figure and fails the row"),
        .workload = frames + workload_tail + ", " + grid + " regions",
        .runs = {key},
        .measure =
            [key](const RunResults& r) {
              return Measured{mean_migrated(r, key), table_note(r, key)};
            },
    });
  }
  // L597: "increasing the number of regions increases the percentage of primitives that are
  // communicated"; the table roughly doubles with each doubling of the regions a side.
  const std::vector<std::pair<int, const char*>> steps = {{0, "SF2a"}, {1, "SF2b"}};
  for (const auto& [i, id] : steps) {
    const Grid& lo = grids[static_cast<std::size_t>(i)];
    const Grid& hi = grids[static_cast<std::size_t>(i + 1)];
    const std::string lo_key = keys[static_cast<std::size_t>(i)];
    const std::string hi_key = keys[static_cast<std::size_t>(i + 1)];
    const std::string names = std::to_string(hi.side) + "x" + std::to_string(hi.side) + " over " +
                              std::to_string(lo.side) + "x" + std::to_string(lo.side);
    plan.figures.push_back(Figure{
        .id = id,
        .title = "Migration grows with the regions: " + names,
        .seed_ref = "seed 004 L597, L570-L577",
        .seed_text = "\"increasing the number of regions increases the percentage of primitives "
                     "that are communicated\": PLB " +
                     format_number(hi.mean) + " / " + format_number(lo.mean) + " = " +
                     format_number(hi.mean / lo.mean),
        .seed_value = hi.mean / lo.mean,
        .unit = "x",
        .tolerance = Tolerance::range(
            1.6, 2.6,
            "twice the regions a side doubles the border length a primitive can cross; a "
            "ratio under 1.6 or over 2.6 is no longer the table's doubling"),
        .workload = "the runs of " + std::string(grids[static_cast<std::size_t>(i)].id) + " and " +
                    grids[static_cast<std::size_t>(i + 1)].id,
        .runs = {lo_key, hi_key},
        .measure =
            [lo_key, hi_key](const RunResults& r) {
              const double a = mean_migrated(r, lo_key), b = mean_migrated(r, hi_key);
              if (!(a > 0.0)) throw MeasureError(lo_key + ": nothing migrated");
              return Measured{b / a, format_number(b) + " % over " + format_number(a) + " %"};
            },
        .figure_class = FigureClass::kQualitative,
    });
  }

  // L601: "for moderately interactive applications (PLB, Xfront), 95% of the rendered frames
  // require reshuffling of only about 20% of the primitives or less" (PLB 16x16: 20.06).
  const std::string plb16 = keys.back();
  plan.figures.push_back(Figure{
      .id = "SF3",
      .title = "95th percentile of migration on the spun head, 16x16 regions",
      .seed_ref = "seed 004 L599-L601, L570-L577",
      .seed_text = "\"95% of the rendered frames require reshuffling of only about 20% of the "
                   "primitives or less\" (PLB 16x16: 20.06)",
      .seed_value = 20.06,
      .unit = "%",
      .tolerance = Tolerance::range(0.0, 22.0,
                                    "\"about 20% or less\": up to a tenth over 20%; a faster "
                                    "spin (9 degrees a frame) doubles it and fails the row"),
      .workload = "the run of SF1c",
      .runs = {plb16},
      .measure =
          [plb16](const RunResults& r) {
            return Measured{stats_number(r, plb16, "sort_first.migrated_percent.p95"),
                            table_note(r, plb16)};
          },
      .figure_class = FigureClass::kQualitative,
  });

  // L597-L599: the Sierra path's abrupt resets move primitives into other regions all at once,
  // and a primitive covering several regions is sent to each: the high exceeds 100%.
  const int fly_frames = options.quick ? 40 : 60;
  const std::string fly = plan.add_run(
      machine_run_request("sf-fly-16", kSortFirst, "builtin:bowling", 256, 256,
                          {"regions=16", "frames=" + std::to_string(fly_frames), "camera.path=fly",
                           "camera.sequence=20", "camera.dolly=0.02", "camera.spin=4.5"},
                          5e4 * fly_frames * 3.0));
  plan.figures.push_back(Figure{
      .id = "SF4",
      .title = "The most primitives migrated in one frame of a path with abrupt resets, 16x16",
      .seed_ref = "seed 004 L588-L599 (Sierra table)",
      .seed_text = "Sierra, \"zooms, rotations, and translations, with an abrupt reset between "
                   "each sequence\": high 107.38 % at 16x16; \"these exceeded 100% ... since "
                   "primitives which fall into multiple regions may need to be sent more than "
                   "once\"",
      .seed_value = 107.38,
      .unit = "%",
      .tolerance = Tolerance::above(100.0,
                                    "over 100%: a reset moves nearly every primitive, and the "
                                    "multi-region ones more than once; a path without resets "
                                    "(camera.sequence of the whole path) stays near its mean"),
      .workload = std::to_string(fly_frames) +
                  " frames of builtin:bowling (10,704 triangles), sequences of 20 "
                  "frames closing in 2% and turning 4.5 degrees a frame, reset between, 256 x "
                  "256, 16x16 regions",
      .runs = {fly},
      .measure =
          [fly](const RunResults& r) {
            return Measured{stats_number(r, fly, "sort_first.migrated_percent.high"),
                            table_note(r, fly)};
          },
      .figure_class = FigureClass::kQualitative,
  });

  // L531-L546: sort-first moves only the primitives that cross regions, and its traffic does not
  // grow with the display's pixels; sort-middle routes every primitive every frame (L511); sort-
  // last composites full-screen images, whose traffic does (L519).
  const auto sort_run = [&](const std::string& sort, int size) {
    return plan.add_run(machine_run_request(
        "sf-" + sort + "-" + std::to_string(size), kSortFirst, "builtin:plb-head", size, size,
        {"sort=" + sort, "regions=4", "frames=" + std::string(options.quick ? "5" : "10")},
        6e4 * 10 * 2.0));
  };
  const std::string first_lo = sort_run("first", 128), first_hi = sort_run("first", 512);
  const std::string middle_hi = sort_run("middle", 512);
  const std::string last_lo = sort_run("last", 128), last_hi = sort_run("last", 512);
  // Bytes a frame of one class, over the frames after the first.
  const auto mean_bytes = [](const RunResults& r, const std::string& key, const char* cls) {
    const nlohmann::json& frames = stats_of(r, key)["sort_first"]["per_frame"];
    if (!frames.is_array() || frames.size() < 2) throw MeasureError(key + ": no frames");
    double sum = 0.0;
    for (std::size_t f = 1; f < frames.size(); ++f) sum += frames[f]["bytes"][cls].get<double>();
    return sum / static_cast<double>(frames.size() - 1);
  };
  plan.figures.push_back(Figure{
      .id = "SF5a",
      .title = "Sort-first's redistribution a frame at 16 times the pixels, over 128 x 128's",
      .seed_ref = "seed 004 L463, L531-L546",
      .seed_text = "only primitives crossing region boundaries are communicated, and only "
                   "finished pixels go to the frame buffer: sort-first \"can easily handle very "
                   "high resolution displays\" [its primitive traffic does not grow with them]",
      .seed_value = 1.0,
      .seed_display = "the same",
      .unit = "x",
      .tolerance = Tolerance::range(0.8, 1.25,
                                    "the screen boxes' pixels round region borders a little "
                                    "differently; a traffic that grew with the pixels would "
                                    "be 16 times"),
      .workload = "builtin:plb-head spun 4.5 degrees a frame, 4x4 regions, 128 x 128 and 512 x "
                  "512, sort = first",
      .runs = {first_lo, first_hi},
      .measure =
          [=](const RunResults& r) {
            const double lo = mean_bytes(r, first_lo, "redistribution");
            const double hi = mean_bytes(r, first_hi, "redistribution");
            if (!(lo > 0.0)) throw MeasureError(first_lo + ": nothing redistributed");
            return Measured{hi / lo, format_number(hi) + " bytes a frame at 512 x 512, " +
                                         format_number(lo) + " at 128 x 128"};
          },
      .figure_class = FigureClass::kQualitative,
  });
  plan.figures.push_back(Figure{
      .id = "SF5b",
      .title = "Sort-first's redistribution a frame over sort-middle's, the same frames",
      .seed_ref = "seed 004 L509-L511, L535-L538",
      .seed_text = "sort-middle: \"all of the transformed primitives must be routed\" every "
                   "frame; sort-first: \"only a fraction of them will have to be "
                   "communicated\"",
      .seed_value = 0.0,
      .seed_display = "a fraction",
      .unit = "x",
      .tolerance = Tolerance::range(0.0, 0.2,
                                    "a fifth at most: the spun head moves 4% of its primitives "
                                    "a frame at 4x4 (SF1a), sort-middle routes all of them"),
      .workload = "builtin:plb-head spun 4.5 degrees a frame, 4x4 regions, 512 x 512, sort = "
                  "first and sort = middle",
      .runs = {first_hi, middle_hi},
      .measure =
          [=](const RunResults& r) {
            const double first = mean_bytes(r, first_hi, "redistribution");
            const double middle = mean_bytes(r, middle_hi, "redistribution");
            if (!(middle > 0.0)) throw MeasureError(middle_hi + ": nothing routed");
            return Measured{first / middle, format_number(first) + " bytes a frame against " +
                                                format_number(middle)};
          },
      .figure_class = FigureClass::kQualitative,
  });
  plan.figures.push_back(Figure{
      .id = "SF5c",
      .title = "Sort-last's composition traffic a frame at 16 times the pixels, over 128 x 128's",
      .seed_ref = "seed 004 L517-L519",
      .seed_text = "sort-last's \"pixel budget is limited by the bandwidth available at the "
                   "composition stage\": every processor's full-area image is composited",
      .seed_value = 16.0,
      .unit = "x",
      .tolerance = Tolerance::relative(0.01,
                                       "the partial images' bytes are the pixels times "
                                       "the renderers times a 34-byte record"),
      .workload = "builtin:plb-head, 4x4 regions, 128 x 128 and 512 x 512, sort = last",
      .runs = {last_lo, last_hi},
      .measure =
          [=](const RunResults& r) {
            const double lo = mean_bytes(r, last_lo, "partial");
            const double hi = mean_bytes(r, last_hi, "partial");
            if (!(lo > 0.0)) throw MeasureError(last_lo + ": nothing composited");
            return Measured{hi / lo, format_number(hi) + " bytes a frame at 512 x 512, " +
                                         format_number(lo) + " at 128 x 128"};
          },
      .figure_class = FigureClass::kDerived,
  });
}

const RegisterFigures kRegistered(kSortFirst, add_sort_first_figures);

}  // namespace

}  // namespace rtsim::validation
