#include "scenes/nff_reader.hpp"

#include <array>
#include <bit>
#include <cmath>
#include <limits>
#include <map>
#include <optional>

#include "scenes/scene_text.hpp"

namespace rtsim::scenes {

namespace {

constexpr std::string_view kKeywordList = "v, b, l, f, s, c, p, pp, #";
constexpr std::array<std::string_view, 6> kViewKeys = {"from",  "at",     "up",
                                                       "angle", "hither", "resolution"};

bool is_top_level_keyword(std::string_view t) {
  return t == "v" || t == "b" || t == "l" || t == "f" || t == "s" || t == "c" || t == "p" ||
         t == "pp";
}

int view_key_index(std::string_view t) {
  for (std::size_t i = 0; i < kViewKeys.size(); ++i) {
    if (kViewKeys[i] == t) return static_cast<int>(i);
  }
  return -1;
}

/// Exact bit patterns of a material, so identical `f` lines share one Scene::materials entry.
using MaterialKey = std::array<std::uint64_t, 8>;

MaterialKey key_of(const Material& m) {
  return {std::bit_cast<std::uint64_t>(m.color.r),
          std::bit_cast<std::uint64_t>(m.color.g),
          std::bit_cast<std::uint64_t>(m.color.b),
          std::bit_cast<std::uint64_t>(m.kd),
          std::bit_cast<std::uint64_t>(m.ks),
          std::bit_cast<std::uint64_t>(m.shine),
          std::bit_cast<std::uint64_t>(m.transmittance),
          std::bit_cast<std::uint64_t>(m.ior)};
}

class NffParser {
 public:
  NffParser(std::string_view text, const std::string& name) : cursor_(text, name) {
    scene_.name = name;
  }

  Scene parse() {
    SceneLine line;
    while (cursor_.next(line)) {
      const std::string_view kw = line.tokens[0];
      if (kw == "v") {
        parse_view(line);
      } else if (kw == "b") {
        parse_background(line);
      } else if (kw == "l") {
        parse_light(line);
      } else if (kw == "f") {
        parse_material(line);
      } else if (kw == "s") {
        parse_sphere(line);
      } else if (kw == "c") {
        parse_cone(line);
      } else if (kw == "p") {
        parse_polygon(line, false);
      } else if (kw == "pp") {
        parse_polygon(line, true);
      } else if (view_key_index(kw) >= 0) {
        fail(line, cat("'", kw, "' outside a view block; it must follow a 'v' line"));
      } else {
        fail(line, cat("unknown keyword ", quote_token(kw), "; expected one of ", kKeywordList));
      }
    }
    if (scene_.primitives.empty()) {
      cursor_.fail(cursor_.last_line_number(),
                   "no primitives in scene file by its end (expected at least one s, c, p or pp)");
    }
    return std::move(scene_);
  }

 private:
  [[noreturn]] void fail(const SceneLine& line, const std::string& message) const {
    cursor_.fail(line.number, message);
  }

  void expect_alone(const SceneLine& line, std::string_view what) const {
    if (line.tokens.size() != 1) {
      fail(line, cat("unexpected ", quote_token(line.tokens[1]), " after '", line.tokens[0], "'; ",
                     what));
    }
  }

  Vec3 vec_of(const double* d) const { return Vec3{d[0], d[1], d[2]}; }

  /// rgb[0..3) came from tokens[first_token ...].
  void require_colour(const SceneLine& line, const double* rgb, std::size_t first_token,
                      std::string_view what) const {
    for (std::size_t i = 0; i < 3; ++i) {
      if (rgb[i] < 0.0) {
        fail(line, cat(what, " colour components must be >= 0, got ",
                       quote_token(line.tokens[first_token + i])));
      }
    }
  }

  /// Unit vector of a non-zero finite vector, scaled first so tiny or huge inputs do not
  /// underflow or overflow in the length.
  static Vec3 unit(const Vec3& v) { return glm::normalize(v / max_abs_component(v)); }

