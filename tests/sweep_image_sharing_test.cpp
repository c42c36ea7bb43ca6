// A sweep renders each distinct image once (platform/sweep/image_sharing.hpp): points that differ
// only in parameters the image does not depend on run timing-only and get the first's image;
// the images are byte-identical to those every point renders with `share-images = false`, and
// the frame times are the same. A parameter the image depends on (shade.max_depth) makes images
// of their own; a sampled point renders only its detailed rows; `image = "none"` shares nothing;
// a bad `share-images` is refused.
#include <gtest/gtest.h>

#include <fstream>
#include <string>

#include "platform/machine_registry.hpp"
#include "tests/test_support.hpp"

namespace fs = std::filesystem;
using rtsim::test::read_file;
using rtsim::test::read_json;
using rtsim::test::run_rtsim;
using rtsim::test::scratch_dir;

namespace {

const std::string& peripheral() { return rtsim::platform::default_machine().name(); }

// 2 depths (image) x 2 ray-queue depths (timing) x sampled or not (timing).
std::string sweep_text(const std::string& extra) {
  return extra + "machine = \"" + peripheral() +
         "\"\n"
         "scene = \"builtin:ullner-cubes\"\n"
         "width = 24\n"
         "height = 16\n"
         "sample-window = 2\n"
         "[[axes]]\n"
         "param = \"shade.max_depth\"\n"
         "values = [0, 2]\n"
         "[[axes]]\n"
         "param = \"peripheral.ray_queue_depth\"\n"
         "values = [1, 4]\n"
         "[[axes]]\n"
         "param = \"sample\"\n"
         "values = [0, 2]\n";
}

fs::path run_sweep(const fs::path& dir, const std::string& name, const std::string& text,
                   std::string* listing = nullptr, const std::string& flags = "") {
  const fs::path file = dir / (name + ".toml");
  std::ofstream(file) << text;
  const fs::path out = dir / name;
  if (listing) {
    const auto l = run_rtsim("sweep " + file.string() + " --list --out " + out.string());
    EXPECT_EQ(l.exit_code, 0) << l.output;
    *listing = l.output;
  }
  const auto r = run_rtsim("sweep " + file.string() + " --jobs 2 --out " + out.string() + flags);
  EXPECT_EQ(r.exit_code, 0) << r.output;
  return out / "points";
}

std::string point(int i) {
  std::string s = std::to_string(i);
  return std::string(4 - s.size(), '0') + s;
}

}  // namespace

TEST(SweepImageSharing, EachImageOnceAndIdenticalToEveryPointsOwn) {
  const fs::path dir = scratch_dir("sweep-image-sharing");
  fs::create_directories(dir);
  std::string listing;
  const fs::path shared = run_sweep(dir, "shared", sweep_text(""), &listing, " --report");
  const fs::path own = run_sweep(dir, "own", sweep_text("share-images = false\n"));

  // Points 0-3 have depth 0, 4-7 depth 2: one image point each, the first; the other three
  // run timing-only.
  int timing_only = 0;
  for (int i = 0; i < 8; ++i) {
    const std::string key = point(i);
    const bool renders = i == 0 || i == 4;
    const auto line_at = listing.find(key + "  ");
    ASSERT_NE(line_at, std::string::npos) << listing;
    const std::string line = listing.substr(line_at, listing.find('\n', line_at) - line_at);
    EXPECT_EQ(line.find("--image none") == std::string::npos, renders) << line;

    const auto s = read_json(shared / key / "stats.json");
    const auto o = read_json(own / key / "stats.json");
    EXPECT_EQ(s["image"]["files"], renders ? "all" : "none") << key;
    EXPECT_EQ(o["image"]["files"], "all") << key;
    timing_only += renders ? 0 : 1;
    // The image in every folder is the one the point renders itself.
    for (const char* f : {"image.png", "image.exr"}) {
      ASSERT_TRUE(fs::exists(shared / key / f)) << key << "/" << f;
      EXPECT_TRUE(read_file(shared / key / f) == read_file(own / key / f)) << key << "/" << f;
    }
    // Timing-only changes no time: the same frame time, estimate and interval.
    EXPECT_EQ(s["simulated_time_s"], o["simulated_time_s"]) << key;
    if (o.contains("sample")) {
      EXPECT_EQ(s["sample"]["ci99_7_s"], o["sample"]["ci99_7_s"]) << key;
      // A sampled timing-only point renders its detailed rows only (and the work count's
      // subsample): fewer rays than the image point traced.
      if (!renders) {
        EXPECT_LT(s["rays"]["total"].get<double>(), o["rays"]["total"].get<double>()) << key;
      }
    } else {
      EXPECT_EQ(s["rays"], o["rays"]) << key;
    }
  }
  EXPECT_EQ(timing_only, 6);
  // The report shows each distinct image once, saying for how many points it stands.
  const std::string html = read_file(shared.parent_path() / "report.html");
  EXPECT_NE(html.find("alt=\"point 0000\""), std::string::npos);
  EXPECT_NE(html.find("alt=\"point 0004\""), std::string::npos);
  EXPECT_EQ(html.find("alt=\"point 0001\""), std::string::npos);
  EXPECT_NE(html.find("The 2 distinct images"), std::string::npos);
  EXPECT_NE(html.find("the image of 4 points"), std::string::npos);
  // The depths' images differ: the image point of each renders its own.
  EXPECT_FALSE(read_file(shared / point(0) / "image.png") ==
               read_file(shared / point(4) / "image.png"));
  fs::remove_all(dir);
}

TEST(SweepImageSharing, TimingOnlySweepsAndBadValues) {
  const fs::path dir = scratch_dir("sweep-image-sharing-none");
  fs::create_directories(dir);
  std::string listing;
  const fs::path none = run_sweep(dir, "none", sweep_text("image = \"none\"\n"), &listing);
  for (int i = 0; i < 8; ++i) {
    EXPECT_FALSE(fs::exists(none / point(i) / "image.png")) << i;
    EXPECT_EQ(read_json(none / point(i) / "stats.json")["image"]["files"], "none");
  }

  const fs::path bad = dir / "bad.toml";
  std::ofstream(bad) << sweep_text("share-images = 1\n");
  const auto r = run_rtsim("sweep " + bad.string() + " --list");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("bad.toml:1: 'share-images' must be true or false"), std::string::npos)
      << r.output;
  fs::remove_all(dir);
}
