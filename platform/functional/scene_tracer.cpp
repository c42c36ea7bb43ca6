#include "platform/functional/scene_tracer.hpp"

#include <sstream>

#include "firmware/accel/dda.hpp"
#include "firmware/accel/gaudet_data_sets.hpp"
#include "firmware/accel/grid_divisions.hpp"
#include "firmware/accel/grid_traversal.hpp"
#include "firmware/accel/uniform_grid.hpp"

namespace rtsim::functional {

bool test_shape(const SceneGeometry& g, std::uint32_t slot, const Ray& ray, double t_min,
                double t_max, SurfaceHit& out, TraceCounters& c) {
  ++c.intersection_tests;
  return std::visit(
      [&](const auto& s) {
        using Kernel = std::decay_t<decltype(s)>;
        if constexpr (std::is_same_v<Kernel, PatchShape>) {
          // Wang's loop stops early when no subpatch survives: count the work it did.
          kernels::WangCounters wc;
          const bool hit = s.intersect(ray, t_min, t_max, out, &wc);
          c.patch_subdivisions += wc.subdivisions;
          c.cost += kernels::wang_cost(wc);
          return hit;
        } else {
          c.cost += Kernel::kTestCost;
          return s.intersect(ray, t_min, t_max, out);
        }
      },
      g.shapes[slot].shape);
}

void fill_hit(const SceneGeometry& g, std::uint32_t slot, const SurfaceHit& s, Hit& hit) {
  hit.surface = s;
  hit.prim_id = g.shapes[slot].prim_id;
  hit.material = g.shapes[slot].material;
}

namespace {

/// Runs the kernel of one shape and counts the test.
class ShapeTester {
 public:
  /// `machine_test`: a machine's own test of a candidate (its kernels on the words in its
  /// memories), or nullptr for the kernels of `g`.
  ShapeTester(const SceneGeometry& g, const CandidateTest* machine_test)
      : g_(&g), machine_test_(machine_test) {}

  bool test(std::uint32_t slot, const Ray& ray, double t_min, double t_max, SurfaceHit& out,
            TraceCounters& c) const {
    if (machine_test_) return machine_test_->test(slot, ray, t_min, t_max, out, c);
    return test_shape(*g_, slot, ray, t_min, t_max, out, c);
  }

  /// The per-candidate callback of the grid and shell traversals (their PrimTest): tests shape
  /// `slot` over (lo, hi) and returns its hit distance, or kInfinity on a miss. Each hit's
  /// details are copied to `last` (a miss leaves it alone); the closest-hit traversals pass
  /// hi = the best hit so far, so `last` ends as the details of the closest hit.
  auto candidate_test(const Ray& ray, SurfaceHit& last, TraceCounters& c) const {
    return [this, &ray, &last, &c, s = SurfaceHit{}](std::uint32_t slot, double lo,
                                                     double hi) mutable {
      if (!test(slot, ray, lo, hi, s, c)) return kInfinity;
      last = s;
      return s.t;
    };
  }

  /// Ends a grid or shell closest-hit search: for a hit (`result` valid) fills `hit` from the
  /// details candidate_test kept, which are the closest hit's, and counts it.
  template <class SearchHit>
  bool report_closest(const SearchHit& result, const SurfaceHit& details, Hit& hit,
                      TraceCounters& c) const {
    if (!result.valid()) return false;
    fill(hit, static_cast<std::uint32_t>(result.prim), details);
    ++c.hits;
    return true;
  }

  void fill(Hit& hit, std::uint32_t slot, const SurfaceHit& s) const {
    fill_hit(*g_, slot, s, hit);
  }

  std::size_t size() const { return g_->shapes.size(); }

 private:
  const SceneGeometry* g_;
  const CandidateTest* machine_test_;
};

/// Every ray tests every shape.
class BruteForceTracer final : public Tracer {
 public:
  explicit BruteForceTracer(ShapeTester tester) : tester_(tester) {}

  bool closest_hit(const Ray& ray, double t_min, double t_max, Hit& hit,
                   TraceCounters& c) const override {
    SurfaceHit s;
    bool found = false;
    for (std::uint32_t i = 0; i < tester_.size(); ++i) {
      if (tester_.test(i, ray, t_min, t_max, s, c)) {
        t_max = s.t;
        tester_.fill(hit, i, s);
        found = true;
      }
    }
    if (found) ++c.hits;
    return found;
  }