  // --- v ------------------------------------------------------------------------------------
  void parse_view(const SceneLine& v_line) {
    expect_alone(v_line,
                 "the view parameters (from, at, up, angle, hither, resolution) follow "
                 "on their own lines");
    if (view_line_ != 0) {
      fail(v_line, cat("second view block 'v' (the first is at line ", view_line_, ")"));
    }
    view_line_ = v_line.number;
    std::array<std::size_t, 6> seen_at{};  // line of each view key, 0 when missing
    Camera& cam = scene_.camera;
    SceneLine line;
    while (cursor_.next(line)) {
      const int key = view_key_index(line.tokens[0]);
      if (key < 0) {
        cursor_.unread();
        break;
      }
      const auto k = static_cast<std::size_t>(key);
      if (seen_at[k] != 0) {
        fail(line, cat("duplicate '", kViewKeys[k], "' in the view block (first at line ",
                       seen_at[k], ")"));
      }
      seen_at[k] = line.number;
      double d[3];
      switch (k) {
        case 0:
          parse_numbers(cursor_, line, 1, 3, "view 'from' point", d);
          cam.from = vec_of(d);
          break;
        case 1:
          parse_numbers(cursor_, line, 1, 3, "view 'at' point", d);
          cam.at = vec_of(d);
          break;
        case 2:
          parse_numbers(cursor_, line, 1, 3, "view 'up' vector", d);
          cam.up = vec_of(d);
          if (cam.up == Vec3{0.0}) fail(line, "view 'up' vector must not be zero");
          break;
        case 3:
          parse_numbers(cursor_, line, 1, 1, "view 'angle' in degrees", d);
          if (!(d[0] > 0.0 && d[0] < 180.0)) {
            fail(line, cat("view 'angle' must be between 0 and 180 degrees (exclusive), got ",
                           quote_token(line.tokens[1])));
          }
          cam.angle_deg = d[0];
          break;
        case 4:
          parse_numbers(cursor_, line, 1, 1, "view 'hither' distance", d);
          if (d[0] < 0.0) {
            fail(line, cat("view 'hither' must be >= 0, got ", quote_token(line.tokens[1])));
          }
          cam.hither = d[0];
          break;
        default:
          parse_resolution(line);
          break;
      }
    }
    std::string missing;
    for (std::size_t k = 0; k < kViewKeys.size(); ++k) {
      if (seen_at[k] == 0) missing += cat(missing.empty() ? "'" : ", '", kViewKeys[k], "'");
    }
    if (!missing.empty()) {
      fail(v_line, cat("view block is missing ", missing,
                       "; expected from, at, up, angle, hither and resolution, each on its own "
                       "line after 'v'"));
    }
    const Vec3 dir = cam.at - cam.from;
    if (!is_finite(dir)) {
      cursor_.fail(seen_at[1], "view 'at' point is too far from the 'from' point");
    }
    if (dir == Vec3{0.0}) {
      cursor_.fail(seen_at[1],
                   "view 'at' point equals the 'from' point; the camera has no view "
                   "direction");
    }
    const Vec3 c = glm::cross(unit(dir), unit(cam.up));
    // Parallel to within ~1e-6 rad: the camera's right vector would be undefined.
    constexpr double kMinUpSine = 1e-6;
    if (!(glm::length(c) > kMinUpSine)) {
      cursor_.fail(seen_at[2], "view 'up' vector is parallel to the view direction (at - from)");
    }
    scene_.has_camera = true;
  }

  void parse_resolution(const SceneLine& line) {
    if (line.tokens.size() != 3) {
      std::string msg = cat("expected 2 integers for view 'resolution' (width height), got ",
                            line.tokens.size() - 1);
      if (line.tokens.size() > 3)
        msg += cat(" (unexpected trailing ", quote_token(line.tokens[3]), ")");
      fail(line, msg);
    }
    std::int64_t wh[2];
    for (int i = 0; i < 2; ++i) {
      wh[i] = parse_integer(cursor_, line, line.tokens[1 + static_cast<std::size_t>(i)],
                            i == 0 ? "resolution width" : "resolution height");
      if (wh[i] <= 0 || wh[i] > kMaxNffResolution) {
        fail(line, cat("resolution ", i == 0 ? "width" : "height", " must be 1..",
                       kMaxNffResolution, " (kMaxNffResolution), got ",
                       quote_token(line.tokens[1 + static_cast<std::size_t>(i)])));
      }
    }
    scene_.camera.width = static_cast<int>(wh[0]);
    scene_.camera.height = static_cast<int>(wh[1]);
  }

