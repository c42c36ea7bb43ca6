#include "scenes/nff_reader.hpp"

#include <array>
#include <bit>
#include <cmath>
#include <limits>
#include <map>
#include <optional>
#include <type_traits>

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

/// A word of the format (a top-level keyword or a view key). Where a number is expected, a
/// keyword means the numbers ran out; any other token there is a bad number.
bool is_keyword(std::string_view t) {
  return !t.empty() && t[0] >= 'a' && t[0] <= 'z' &&
         (is_top_level_keyword(t) || view_key_index(t) >= 0);
}

/// Starts like a number: a digit, a sign or a point.
bool looks_numeric(std::string_view t) {
  const char c = t.empty() ? '\0' : t[0];
  return (c >= '0' && c <= '9') || c == '+' || c == '-' || c == '.';
}

/// "1 value", "4 values".
std::string values_text(std::size_t n) { return cat(n, n == 1 ? " value" : " values"); }

/// The name of a quantity for a message: a string, or a callable that builds it (so the hot path
/// builds no string).
template <typename What>
std::string describe(const What& what) {
  if constexpr (std::is_invocable_v<const What&>) {
    return std::string(what());
  } else {
    return std::string(what);
  }
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
    SceneToken kw;
    while (cursor_.next(kw)) {
      const std::size_t left = cursor_.tokens_left();
      const std::string_view k = kw.text;
      if (k == "v") {
        parse_view(kw);
      } else if (k == "b") {
        parse_background(kw);
      } else if (k == "l") {
        parse_light(kw);
      } else if (k == "f") {
        parse_material(kw);
      } else if (k == "s") {
        parse_sphere(kw);
      } else if (k == "c") {
        parse_cone(kw);
      } else if (k == "p") {
        parse_polygon(kw, false);
      } else if (k == "pp") {
        parse_polygon(kw, true);
      } else if (view_key_index(k) >= 0) {
        fail(kw, cat("'", k, "' outside a view block; it must follow a 'v'"));
      } else {
        fail_unexpected(kw);
      }
      previous_ = kw;
      previous_values_ = left - cursor_.tokens_left();
      previous_end_line_ = cursor_.last_line();
    }
    if (scene_.primitives.empty()) {
      cursor_.fail(cursor_.last_line_number(),
                   "no primitives in scene file by its end (expected at least one s, c, p or pp)");
    }
    return std::move(scene_);
  }

 private:
  [[noreturn]] void fail(const SceneToken& token, const std::string& message) const {
    cursor_.fail(token.line, message);
  }

  /// A token where a keyword must be: an unknown word, or a number the entity before it did not
  /// take.
  [[noreturn]] void fail_unexpected(const SceneToken& token) const {
    const std::string after = previous_.line == 0
                                  ? std::string()
                                  : cat("'", previous_.text, "' at line ", previous_.line,
                                        ", which took ", values_text(previous_values_));
    if (looks_numeric(token.text) && !after.empty()) {
      fail(token, cat("unexpected ", quote_token(token.text), " after ", after,
                      "; expected a keyword (one of ", kKeywordList, ")"));
    }
    std::string msg =
        cat("unknown keyword ", quote_token(token.text), "; expected one of ", kKeywordList);
    if (!after.empty() && token.line == previous_end_line_) msg += cat(" (after ", after, ")");
    fail(token, msg);
  }

  /// "keyword 's' at line 5" or "the end of the file": what came where a value was expected.
  /// The line is left out when it is `line`, the line of the message.
  static std::string stop_text(const SceneToken* stop, std::size_t line) {
    if (stop == nullptr) return "the end of the file";
    return cat("keyword ", quote_token(stop->text),
               stop->line != line ? cat(" at line ", stop->line) : std::string());
  }

  /// Missing values of the entity `keyword` starts: reported at the line of the last token the
  /// entity took (where the user would add what is missing), naming what came instead and, when
  /// it is elsewhere, the keyword's line. `expected` is "expected N numbers for X, got K".
  [[noreturn]] void fail_missing(const SceneToken& keyword, const std::string& expected,
                                 const SceneToken* stop,
                                 std::string_view before = " before ") const {
    const std::size_t line = cursor_.last_line();
    std::string msg = cat(expected, before, stop_text(stop, line));
    if (keyword.line != line) msg += cat(" ('", keyword.text, "' at line ", keyword.line, ")");
    cursor_.fail(line, msg);
  }

  /// Takes `count` numbers for the entity `keyword` starts into out[0..count), their tokens into
  /// tokens[0..count) when not null. `what` names them for messages (a string or a callable).
  template <typename What>
  void take_numbers(const SceneToken& keyword, std::size_t count, double* out, SceneToken* tokens,
                    const What& what) {
    for (std::size_t i = 0; i < count; ++i) {
      const SceneToken* t = cursor_.peek();
      if (t == nullptr || is_keyword(t->text)) {
        fail_missing(keyword,
                     cat("expected ", count, count == 1 ? " number for " : " numbers for ",
                         describe(what), ", got ", i),
                     t);
      }
      const NumberStatus status = try_parse_number(t->text, out[i]);
      if (status != NumberStatus::kOk) fail_number(cursor_, *t, status, describe(what), i + 1);
      if (tokens != nullptr) tokens[i] = *t;
      cursor_.skip();
    }
  }

  Vec3 vec_of(const double* d) const { return Vec3{d[0], d[1], d[2]}; }

  /// rgb[0..3) were read from tokens[0..3).
  void require_colour(const double* rgb, const SceneToken* tokens, std::string_view what) const {
    for (std::size_t i = 0; i < 3; ++i) {
      if (rgb[i] < 0.0) {
        fail(tokens[i],
             cat(what, " colour components must be >= 0, got ", quote_token(tokens[i].text)));
      }
    }
  }

  /// Unit vector of a non-zero finite vector, scaled first so tiny or huge inputs do not
  /// underflow or overflow in the length.
  static Vec3 unit(const Vec3& v) { return glm::normalize(v / max_abs_component(v)); }

  // --- v ------------------------------------------------------------------------------------
  static std::string missing_view_keys(const std::array<std::size_t, 6>& seen_at) {
    std::string missing;
    for (std::size_t k = 0; k < kViewKeys.size(); ++k) {
      if (seen_at[k] == 0) missing += cat(missing.empty() ? "'" : ", '", kViewKeys[k], "'");
    }
    return missing;
  }

  void parse_view(const SceneToken& v) {
    if (view_line_ != 0) {
      fail(v, cat("second view block 'v' (the first is at line ", view_line_, ")"));
    }
    view_line_ = v.line;
    std::array<std::size_t, 6> seen_at{};  // line of each view key, 0 when missing
    std::size_t seen = 0;
    Camera& cam = scene_.camera;
    while (const SceneToken* t = cursor_.peek()) {
      const int key = view_key_index(t->text);
      if (key < 0) {
        // The block ends at the next keyword, or after its six keys; anything else is misplaced.
        if (seen == kViewKeys.size() || is_top_level_keyword(t->text)) break;
        fail(*t, cat("unexpected ", quote_token(t->text), " in the view block of line ", v.line,
                     "; expected one of ", missing_view_keys(seen_at)));
      }
      SceneToken kt;
      cursor_.next(kt);
      const auto k = static_cast<std::size_t>(key);
      if (seen_at[k] != 0) {
        fail(kt, cat("duplicate '", kViewKeys[k], "' in the view block (first at line ", seen_at[k],
                     ")"));
      }
      seen_at[k] = kt.line;
      ++seen;
      double d[3];
      SceneToken tok[3];
      switch (k) {
        case 0:
          take_numbers(kt, 3, d, tok, "view 'from' point");
          cam.from = vec_of(d);
          break;
        case 1:
          take_numbers(kt, 3, d, tok, "view 'at' point");
          cam.at = vec_of(d);
          break;
        case 2:
          take_numbers(kt, 3, d, tok, "view 'up' vector");
          cam.up = vec_of(d);
          if (cam.up == Vec3{0.0}) fail(kt, "view 'up' vector must not be zero");
          break;
        case 3:
          take_numbers(kt, 1, d, tok, "view 'angle' in degrees");
          if (!(d[0] > 0.0 && d[0] < 180.0)) {
            fail(tok[0], cat("view 'angle' must be between 0 and 180 degrees (exclusive), got ",
                             quote_token(tok[0].text)));
          }
          cam.angle_deg = d[0];
          break;
        case 4:
          take_numbers(kt, 1, d, tok, "view 'hither' distance");
          if (d[0] < 0.0) {
            fail(tok[0], cat("view 'hither' must be >= 0, got ", quote_token(tok[0].text)));
          }
          cam.hither = d[0];
          break;
        default:
          parse_resolution(kt);
          break;
      }
    }
    if (seen != kViewKeys.size()) {
      fail(v, cat("view block is missing ", missing_view_keys(seen_at),
                  "; expected from, at, up, angle, hither and resolution after 'v'"));
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

  void parse_resolution(const SceneToken& key) {
    std::int64_t wh[2];
    for (std::size_t i = 0; i < 2; ++i) {
      const SceneToken* t = cursor_.peek();
      if (t == nullptr || is_keyword(t->text)) {
        fail_missing(key, cat("expected 2 integers for view 'resolution' (width height), got ", i),
                     t);
      }
      const char* name = i == 0 ? "width" : "height";
      wh[i] = parse_integer(cursor_, *t, cat("resolution ", name));
      if (wh[i] <= 0 || wh[i] > kMaxNffResolution) {
        fail(*t, cat("resolution ", name, " must be 1..", kMaxNffResolution,
                     " (kMaxNffResolution), got ", quote_token(t->text)));
      }
      cursor_.skip();
    }
    scene_.camera.width = static_cast<int>(wh[0]);
    scene_.camera.height = static_cast<int>(wh[1]);
  }

  // --- b, l, f ------------------------------------------------------------------------------
  void parse_background(const SceneToken& kw) {
    if (background_line_ != 0) {
      fail(kw, cat("second background 'b' (the first is at line ", background_line_, ")"));
    }
    background_line_ = kw.line;
    double d[3];
    SceneToken tok[3];
    take_numbers(kw, 3, d, tok, "background colour (r g b)");
    require_colour(d, tok, "background");
    scene_.background = vec_of(d);
  }

  /// `l x y z` (white), `l x y z i` (grey of intensity i) or `l x y z r g b`. The optional
  /// numbers are the tokens up to the next keyword; five numbers in all is ambiguous.
  void parse_light(const SceneToken& kw) {
    double d[6];
    SceneToken tok[6];
    take_numbers(kw, 3, d, tok,
                 "light position (x y z, then optionally an intensity i or a colour r g b)");
    std::size_t extra = 0;
    for (const SceneToken* t = cursor_.peek(); extra < 3 && t != nullptr && !is_keyword(t->text);
         t = cursor_.peek()) {
      const NumberStatus status = try_parse_number(t->text, d[3 + extra]);
      if (status != NumberStatus::kOk) {
        fail_number(cursor_, *t, status, "light intensity or colour (x y z i or x y z r g b)",
                    4 + extra);
      }
      tok[3 + extra] = *t;
      cursor_.skip();
      ++extra;
    }
    Color color{1.0};
    if (extra == 1) {
      if (d[3] < 0.0) {
        fail(tok[3], cat("light intensity must be >= 0, got ", quote_token(tok[3].text)));
      }
      color = Color{d[3]};
    } else if (extra == 2) {
      fail(kw, cat("light with 5 numbers is ambiguous; expected 3 (x y z: white), 4 (x y z "
                   "intensity) or 6 (x y z r g b)"));
    } else if (extra == 3) {
      require_colour(d + 3, tok + 3, "light");
      color = vec_of(d + 3);
    }
    scene_.lights.push_back(Light{vec_of(d), color});
  }

  void parse_material(const SceneToken& kw) {
    double d[8];
    SceneToken tok[8];
    take_numbers(kw, 8, d, tok, "material (r g b Kd Ks Shine T index_of_refraction)");
    require_colour(d, tok, "material");
    static constexpr std::array<const char*, 5> kNames = {"Kd", "Ks", "Shine", "T",
                                                          "index_of_refraction"};
    for (std::size_t i = 3; i < 7; ++i) {
      if (d[i] < 0.0) {
        fail(tok[i],
             cat("material ", kNames[i - 3], " must be >= 0, got ", quote_token(tok[i].text)));
      }
    }
    if (d[6] > 0.0 && !(d[7] > 0.0)) {
      fail(tok[7],
           cat("material index_of_refraction must be > 0 for a transmissive material (T > 0), "
               "got ",
               quote_token(tok[7].text)));
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

  void add_primitive(PrimitiveKind kind, std::size_t index, const SceneToken& kw) {
    if (scene_.primitives.size() >= std::numeric_limits<std::uint32_t>::max()) {
      fail(kw, "too many primitives (more than 2^32 - 1)");
    }
    scene_.primitives.push_back(Primitive{kind, static_cast<std::uint32_t>(index), material_index(),
                                          static_cast<std::uint32_t>(kw.line)});
  }

  // --- s, c, p, pp --------------------------------------------------------------------------
  void parse_sphere(const SceneToken& kw) {
    double d[4];
    SceneToken tok[4];
    take_numbers(kw, 4, d, tok, "sphere centre and radius (x y z r)");
    if (!(d[3] > 0.0)) {
      fail(tok[3], cat("sphere radius must be > 0, got ", quote_token(tok[3].text)));
    }
    scene_.spheres.push_back(Sphere{vec_of(d), d[3]});
    add_primitive(PrimitiveKind::Sphere, scene_.spheres.size() - 1, kw);
  }

  void parse_cone(const SceneToken& kw) {
    double base[4];
    double apex[4];
    take_numbers(kw, 4, base, nullptr, "cone base (x y z r)");
    take_numbers(kw, 4, apex, nullptr, "cone apex (x y z r)");
    scene_.cones.push_back(Cone{vec_of(base), base[3], vec_of(apex), apex[3]});
    add_primitive(PrimitiveKind::Cone, scene_.cones.size() - 1, kw);
  }

  void parse_polygon(const SceneToken& kw, bool with_normals) {
    const SceneToken* t = cursor_.peek();
    if (t == nullptr || is_keyword(t->text)) {
      fail_missing(kw, cat("expected the vertex count after '", kw.text, "'"), t, ", got ");
    }
    const SceneToken count_token = *t;
    const std::int64_t count = parse_integer(cursor_, count_token, "polygon vertex count");
    if (count < 3) {
      fail(count_token,
           cat("polygon needs at least 3 vertices, got ", quote_token(count_token.text)));
    }
    if (count > kMaxPolygonVertices) {
      fail(count_token,
           cat("polygon vertex count ", count, " exceeds the limit of ", kMaxPolygonVertices,
               " (kMaxPolygonVertices: larger polygons can take minutes to "
               "triangulate); split it into smaller polygons"));
    }
    cursor_.skip();
    const auto n = static_cast<std::size_t>(count);
    const std::size_t per_vertex = with_normals ? 6 : 3;
    // Checked before allocating: every number is one token, so the file must still hold them.
    if (n * per_vertex > cursor_.tokens_left()) {
      fail(kw,
           cat("polygon declares ", n, " vertices (", n * per_vertex,
               " numbers) but the file has only ", values_text(cursor_.tokens_left()), " left"));
    }
    Polygon poly;
    poly.vertices.reserve(n);
    if (with_normals) poly.normals.reserve(n);
    const std::string_view layout = with_normals ? "x y z nx ny nz" : "x y z";
    double d[6];
    for (std::size_t i = 0; i < n; ++i) {
      take_numbers(kw, per_vertex, d, nullptr,
                   [&] { return cat("polygon vertex ", i + 1, " of ", n, " (", layout, ")"); });
      poly.vertices.push_back(vec_of(d));
      if (with_normals) poly.normals.push_back(vec_of(d + 3));
    }
    scene_.polygons.push_back(std::move(poly));
    add_primitive(PrimitiveKind::Polygon, scene_.polygons.size() - 1, kw);
  }

  TokenCursor cursor_;
  Scene scene_;
  std::size_t view_line_ = 0;
  std::size_t background_line_ = 0;
  std::optional<Material> pending_material_;
  std::optional<std::uint32_t> current_material_;
  std::map<MaterialKey, std::uint32_t> material_ids_;
  // The entity before the current one, for messages about a token it did not take.
  SceneToken previous_;
  std::size_t previous_values_ = 0;
  std::size_t previous_end_line_ = 0;
};

}  // namespace

Scene parse_nff(std::string_view text, const std::string& name) {
  return NffParser(text, name).parse();
}

Scene read_nff(const std::string& path) { return parse_nff(read_scene_file(path), path); }

}  // namespace rtsim::scenes