  bool any_hit(const Ray& ray, double t_min, double t_max, TraceCounters& c) const override {
    SurfaceHit s;
    for (std::uint32_t i = 0; i < tester_.size(); ++i)
      if (tester_.test(i, ray, t_min, t_max, s, c)) return true;
    return false;
  }

 private:
  ShapeTester tester_;
};

/// Ullner's subvolumes walked by the corrected Appendix B DDA.
class GridTracer final : public Tracer {
 public:
  /// `by_subvolume`: each subvolume looks for a hit within itself only (the array's search).
  GridTracer(const SceneGeometry& g, ShapeTester tester, const Bounds& box, accel::GridDivisions n,
             accel::DdaVariant variant, bool by_subvolume)
      : GridTracer(tester, std::make_shared<const accel::UniformGrid>(g.bounds, box, n), variant,
                   by_subvolume) {}
  /// Another search over the same grid (a machine's, testing on its own memories).
  GridTracer(ShapeTester tester, std::shared_ptr<const accel::UniformGrid> grid,
             accel::DdaVariant variant, bool by_subvolume)
      : tester_(tester),
        grid_(std::move(grid)),
        variant_(variant),
        by_subvolume_(by_subvolume),
        dda_(*grid_, variant) {}

  const accel::UniformGrid& grid() const { return *grid_; }
  std::shared_ptr<const accel::UniformGrid> shared_grid() const { return grid_; }
  std::unique_ptr<Tracer> sharing_grid(ShapeTester tester) const {
    return std::make_unique<GridTracer>(tester, grid_, variant_, by_subvolume_);
  }

  bool closest_hit(const Ray& ray, double t_min, double t_max, Hit& hit,
                   TraceCounters& c) const override {
    SurfaceHit best;
    accel::GridTraversalStats st;
    const auto h = by_subvolume_
                       ? accel::grid_closest_hit_by_subvolume(
                             dda_, ray, t_min, t_max, tester_.candidate_test(ray, best, c), st)
                       : accel::grid_closest_hit(dda_, ray, t_min, t_max,
                                                 tester_.candidate_test(ray, best, c), st);
    add(st, c);
    return tester_.report_closest(h, best, hit, c);
  }

  bool any_hit(const Ray& ray, double t_min, double t_max, TraceCounters& c) const override {
    SurfaceHit unused;
    accel::GridTraversalStats st;
    const auto h =
        accel::grid_any_hit(dda_, ray, t_min, t_max, tester_.candidate_test(ray, unused, c), st);
    add(st, c);
    return h.valid();
  }

 private:
  static void add(const accel::GridTraversalStats& st, TraceCounters& c) {
    c.dda_steps += st.steps;
    c.cells_visited += st.cells_visited;
  }
  ShapeTester tester_;
  std::shared_ptr<const accel::UniformGrid> grid_;  ///< shared with the twin's search
  accel::DdaVariant variant_;
  bool by_subvolume_;
  accel::Dda dda_;
};

/// Gaudet's box-shell hierarchy searched as the Shell and Prim tasks do.
class ShellTracer final : public ShellSearch {
 public:
  ShellTracer(ShapeTester tester, accel::ShellTree tree)
      : tester_(tester), tree_(std::move(tree)) {}

  const accel::ShellTree& tree() const override { return tree_; }

  bool closest_hit(const Ray& ray, double t_min, double t_max, Hit& hit,
                   TraceCounters& c) const override {
    accel::ShellTraversalStats st;
    return closest_hit(ray, t_min, t_max, hit, c, st);
  }
  bool any_hit(const Ray& ray, double t_min, double t_max, TraceCounters& c) const override {
    accel::ShellTraversalStats st;
    return any_hit(ray, t_min, t_max, c, st);
  }

  bool closest_hit(const Ray& ray, double t_min, double t_max, Hit& hit, TraceCounters& c,
                   accel::ShellTraversalStats& st) const override {
    SurfaceHit best;
    const std::uint64_t boxes = st.box_tests;
    accel::ShellTraverser traverser(tree_);
    const auto h =
        traverser.closest_hit(ray, t_min, t_max, tester_.candidate_test(ray, best, c), st);
    c.box_tests += st.box_tests - boxes;
    return tester_.report_closest(h, best, hit, c);
  }

