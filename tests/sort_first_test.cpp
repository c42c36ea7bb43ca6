// sort-first (platform/machines/sort_first/, firmware/sortfirst/): a primitive's record holds
// its triangle exactly in single precision; the regions partition the screen; classification by
// screen box gives each region every triangle that covers one of its samples (the frame rendered
// region by region equals the frame rendered whole); the renderers' stores, run through a camera
// path, hold exactly what their regions need and send exactly the twin's migration count; the
// machine's image is the twin's whatever the timing, and a record corrupted in flight changes it;
// its time comes from its modules (a slower ring or renderer moves it).
#include <gtest/gtest.h>

#include <map>
#include <set>
#include <string>

#include "firmware/sortfirst/primitive_record.hpp"
#include "firmware/sortfirst/region_store.hpp"
#include "platform/machines/sort_first/frame_data.hpp"
#include "scenes/scene_loader.hpp"
#include "tests/test_support.hpp"

namespace {

using namespace rtsim;
using rtsim::test::read_file;
using rtsim::test::run_machine;
using rtsim::test::run_rtsim;
using rtsim::test::scratch_dir;

const std::string kMachine = "sort-first";
const std::string kTeapot = "--scene builtin:spd-teapot --width 160 --height 120";

scenes::Scene teapot() {
  return scenes::make_builtin_scene("spd-teapot", scenes::default_generator_seeds());
}

TEST(SortFirstRecord, PacksATriangleInSinglePrecisionAndRefusesWhatIsNotAFloat) {
  raster::RasterTriangle t;
  t.v[0].position = Vec3(0.5, -1.25, 3.0);
  t.v[1].position = Vec3(0.1, 0.2, 0.3);
  t.v[2].normal = Vec3(0.0, 1.0, 0.0);
  t.v[1].uv = glm::dvec2(0.25, 0.75);
  t.face_normal = Vec3(0.0, 0.0, 1.0);
  t.material = 2;
  t.one_sided = true;
  t.primitive = 77;
  const sortfirst::PrimitiveRecord r = sortfirst::pack(t, 12345);
  EXPECT_EQ(sortfirst::record_id(r), 12345u);
  const auto back = sortfirst::unpack(r, 3);
  ASSERT_TRUE(back.has_value());
  EXPECT_EQ(back->v[0].position, t.v[0].position);  // exact in a float
  EXPECT_FLOAT_EQ(static_cast<float>(back->v[1].position.x), 0.1f);
  EXPECT_EQ(back->material, 2u);
  EXPECT_TRUE(back->one_sided);
  EXPECT_EQ(back->primitive, 77u);
  // Stored once, a record packs to the same words again.
  EXPECT_EQ(sortfirst::pack(*back, 12345).words, r.words);
  // A material past the scene's, or an exponent of all ones (inf or NaN), is refused.
  EXPECT_FALSE(sortfirst::unpack(r, 2).has_value());
  sortfirst::PrimitiveRecord bad = r;
  bad.words[4] |= 0x7F800000u;
  EXPECT_FALSE(sortfirst::unpack(bad, 3).has_value());
}

TEST(SortFirstRegions, PartitionTheScreenWhateverItsSize) {
  for (const int side : {1, 3, 4, 16, 32})
    for (const auto& [w, h] : {std::pair{64, 64}, std::pair{160, 120}, std::pair{17, 5}}) {
      SCOPED_TRACE(std::to_string(side) + " " + std::to_string(w) + "x" + std::to_string(h));
      const sortfirst::ScreenRegions g{side, w, h};
      EXPECT_EQ(g.x0(0), 0);
      EXPECT_EQ(g.x0(side), w);
      for (int x = 0; x < w; ++x) {
        const int c = g.col_of(x);
        EXPECT_LE(g.x0(c), x);
        EXPECT_LT(x, g.x0(c + 1));
      }
      for (int y = 0; y < h; ++y) {
        const int r = g.row_of(y);
        EXPECT_LE(g.y0(r), y);
        EXPECT_LT(y, g.y0(r + 1));
      }
    }
}

TEST(SortFirstClassify, ABoxOffTheScreenOrBehindTheEyeCoversNothing) {
  raster::ViewTransform view;
  view.width = view.height = 100;
  view.centre_x = view.centre_y = 50.0;
  view.pixel = 0.01;
  view.near = 0.1;
  const sortfirst::ScreenRegions g{4, 100, 100};
  raster::RasterTriangle t;
  t.v[0].position = Vec3(-0.1, 0.1, 1.0);  // screen (40, 40)
  t.v[1].position = Vec3(0.1, 0.1, 1.0);   // (60, 40)
  t.v[2].position = Vec3(0.0, -0.3, 1.0);  // (50, 80)
  const auto r = sortfirst::classify(t, view, g);
  ASSERT_TRUE(r.on_screen);
  EXPECT_EQ(r.c0, 1);
  EXPECT_EQ(r.c1, 2);
  EXPECT_EQ(r.r0, 1);
  EXPECT_EQ(r.r1, 3);
  EXPECT_EQ(g.owner(r), g.index(1, 1));  // the upper-left region (L564)
  EXPECT_EQ(r.count(), 6);
  raster::RasterTriangle behind = t;
  for (auto& v : behind.v) v.position.z = -1.0;
  EXPECT_FALSE(sortfirst::classify(behind, view, g).on_screen);
  raster::RasterTriangle aside = t;
  for (auto& v : aside.v) v.position.x += 5.0;
  EXPECT_FALSE(sortfirst::classify(aside, view, g).on_screen);
  // A triangle through the near plane is clipped to it, not lost.
  raster::RasterTriangle through = t;
  through.v[2].position.z = -1.0;
  EXPECT_TRUE(sortfirst::classify(through, view, g).on_screen);
}

TEST(SortFirstTwin, RegionByRegionIsTheWholeFrame) {
  // Every sample's triangles reach its region: a partition changes no pixel.
  const scenes::Scene scene = teapot();
  const raster::MeshSettings mesh;
  std::vector<float> whole;
  for (const int side : {1, 3, 8, 16}) {
    platform::sort_first::FrameData data;
    platform::sort_first::make_frame_data(data, scene, mesh, shading::ShadeParams{}, side, 96, 72);
    functional::FrameState frame(96, 72, 1, false, false);
    platform::sort_first::render_frame(
        data, platform::sort_first::frame_view(scene, data.mesh, 96, 72, 0, 1, {}), frame);
    const auto result = frame.finish(0.0);
    if (side == 1)
      whole = result.rgb;
    else
      EXPECT_EQ(result.rgb, whole) << side << "x" << side;
  }
}

TEST(SortFirstStore, RenderersHoldWhatTheirRegionsNeedAndSendTheTwinsCount) {
  const scenes::Scene scene = teapot();
  platform::sort_first::FrameData data;
  const int side = 4, w = 128, h = 96, frames = 6;
  platform::sort_first::make_frame_data(data, scene, raster::MeshSettings{}, shading::ShadeParams{},
                                        side, w, h);
  std::vector<raster::ViewTransform> views;
  for (int f = 0; f < frames; ++f)
    views.push_back(
        platform::sort_first::frame_view(scene, data.mesh, w, h, f, frames, {.spin = 25.0}));
  const auto initial = sortfirst::random_distribution(data.mesh.triangles.size(), 16, 7);
  std::vector<sortfirst::RegionStore> stores;
  for (int k = 0; k < 16; ++k) stores.emplace_back(k, data.regions, data.shading.words.size());
  for (std::uint32_t i = 0; i < data.mesh.triangles.size(); ++i)
    stores[static_cast<std::size_t>(initial[i])].load(sortfirst::pack(data.mesh.triangles[i], i));
  const auto expected = sortfirst::migration_counts(data.mesh, views, data.regions, initial);
  const auto n = static_cast<std::uint32_t>(data.mesh.triangles.size());
  for (int f = 0; f < frames; ++f) {
    SCOPED_TRACE(f);
    std::vector<std::vector<sortfirst::PrimitiveRecord>> inbox(16);
    std::uint64_t sent = 0;
    for (auto& s : stores)
      for (const auto& m : s.classify_all(views[static_cast<std::size_t>(f)]).sends) {
        inbox[static_cast<std::size_t>(m.to)].push_back(m.record);
        ++sent;
      }
    EXPECT_EQ(sent, expected[static_cast<std::size_t>(f)]);
    std::uint64_t refused = 0;
    for (int k = 0; k < 16; ++k)
      for (const auto& r : inbox[static_cast<std::size_t>(k)])
        refused +=
            stores[static_cast<std::size_t>(k)].receive(r, views[static_cast<std::size_t>(f)], n)
                ? 0
                : 1;
    EXPECT_EQ(refused, 0u);
    // Each region holds exactly the triangles whose box covers it; every primitive has one owner.
    std::size_t masters = 0;
    for (int k = 0; k < 16; ++k) {
      std::multiset<std::uint32_t> held, needed;
      for (const auto& t : stores[static_cast<std::size_t>(k)].to_render().triangles)
        held.insert(t.primitive * 4096u + static_cast<std::uint32_t>(t.v[0].position.x * 1000.0));
      for (const auto& t : data.mesh.triangles)
        if (sortfirst::classify(t, views[static_cast<std::size_t>(f)], data.regions)
                .covers(k / side, k % side))
          needed.insert(t.primitive * 4096u +
                        static_cast<std::uint32_t>(t.v[0].position.x * 1000.0));
      EXPECT_EQ(held, needed) << "region " << k;
      masters += stores[static_cast<std::size_t>(k)].masters();
    }
    EXPECT_EQ(masters, data.mesh.triangles.size());
  }
  // Frame 0 redistributes the random distribution: most primitives move.
  EXPECT_GT(expected[0], data.mesh.triangles.size() / 2);
}

TEST(SortFirst, TheImageIsTheTwinsWhateverTheTimingAndTheMigrationIsTheTwins) {
  const auto dir = scratch_dir("sort-first-render");
  const auto r =
      run_rtsim("render --machine " + kMachine + " " + kTeapot + " -q --out " + dir.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  for (const std::string& p :
       {std::string(" -p regions=8 -p frames=5 -p camera.spin=20"),
        std::string(" -p regions=4 -p frames=3 -p interconnect=mesh -p camera.path=fly"),
        std::string(" -p regions=4 -p frames=3 -p sort=middle -p interconnect=mesh"),
        std::string(" -p regions=3 -p frames=2 -p sort=last"),
        std::string(" -p regions=3 -p frames=4 -p ring.bandwidth=\"50 Mbit/s\" -p "
                    "renderer.triangle_time=\"40 us\" -p ring.service=one_packet")}) {
    SCOPED_TRACE(p);
    const auto s = run_machine(kMachine, "image", kTeapot + p);
    ASSERT_FALSE(s.empty());
    EXPECT_EQ(read_file(s["image_png"].get<std::string>()), read_file(dir / "image.png"));
  }
  // The records the renderers counted sending are the twin's migration, frame by frame.
  const auto s =
      run_machine(kMachine, "counts", kTeapot + " -p regions=8 -p frames=5 -p camera.spin=20");
  ASSERT_FALSE(s.empty());
  const scenes::Scene scene = teapot();
  platform::sort_first::FrameData data;
  platform::sort_first::make_frame_data(data, scene, raster::MeshSettings{}, shading::ShadeParams{},
                                        8, 160, 120);
  std::vector<raster::ViewTransform> views;
  for (int f = 0; f < 5; ++f)
    views.push_back(
        platform::sort_first::frame_view(scene, data.mesh, 160, 120, f, 5, {.spin = 20.0}));
  const auto counts = sortfirst::migration_counts(
      data.mesh, views, data.regions,
      sortfirst::random_distribution(data.mesh.triangles.size(), 64, 1995));
  const auto& frames = s["sort_first"]["per_frame"];
  ASSERT_EQ(frames.size(), 5u);
  for (std::size_t f = 0; f < 5; ++f)
    EXPECT_EQ(frames[f]["records_migrated"].get<std::uint64_t>(), counts[f]) << f;
}

TEST(SortFirst, TimeComesFromTheModules) {
  const std::string path = kTeapot + " -p frames=3";
  const auto base = run_machine(kMachine, "base", path);
  const auto slow_ring = run_machine(kMachine, "ring", path + " -p ring.bandwidth=\"20 Mbit/s\"");
  const auto slow_setup =
      run_machine(kMachine, "setup", path + " -p renderer.triangle_time=\"40 us\"");
  ASSERT_FALSE(base.empty() || slow_ring.empty() || slow_setup.empty());
  const auto frame_time = [](const nlohmann::ordered_json& s) {
    return s["sort_first"]["per_frame"][2]["time_s"].get<double>();
  };
  // 160 x 120 pixels of 3 bytes at 20 Mbit/s: 23 ms of pixels alone.
  EXPECT_GT(frame_time(slow_ring), frame_time(base) + 0.02);
  EXPECT_GT(frame_time(slow_setup), frame_time(base) * 2.0);
  // The busiest renderer's load, over the mean: a teapot in the middle loads the middle regions.
  EXPECT_GT(base["sort_first"]["per_frame"][2]["load_imbalance"].get<double>(), 1.2);
}

TEST(SortFirst, ARecordCorruptedInFlightChangesTheImage) {
  const std::string path = kTeapot + " -p frames=3";
  const auto good = run_machine(kMachine, "good", path);
  // Record 10's first vertex's y, its exponent's low bit: the triangle is stretched.
  const auto bad = run_machine(kMachine, "fault", path + " --fault migration:301:0x00800000");
  ASSERT_FALSE(good.empty() || bad.empty());
  EXPECT_NE(read_file(good["image_png"].get<std::string>()),
            read_file(bad["image_png"].get<std::string>()));
  EXPECT_TRUE(bad["sort_first"]["faults_in_flight"][0]["applied"].get<bool>());
  // A word past what migrated: exit 2, saying how many did, and no output.
  const auto dir = scratch_dir("sort-first-past");
  const auto r = run_rtsim("run --machine " + kMachine + " " + path +
                           " -q --fault migration:99999999:1 --out " + dir.string());
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("words of records"), std::string::npos) << r.output;
  EXPECT_FALSE(std::filesystem::exists(dir / "image.png"));
  // A fly path whose dolly brings the eye onto the point it looks at: exit 2, before the run.
  const auto eye = run_rtsim("run --machine " + kMachine + " " + path +
                             " -p camera.path=fly -p camera.dolly=-0.5 -p camera.sequence=3 -q");
  EXPECT_EQ(eye.exit_code, 2) << eye.output;
  EXPECT_NE(eye.output.find("camera.dolly"), std::string::npos) << eye.output;
}

TEST(SortFirst, SortMiddleRoutesEveryPrimitiveAndSortLastCompositesWholeScreens) {
  const std::string path = kTeapot + " -p regions=4 -p frames=3";
  const auto first = run_machine(kMachine, "first", path);
  const auto middle = run_machine(kMachine, "middle", path + " -p sort=middle");
  const auto last = run_machine(kMachine, "last", path + " -p sort=last");
  ASSERT_FALSE(first.empty() || middle.empty() || last.empty());
  const auto bytes = [](const nlohmann::ordered_json& s, const char* cls) {
    return s["sort_first"]["per_frame"][2]["bytes"][cls].get<std::uint64_t>();
  };
  // Sort-middle sends every primitive to each other region it covers, every frame (L511).
  EXPECT_GT(bytes(middle, "redistribution"), 10 * bytes(first, "redistribution"));
  EXPECT_GT(middle["sort_first"]["per_frame"][2]["migrated_percent"].get<double>(), 90.0);
  // Sort-last redistributes nothing and composites 16 full screens of 34-byte records (L515).
  EXPECT_EQ(bytes(last, "redistribution"), 0u);
  EXPECT_EQ(bytes(last, "pixels"), 0u);
  EXPECT_EQ(bytes(last, "partial"), 16u * (160u * 120u * 34u + 4u * 8u));  // 4 tiles each
  EXPECT_EQ(bytes(first, "pixels"), 160u * 120u * 3u + 16u * 8u);
  // 256 renderers' partial images of a 2048-pixel square would take 35 GiB: refused first.
  const auto r = run_rtsim("run --machine " + kMachine +
                           " --scene builtin:spd-teapot --width 2048 --height 2048 -p sort=last "
                           "-p regions=16 -q");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("partial image"), std::string::npos) << r.output;
}

