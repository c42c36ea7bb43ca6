#include "scenes/bpt_reader.hpp"

#include "scenes/scene_text.hpp"

namespace rtsim::scenes {

namespace {

/// Control points of a bicubic patch, and numbers per patch: the two degrees and 16 x y z.
constexpr std::size_t kPointsPerPatch = 16;
constexpr std::size_t kNumbersPerPatch = 2 + 3 * kPointsPerPatch;

}  // namespace

Scene parse_bpt(std::string_view text, const std::string& name) {
  TokenCursor cursor(text, name);
  Scene scene;
  scene.name = name;

  SceneToken count_token;
  if (!cursor.next(count_token)) {
    cursor.fail(0, "empty .bpt file; expected the number of patches first");
  }
  const std::int64_t count = parse_integer(cursor, count_token, "the patch count");
  if (count < 1 || count > kMaxBptPatches) {
    cursor.fail(count_token.line, cat("patch count must be 1..", kMaxBptPatches,
                                      " (kMaxBptPatches), got ", quote_token(count_token.text)));
  }
  const auto n = static_cast<std::size_t>(count);
  // Checked before allocating: every number is one token, so the file must still hold them.
  if (n > cursor.tokens_left() / kNumbersPerPatch) {
    const std::size_t left = cursor.tokens_left();
    cursor.fail(count_token.line,
                cat("file declares ", n, n == 1 ? " patch (" : " patches (", kNumbersPerPatch,
                    " numbers each: the degrees '3 3' and 16 control points x y z) but has only ",
                    left, left == 1 ? " value" : " values", " left"));
  }
  scene.patches.reserve(n);
  scene.primitives.reserve(n);
  scene.materials.push_back(kDefaultBptMaterial);

  for (std::size_t p = 0; p < n; ++p) {
    SceneToken du_token;
    SceneToken dv_token;
    // The ends of the file below cannot come after the check above; kept as guards.
    if (!cursor.next(du_token) || !cursor.next(dv_token)) {
      cursor.fail(count_token.line, cat("file declares ", n, " patches but ends after ", p));
    }
    const std::string patch_label = cat("patch ", p + 1, " of ", n);
    const std::int64_t du = parse_integer(cursor, du_token, cat("the u degree of ", patch_label));
    const std::int64_t dv = parse_integer(cursor, dv_token, cat("the v degree of ", patch_label));
    if (du != 3 || dv != 3) {
      cursor.fail(du_token.line, cat(patch_label, " has degrees ",
                                     quote_token(cat(du_token.text, " ", dv_token.text)),
                                     "; only bicubic patches ('3 3') are supported"));
    }
    BezierPatch patch;
    for (std::size_t k = 0; k < kPointsPerPatch; ++k) {
      double d[3];
      for (std::size_t j = 0; j < 3; ++j) {
        SceneToken t;
        if (!cursor.next(t)) {
          cursor.fail(du_token.line, cat("file ends inside ", patch_label, " after ", k,
                                         " of its 16 control points"));
        }
        const NumberStatus status = try_parse_number(t.text, d[j]);
        if (status != NumberStatus::kOk) {
          fail_number(cursor, t, status, cat("control point ", k + 1, " of 16 of ", patch_label),
                      j + 1);
        }
      }
      patch.control[k] = Vec3{d[0], d[1], d[2]};
    }
    scene.patches.push_back(patch);
    scene.primitives.push_back(Primitive{PrimitiveKind::Patch, static_cast<std::uint32_t>(p), 0,
                                         static_cast<std::uint32_t>(du_token.line)});
  }

  if (const SceneToken* extra = cursor.peek()) {
    cursor.fail(extra->line, cat("unexpected content after the last of ", n,
                                 " patches: ", quote_token(cursor.rest_of_line(*extra))));
  }
  return scene;
}

Scene read_bpt(const std::string& path) { return parse_bpt(read_scene_file(path), path); }

}  // namespace rtsim::scenes