  bool any_hit(const Ray& ray, double t_min, double t_max, TraceCounters& c,
               accel::ShellTraversalStats& st) const override {
    SurfaceHit unused;
    const std::uint64_t boxes = st.box_tests;
    accel::ShellTraverser traverser(tree_);
    const auto h = traverser.any_hit(ray, t_min, t_max, tester_.candidate_test(ray, unused, c), st);
    c.box_tests += st.box_tests - boxes;
    return h.valid();
  }

 private:
  ShapeTester tester_;
  accel::ShellTree tree_;
};

}  // namespace

std::unique_ptr<Tracer> make_tracer_sharing(const Tracer& twin, const SceneGeometry& g,
                                            const CandidateTest* machine_test) {
  const ShapeTester tester(g, machine_test);
  if (const auto* grid = dynamic_cast<const GridTracer*>(&twin)) return grid->sharing_grid(tester);
  if (dynamic_cast<const BruteForceTracer*>(&twin))
    return std::make_unique<BruteForceTracer>(tester);
  throw std::logic_error("make_tracer_sharing: only the grid and brute force are shared");
}

std::shared_ptr<const accel::UniformGrid> grid_of(const Tracer& twin) {
  const auto* grid = dynamic_cast<const GridTracer*>(&twin);
  return grid ? grid->shared_grid() : nullptr;
}

std::unique_ptr<Tracer> make_tracer(SceneGeometry& g, const scenes::Scene& scene,
                                    const RenderSettings& settings,
                                    const CandidateTest* machine_test) {
  const ShapeTester tester(g, machine_test);
  std::ostringstream desc;
  if (g.shapes.empty() || settings.accel == AccelKind::None) {
    desc << "none: every ray tests all " << g.shapes.size() << " shapes";
    g.accel_description = desc.str();
    return std::make_unique<BruteForceTracer>(tester);
  }
  if (settings.accel == AccelKind::Grid) {
    accel::GridDivisions n{settings.grid_divisions, settings.grid_divisions,
                           settings.grid_divisions};
    // The grid divides the modelling space (seed 000 L2118): the scene's own when it defines
    // one, else the bounding box of the geometry.
    Bounds box = g.scene_bounds;
    if (!scene.modelling_space.empty()) box.extend(scene.modelling_space);
    if (settings.grid_divisions == 0) n = accel::choose_divisions(box, g.shapes.size());
    auto tracer = std::make_unique<GridTracer>(
        g, tester, box, n,
        settings.dda_as_printed ? accel::DdaVariant::AsPrinted : accel::DdaVariant::Corrected,
        settings.grid_by_subvolume);
    const auto& grid = tracer->grid();
    desc << "grid " << n.x << "x" << n.y << "x" << n.z
         << (settings.dda_as_printed ? " (DDA as printed)" : "") << ", "
         << grid.occupied_cell_count() << " occupied subvolumes, " << grid.reference_count()
         << " polygon addresses";
    g.accel_description = desc.str();
    return tracer;
  }
  // Shells: the scene's clusters when it has them (Gaudet's npp scenes), else a generic build.
  accel::ShellTree tree;
  if (!scene.cluster_of_primitive.empty()) {
    std::vector<std::uint32_t> cluster_of_shape(g.shapes.size());
    for (std::size_t i = 0; i < g.shapes.size(); ++i)
      cluster_of_shape[i] =
          scene.cluster_of_primitive[static_cast<std::size_t>(g.shapes[i].prim_id)];
    const int b = scene.cluster_branching > 0 ? scene.cluster_branching : settings.shell_branching;
    tree = accel::ShellTree::from_clusters(g.bounds, cluster_of_shape, b);
  } else {
    tree = accel::ShellTree::build(g.bounds, settings.shell_branching, settings.shell_leaf_size);
  }
  if (settings.shell_boxes_as_stored) tree.store_boxes(accel::stored_shell_box);
  const auto counts = tree.counts();
  desc << "shells: " << counts.shells << " shells in " << counts.shell_packets << " shell packets, "
       << counts.prims << " primitives in " << counts.prim_packets << " primitive packets";
  g.accel_description = desc.str();
  return std::make_unique<ShellTracer>(tester, std::move(tree));
}

}  // namespace rtsim::functional