TEST(SortFirst, TheMeshCarriesMigrationsHopByHopAndTheHostBusThePixels) {
  const std::string path = kTeapot + " -p regions=4 -p frames=3 -p interconnect=mesh";
  const auto base = run_machine(kMachine, "mesh", path);
  const auto narrow = run_machine(kMachine, "mesh-narrow", path + " -p mesh.link.lanes=1");
  const auto slow_bus =
      run_machine(kMachine, "mesh-bus", path + " -p host_bus.bit_rate=\"1 Mbit/s\"");
  ASSERT_FALSE(base.empty() || narrow.empty() || slow_bus.empty());
  const auto frame_time = [](const nlohmann::ordered_json& s, int f) {
    return s["sort_first"]["per_frame"][f]["time_s"].get<double>();
  };
  // Frame 0 redistributes the random distribution over the mesh: a narrower link slows it.
  EXPECT_GT(frame_time(narrow, 0), frame_time(base, 0) * 1.5);
  // The pixels go over the host bus: 57,600 bytes at 32 Mbit/s take 14 ms.
  EXPECT_GT(frame_time(slow_bus, 2), 0.014);
  EXPECT_TRUE(base["modules"].contains("host_bus"));
  EXPECT_FALSE(base["modules"].contains("ring"));
}

}  // namespace
