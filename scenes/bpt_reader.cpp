#include "scenes/bpt_reader.hpp"

#include "scenes/scene_text.hpp"

namespace rtsim::scenes {

namespace {

/// Lines per patch: the degree line and 16 control points.
constexpr std::size_t kLinesPerPatch = 17;

}  // namespace

Scene parse_bpt(std::string_view text, const std::string& name) {
  LineCursor cursor(text, name);
  Scene scene;
  scene.name = name;

  SceneLine count_line;
  if (!cursor.next(count_line)) {
    cursor.fail(0, "empty .bpt file; expected the number of patches on the first line");
  }
  if (count_line.tokens.size() != 1) {
    cursor.fail(count_line.number,
                cat("expected 1 number (the patch count) on the first line, got ",
                    count_line.tokens.size(), " values"));
  }
  const std::int64_t count =
      parse_integer(cursor, count_line, count_line.tokens[0], "the patch count");
  if (count < 1 || count > kMaxBptPatches) {
    cursor.fail(count_line.number,
                cat("patch count must be 1..", kMaxBptPatches, " (kMaxBptPatches), got ",
                    quote_token(count_line.tokens[0])));
  }
  const auto n = static_cast<std::size_t>(count);
  if (n > cursor.lines_left() / kLinesPerPatch) {
    cursor.fail(count_line.number,
                cat("file declares ", n, " patches (", kLinesPerPatch, " lines each) but has only ",
                    cursor.lines_left(), " lines left"));
  }
  scene.patches.reserve(n);
  scene.primitives.reserve(n);
  scene.materials.push_back(kDefaultBptMaterial);

  for (std::size_t p = 0; p < n; ++p) {
    SceneLine degree_line;
    if (!cursor.next(degree_line)) {
      cursor.fail(count_line.number, cat("file declares ", n, " patches but ends after ", p));
    }
    const std::string patch_label = cat("patch ", p + 1, " of ", n);
    if (degree_line.tokens.size() != 2) {
      cursor.fail(degree_line.number, cat("expected the degree line '3 3' of ", patch_label,
                                          ", got ", quote_token(degree_line.text)));
    }
    const std::int64_t du = parse_integer(cursor, degree_line, degree_line.tokens[0],
                                          cat("the u degree of ", patch_label));
    const std::int64_t dv = parse_integer(cursor, degree_line, degree_line.tokens[1],
                                          cat("the v degree of ", patch_label));
    if (du != 3 || dv != 3) {
      cursor.fail(degree_line.number,
                  cat(patch_label, " has degrees ", quote_token(degree_line.text),
                      "; only bicubic patches ('3 3') are supported"));
    }
    BezierPatch patch;
    for (std::size_t k = 0; k < patch.control.size(); ++k) {
      SceneLine line;
      if (!cursor.next(line)) {
        cursor.fail(degree_line.number, cat("file ends inside ", patch_label, " after ", k,
                                            " of its 16 control points"));
      }
      double d[3];
      parse_numbers(cursor, line, 0, 3, cat("control point ", k + 1, " of 16 of ", patch_label), d);
      patch.control[k] = Vec3{d[0], d[1], d[2]};
    }
    scene.patches.push_back(patch);
    scene.primitives.push_back(Primitive{PrimitiveKind::Patch, static_cast<std::uint32_t>(p), 0,
                                         static_cast<std::uint32_t>(degree_line.number)});
  }

  SceneLine extra;
  if (cursor.next(extra)) {
    cursor.fail(extra.number, cat("unexpected content after the last of ", n,
                                  " patches: ", quote_token(extra.text)));
  }
  return scene;
}

Scene read_bpt(const std::string& path) { return parse_bpt(read_scene_file(path), path); }

}  // namespace rtsim::scenes
