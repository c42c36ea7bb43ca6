#pragma once
// Gaudet's three disjoint data sets as Broadcast Processor memory images (seed 001 §4.4,
// L656-L714; §5.3.1, L875-L879).
//  * shell data set: packet i = SHELL_ARRAY[i], the SHELL records of one sibling list;
//  * prim data set:  packet j = PRIM_ARRAY[j], the PRIM records of one leaf shell;
//  * shade data set: packet k = SHADE_ARRAY[k], the SHADE record of one surface (L700-L702).
//
// The thesis gives the C structs (Fig. 4-3, 4-5, 4-7) but no sizes for COORD, PTYPE, RGB, int
// or float on the PERT. Assumption (seed note 001 §6.2): 32-bit words (the broadcast bus is
// 32 bits wide, L867), one word per int, IEEE single per float, COORD = RGB = 3 words; `next`
// pointers are implicit because siblings are contiguous in a packet. The word count of each
// record type is a named parameter (RecordWords) so a machine can be calibrated: fields are
// written first and the record is padded with zero words to the configured size; a size
// smaller than the fields is an error.
//
// PTYPE is a union in Fig. 4-5; a C union would pad every PRIM to its largest member. We store
// each PRIM at its own type's size instead (the type field says how to read it) because the BP
// streams words and a padded union would charge a sphere for a patch's 48 coordinates.
#include <cstdint>
#include <functional>
#include <span>
#include <vector>

#include "firmware/accel/broadcast_image.hpp"
#include "firmware/accel/shell_tree.hpp"
#include "firmware/scene.hpp"

namespace rtsim::accel {

/// Words per record, the calibration knobs (defaults: the field counts of the thesis structs).
struct RecordWords {
  std::uint32_t id_list_entry = kIdListEntryWords;  ///< {ID, address, size} (L877)
  std::uint32_t shell = 8;               ///< leaf, child_index, max[3], min[3] (Fig. 4-3)
  std::uint32_t prim_header = 3;         ///< prim_id, surface_index, type (Fig. 4-5)
  std::uint32_t sphere = 4;              ///< PTYPE sphere: centre[3], radius
  std::uint32_t polygon_fixed = 1;       ///< PTYPE polygon: vertex count (bit 31: has normals)
  std::uint32_t polygon_per_vertex = 3;  ///< one COORD per vertex
  std::uint32_t polygon_per_normal = 3;  ///< one COORD per vertex normal, when present
  std::uint32_t cone = 8;                ///< PTYPE cone: base[3], base radius, apex[3], apex radius
  std::uint32_t patch = 48;              ///< PTYPE bicubic patch: 16 control points
  std::uint32_t shade = 9;  ///< k_s, k_d, n, reflectance[3], transmittance[3] (Fig. 4-7)
};

/// The `type` word of a PRIM record (Fig. 4-5: "sphere, polygon or whatever", L680).
enum class PrimType : std::uint32_t { Sphere = 0, Polygon = 1, Cone = 2, Patch = 3 };

/// Writes one record: its fields, then zero words up to the configured size.
class RecordWriter {
 public:
  /// Throws std::invalid_argument from finish() if the fields exceed record_words.
  RecordWriter(std::vector<std::uint32_t>& out, std::uint32_t record_words, const char* what)
      : out_(&out), start_(out.size()), words_(record_words), what_(what) {}
  void word(std::uint32_t w) { out_->push_back(w); }
  void f32(double v);       ///< nearest single
  void f32_down(double v);  ///< largest single <= v (a box's min corner stays outside)
  void f32_up(double v);    ///< smallest single >= v
  void coord(const Vec3& v) {
    f32(v.x);
    f32(v.y);
    f32(v.z);
  }
  void finish();

 private:
  std::vector<std::uint32_t>* out_;
  std::size_t start_;
  std::uint32_t words_;
  const char* what_;
};

/// Appends the complete PRIM record of primitive `slot` (header and PTYPE).
using PrimEncoder = std::function<void(std::uint32_t slot, std::vector<std::uint32_t>& out)>;

/// SHELL record: leaf, child_index, max[3], min[3] (Fig. 4-3 field order); the box is rounded
/// outward to single precision so the stored shell still encloses its contents.
void encode_shell(const Shell& s, const RecordWords& words, std::vector<std::uint32_t>& out);
/// The SHELL at the start of `record` (at least 8 words), as encode_shell wrote it: what a
/// ShellProcessor reads out of a packet.
Shell decode_shell(std::span<const std::uint32_t> record);
/// `box` as a SHELL record stores it: decode_shell(encode_shell(box)).box.
Bounds stored_shell_box(const Bounds& box);

/// A PRIM record as a PrimProcessor reads it: prim_id, surface_index, type, then the PTYPE's
/// fields in order (a sphere's centre and radius; a polygon's vertex count, bit 31 set when
/// vertex normals follow the vertices, and its vertices).
struct PrimRecord {
  std::uint32_t prim_id = 0;
  std::uint32_t surface_index = 0;
  PrimType type = PrimType::Sphere;
  Vec3 center{0.0};
  double radius = 0.0;
  std::vector<Vec3> vertices{};
};
/// Decodes the PRIM record at the start of `words` into `out` and returns its size in words
/// (the configured size of its type), or 0 if it is not a sphere or polygon record that fits.
std::size_t decode_prim(std::span<const std::uint32_t> words, const RecordWords& record_words,
                        PrimRecord& out);
/// SHADE record from an NFF material: k_s = Ks, k_d = Kd, n = round(shine), reflectance = the
/// colour, transmittance = (T, T, T) (NFF's T is one number; Gaudet's is RGB).
void encode_shade(const scenes::Material& m, const RecordWords& words,
                  std::vector<std::uint32_t>& out);

BroadcastImage shell_data_set(const ShellTree& tree, const RecordWords& words = {});
BroadcastImage prim_data_set(const ShellTree& tree, const PrimEncoder& encode,
                             const RecordWords& words = {});
BroadcastImage shade_data_set(std::span<const scenes::Material> materials,
                              const RecordWords& words = {});

/// PRIM records for the primitives of a scene: prim_id = the slot (scene-file order),
/// surface_index = the material, the geometry by kind.
PrimEncoder scene_prim_encoder(const scenes::Scene& scene, const RecordWords& words = {});

struct GaudetDataSets {
  BroadcastImage shell;
  BroadcastImage prim;
  BroadcastImage shade;
};

/// All three, for a tree built over `scene`'s primitives (slot = index in scene.primitives).
GaudetDataSets make_gaudet_data_sets(const ShellTree& tree, const scenes::Scene& scene,
                                     const RecordWords& words = {});

}  // namespace rtsim::accel