  // --- b, l, f ------------------------------------------------------------------------------
  void parse_background(const SceneLine& line) {
    if (background_line_ != 0) {
      fail(line, cat("second background 'b' (the first is at line ", background_line_, ")"));
    }
    background_line_ = line.number;
    double d[3];
    parse_numbers(cursor_, line, 1, 3, "background colour (r g b)", d);
    require_colour(line, d, 1, "background");
    scene_.background = vec_of(d);
  }

  void parse_light(const SceneLine& line) {
    double d[6];
    const std::size_t n = line.tokens.size() - 1;
    if (n == 6) {
      parse_numbers(cursor_, line, 1, 6, "light position and colour (x y z r g b)", d);
      require_colour(line, d + 3, 4, "light");
    } else {
      parse_numbers(cursor_, line, 1, 3, "light position (x y z, optionally r g b)", d);
      d[3] = d[4] = d[5] = 1.0;
    }
    scene_.lights.push_back(Light{vec_of(d), vec_of(d + 3)});
  }

  void parse_material(const SceneLine& line) {
    double d[8];
    parse_numbers(cursor_, line, 1, 8, "material (r g b Kd Ks Shine T index_of_refraction)", d);
    require_colour(line, d, 1, "material");
    static constexpr std::array<const char*, 5> kNames = {"Kd", "Ks", "Shine", "T",
                                                          "index_of_refraction"};
    for (std::size_t i = 3; i < 7; ++i) {
      if (d[i] < 0.0) {
        fail(line, cat("material ", kNames[i - 3], " must be >= 0, got ",
                       quote_token(line.tokens[i + 1])));
      }
    }
    if (d[6] > 0.0 && !(d[7] > 0.0)) {
      fail(line,
           cat("material index_of_refraction must be > 0 for a transmissive material (T > 0), "
               "got ",
               quote_token(line.tokens[8])));
    }
    pending_material_ = Material{vec_of(d), d[3], d[4], d[5], d[6], d[7]};
    current_material_.reset();
  }

  /// Index of the material in force, interning it on first use.
  std::uint32_t material_index() {
    if (current_material_) return *current_material_;
    const Material m = pending_material_.value_or(kDefaultNffMaterial);
    const auto [it, inserted] =
        material_ids_.try_emplace(key_of(m), static_cast<std::uint32_t>(scene_.materials.size()));
    if (inserted) scene_.materials.push_back(m);
    current_material_ = it->second;
    return it->second;
  }

  void add_primitive(PrimitiveKind kind, std::size_t index, const SceneLine& line) {
    if (scene_.primitives.size() >= std::numeric_limits<std::uint32_t>::max()) {
      fail(line, "too many primitives (more than 2^32 - 1)");
    }
    scene_.primitives.push_back(Primitive{kind, static_cast<std::uint32_t>(index), material_index(),
                                          static_cast<std::uint32_t>(line.number)});
  }

  // --- s, c, p, pp --------------------------------------------------------------------------
  void parse_sphere(const SceneLine& line) {
    double d[4];
    parse_numbers(cursor_, line, 1, 4, "sphere centre and radius (x y z r)", d);
    if (!(d[3] > 0.0)) {
      fail(line, cat("sphere radius must be > 0, got ", quote_token(line.tokens[4])));
    }
    scene_.spheres.push_back(Sphere{vec_of(d), d[3]});
    add_primitive(PrimitiveKind::Sphere, scene_.spheres.size() - 1, line);
  }

  void parse_cone(const SceneLine& c_line) {
    expect_alone(c_line, "the cone's base and apex (x y z r) follow on the next two lines");
    double d[2][4];
    static constexpr std::array<const char*, 2> kEnd = {"base", "apex"};
    for (std::size_t e = 0; e < 2; ++e) {
      SceneLine line;
      if (!cursor_.next(line)) {
        fail(c_line, cat("cone: the file ends before its ", kEnd[e], " line (x y z r)"));
      }
      if (is_top_level_keyword(line.tokens[0])) {
        fail(line, cat("cone at line ", c_line.number, ": expected its ", kEnd[e],
                       " line (x y z r), got keyword ", quote_token(line.tokens[0])));
      }
      parse_numbers(cursor_, line, 0, 4, cat("cone ", kEnd[e], " (x y z r)"), d[e]);
    }
    scene_.cones.push_back(Cone{vec_of(d[0]), d[0][3], vec_of(d[1]), d[1][3]});
    add_primitive(PrimitiveKind::Cone, scene_.cones.size() - 1, c_line);
  }

  void parse_polygon(const SceneLine& p_line, bool with_normals) {
    const std::string kw(p_line.tokens[0]);
    if (p_line.tokens.size() != 2) {
      std::string msg =
          cat("expected 1 vertex count after '", kw, "', got ", p_line.tokens.size() - 1);
      if (p_line.tokens.size() > 2) {
        msg += cat(" (unexpected trailing ", quote_token(p_line.tokens[2]), ")");
      }
      fail(p_line, msg);
    }
    const std::int64_t count =
        parse_integer(cursor_, p_line, p_line.tokens[1], "polygon vertex count");
    if (count < 3) {
      fail(p_line, cat("polygon needs at least 3 vertices, got ", quote_token(p_line.tokens[1])));
    }
    if (count > kMaxPolygonVertices) {
      fail(p_line, cat("polygon vertex count ", count, " exceeds the limit of ",
                       kMaxPolygonVertices, " (kMaxPolygonVertices)"));
    }
    const auto n = static_cast<std::size_t>(count);
    if (n > cursor_.lines_left()) {
      fail(p_line, cat("polygon declares ", n, " vertices but the file has only ",
                       cursor_.lines_left(), " lines left"));
    }
    Polygon poly;
    poly.vertices.reserve(n);
    if (with_normals) poly.normals.reserve(n);
    const std::size_t per_line = with_normals ? 6 : 3;
    const std::string layout = with_normals ? "x y z nx ny nz" : "x y z";
    for (std::size_t i = 0; i < n; ++i) {
      SceneLine line;
      if (!cursor_.next(line)) {
        fail(p_line,
             cat("polygon declares ", n, " vertices but the file ends after ", i, " vertex lines"));
      }
      if (is_top_level_keyword(line.tokens[0])) {
        fail(line, cat("polygon at line ", p_line.number, " declares ", n, " vertices but only ", i,
                       " vertex lines follow before keyword ", quote_token(line.tokens[0])));
      }
      double d[6];
      parse_numbers(cursor_, line, 0, per_line,
                    cat("polygon vertex ", i + 1, " of ", n, " (", layout, ")"), d);
      poly.vertices.push_back(vec_of(d));
      if (with_normals) poly.normals.push_back(vec_of(d + 3));
    }
    scene_.polygons.push_back(std::move(poly));
    add_primitive(PrimitiveKind::Polygon, scene_.polygons.size() - 1, p_line);
  }

  LineCursor cursor_;
  Scene scene_;
  std::size_t view_line_ = 0;
  std::size_t background_line_ = 0;
  std::optional<Material> pending_material_;
  std::optional<std::uint32_t> current_material_;
  std::map<MaterialKey, std::uint32_t> material_ids_;
};

}  // namespace

Scene parse_nff(std::string_view text, const std::string& name) {
  return NffParser(text, name).parse();
}

Scene read_nff(const std::string& path) { return parse_nff(read_scene_file(path), path); }

}  // namespace rtsim::scenes
