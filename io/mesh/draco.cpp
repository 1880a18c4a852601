#include "io/mesh/draco.h"

#include <draco/compression/decode.h>
#include <draco/compression/encode.h>
#include <draco/core/quantization_utils.h>
#include <draco/mesh/mesh.h>
#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <map>
#include <memory>
#include <optional>

#include "geometry/core/error_checks.h"
#include "geometry/core/float32.h"
#include "geometry/mesh/bounding_box.h"
#include "geometry/mesh/halfedge_mesh.h"
#include "io/file.h"

namespace fabmesh {
namespace {

[[noreturn]] void fail(const std::string& name, const std::string& message) {
  throw FileError(name, 0, 0, fmt::format("{}: {}", name, message));
}

// The bounding box of the soup's vertices; an empty soup's is the origin.
BoundingBox box_of(const TriangleSoup& soup) {
  if (soup.vertices.empty()) return {Vec3::Zero(), Vec3::Zero()};
  return bounding_box(soup.vertices);
}

/// Reads Draco's header fields in order; every read fails cleanly past the end.
class HeaderReader {
 public:
  explicit HeaderReader(std::string_view bytes) : bytes_(bytes) {}
  bool byte(std::uint8_t& out) {
    if (pos_ >= bytes_.size()) return false;
    out = static_cast<std::uint8_t>(bytes_[pos_++]);
    return true;
  }
  bool skip(std::uint64_t n) {
    if (bytes_.size() - pos_ < n) return false;
    pos_ += static_cast<std::size_t>(n);
    return true;
  }
  /// A little-endian fixed-size integer of `n` bytes.
  bool fixed(std::uint64_t& out, int n) {
    out = 0;
    for (int i = 0; i < n; ++i) {
      std::uint8_t b = 0;
      if (!byte(b)) return false;
      out |= std::uint64_t{b} << (8 * i);
    }
    return true;
  }
  /// Draco's varint: 7 bits a byte, low first, at most 5 bytes for 32 bits.
  bool varint(std::uint64_t& out) {
    out = 0;
    for (int i = 0; i < 5; ++i) {
      std::uint8_t b = 0;
      if (!byte(b)) return false;
      out |= std::uint64_t{b & 0x7fu} << (7 * i);
      if ((b & 0x80u) == 0) return true;
    }
    return false;
  }
  /// A name: one length byte, then that many bytes.
  bool name() {
    std::uint8_t length = 0;
    return byte(length) && skip(length);
  }
  std::size_t remaining() const { return bytes_.size() - pos_; }

 private:
  std::string_view bytes_;
  std::size_t pos_ = 0;
};

/// Skips one metadata tree: its entries (name, size, bytes), then its
/// sub-metadata (each a name and a tree), depth first as libdraco reads them.
/// Every block read takes at least two bytes, so this ends with the data.
bool skip_metadata_tree(HeaderReader& in) {
  std::uint64_t pending = 1;
  for (bool root = true; pending > 0; root = false) {
    --pending;
    if (!root && !in.name()) return false;
    std::uint64_t entries = 0;
    if (!in.varint(entries)) return false;
    for (std::uint64_t e = 0; e < entries; ++e) {
      std::uint64_t size = 0;
      if (!in.name() || !in.varint(size) || !in.skip(size)) return false;
    }
    std::uint64_t subs = 0;
    if (!in.varint(subs) || subs > in.remaining()) return false;
    pending += subs;
  }
  return true;
}

/// Skips the metadata block: per attribute its id and tree, then the geometry's tree.
bool skip_metadata(HeaderReader& in) {
  std::uint64_t attributes = 0;
  if (!in.varint(attributes)) return false;
  for (std::uint64_t a = 0; a < attributes; ++a) {
    std::uint64_t id = 0;
    if (!in.varint(id) || !skip_metadata_tree(in)) return false;
  }
  return skip_metadata_tree(in);
}

/// The number of triangles a Draco mesh's header declares, read before
/// libdraco allocates for it; nullopt when the header ends early or the
/// method is unknown (libdraco then refuses the file itself).
std::optional<std::uint64_t> declared_triangles(std::string_view bytes) {
  HeaderReader in(bytes);
  std::uint64_t major = 0, minor = 0, type = 0, method = 0, flags = 0;
  if (!in.skip(5) || !in.fixed(major, 1) || !in.fixed(minor, 1) || !in.fixed(type, 1) ||
      !in.fixed(method, 1) || !in.fixed(flags, 2)) {
    return std::nullopt;
  }
  const std::uint64_t version = major * 256 + minor;
  if ((flags & 0x8000u) != 0 && version >= 0x0103 && !skip_metadata(in)) return std::nullopt;
  // Counts are 32-bit words before bitstream 2.0 (sequential: before 2.2), varints after.
  const auto count = [&](std::uint64_t& out, std::uint64_t varint_since) {
    return version < varint_since ? in.fixed(out, 4) : in.varint(out);
  };
  std::uint64_t faces = 0, unused = 0;
  if (method == 0) {  // sequential: faces, then points
    if (!count(faces, 0x0202)) return std::nullopt;
    return faces;
  }
  if (method == 1) {  // edgebreaker: traversal type, [new vertices], vertices, faces
    if (!in.fixed(unused, 1)) return std::nullopt;
    if (version < 0x0202 && !count(unused, 0x0200)) return std::nullopt;
    if (!count(unused, 0x0200) || !count(faces, 0x0200)) return std::nullopt;
    return faces;
  }
  return std::nullopt;
}

}  // namespace

double draco_max_error(const Vec3& lo, const Vec3& hi, int bits) {
  const double extent = (hi - lo).maxCoeff();
  const double magnitude = std::max(lo.cwiseAbs().maxCoeff(), hi.cwiseAbs().maxCoeff());
  const double steps = std::ldexp(1.0, bits) - 1.0;
  // Half a step of rounding to the grid, plus a generous allowance for the
  // float32 arithmetic of conversion, quantization and dequantization.
  const double float_rounding = 8.0 * std::ldexp(magnitude + extent, -24);
  return std::sqrt(3.0) * (0.5 * extent / steps + float_rounding);
}

DracoQuantization draco_quantization(const Vec3& lo, const Vec3& hi, double tolerance) {
  require_positive("draco tolerance", tolerance);
  for (int bits = 1; bits <= 30; ++bits) {
    const double error = draco_max_error(lo, hi, bits);
    if (error <= tolerance) return {bits, error};
  }
  throw RangeError(
      "draco tolerance", tolerance,
      fmt::format("draco tolerance = {} is below what 30-bit float32 positions can hold for a mesh "
                  "of extent {} (best: {})",
                  tolerance, (hi - lo).maxCoeff(), draco_max_error(lo, hi, 30)));
}

TriangleSoup parse_draco(std::string_view bytes, const std::string& name, std::size_t max_triangles) {
  draco::DecoderBuffer buffer;
  buffer.Init(bytes.data(), bytes.size());
  const auto type = draco::Decoder::GetEncodedGeometryType(&buffer);
  if (!type.ok()) fail(name, fmt::format("not a Draco file: {}", type.status().error_msg_string()));
  if (type.value() != draco::TRIANGULAR_MESH) fail(name, "the Draco file holds a point cloud, not a mesh");
  if (const auto declared = declared_triangles(bytes)) {
    const std::uint64_t plausible = std::uint64_t{kMaxDracoTrianglesPerByte} * bytes.size() + 4096;
    if (*declared > max_triangles) {
      fail(name, fmt::format("the Draco mesh declares {} triangles, more than the {} fabmesh reads",
                             *declared, max_triangles));
    }
    if (*declared > plausible) {
      fail(name,
           fmt::format("corrupt Draco mesh: it declares {} triangles in {} bytes", *declared, bytes.size()));
    }
  }
  draco::Decoder decoder;
  auto decoded = decoder.DecodeMeshFromBuffer(&buffer);
  if (!decoded.ok()) fail(name, fmt::format("corrupt Draco mesh: {}", decoded.status().error_msg_string()));
  const std::unique_ptr<draco::Mesh> mesh = std::move(decoded).value();
  if (!mesh) fail(name, "corrupt Draco mesh");
  const draco::PointAttribute* position = mesh->GetNamedAttribute(draco::GeometryAttribute::POSITION);
  if (position == nullptr) fail(name, "the Draco mesh has no positions");
  if (position->num_components() != 3) fail(name, "Draco positions are not 3D");
  // Reading a BOOL attribute as numbers is undefined behaviour inside libdraco
  // (found by fuzzing): positions must be a numeric type.
  const draco::DataType stored = position->data_type();
  if (stored == draco::DT_BOOL || stored == draco::DT_INVALID || stored >= draco::DT_TYPES_COUNT) {
    fail(name, "Draco positions are not numbers");
  }
  TriangleSoup soup;
  const draco::PointIndex::ValueType np = mesh->num_points();
  soup.vertices.reserve(np);
  for (draco::PointIndex::ValueType i = 0; i < np; ++i) {
    const draco::AttributeValueIndex value = position->mapped_index(draco::PointIndex(i));
    if (value.value() >= position->size()) fail(name, fmt::format("point {} has no position", i));
    float xyz[3];
    if (!position->ConvertValue<float, 3>(value, xyz)) fail(name, "cannot read Draco positions");
    const Vec3 p(xyz[0], xyz[1], xyz[2]);
    if (!std::isfinite(p.x()) || !std::isfinite(p.y()) || !std::isfinite(p.z())) {
      fail(name, fmt::format("point {} has a non-finite position", i));
    }
    soup.vertices.push_back(p);
  }
  soup.triangles.reserve(mesh->num_faces());
  for (draco::FaceIndex::ValueType f = 0; f < mesh->num_faces(); ++f) {
    const draco::Mesh::Face& face = mesh->face(draco::FaceIndex(f));
    std::array<std::uint32_t, 3> t{};
    for (int k = 0; k < 3; ++k) {
      t[k] = face[k].value();
      if (t[k] >= np) fail(name, fmt::format("face {} refers to point {} of {}", f, t[k], np));
    }
    soup.triangles.push_back(t);
  }
  return soup;
}

namespace {

// A Draco mesh of the soup's positions (float32) and faces; with `with_ids`
// also a lossless integer attribute holding each point's index in the soup.
std::unique_ptr<draco::Mesh> draco_mesh(const TriangleSoup& soup, bool with_ids) {
  auto mesh = std::make_unique<draco::Mesh>();
  const auto np = static_cast<draco::PointIndex::ValueType>(soup.vertices.size());
  mesh->set_num_points(np);
  draco::GeometryAttribute attribute;
  attribute.Init(draco::GeometryAttribute::POSITION, nullptr, 3, draco::DT_FLOAT32, false, sizeof(float) * 3,
                 0);
  draco::PointAttribute* position = mesh->attribute(mesh->AddAttribute(attribute, true, np));
  for (draco::PointIndex::ValueType i = 0; i < np; ++i) {
    const Vec3& p = soup.vertices[i];
    const float xyz[3] = {static_cast<float>(p.x()), static_cast<float>(p.y()), static_cast<float>(p.z())};
    position->SetAttributeValue(draco::AttributeValueIndex(i), xyz);
  }
  if (with_ids) {
    draco::GeometryAttribute ids;
    ids.Init(draco::GeometryAttribute::GENERIC, nullptr, 1, draco::DT_UINT32, false, sizeof(std::uint32_t),
             0);
    draco::PointAttribute* id = mesh->attribute(mesh->AddAttribute(ids, true, np));
    for (draco::PointIndex::ValueType i = 0; i < np; ++i)
      id->SetAttributeValue(draco::AttributeValueIndex(i), &i);
  }
  for (const auto& t : soup.triangles) {
    mesh->AddFace({draco::PointIndex(t[0]), draco::PointIndex(t[1]), draco::PointIndex(t[2])});
  }
  return mesh;
}

std::string encode(const draco::Mesh& mesh, int bits, const DracoOptions& options) {
  draco::Encoder encoder;
  encoder.SetAttributeQuantization(draco::GeometryAttribute::POSITION, bits);
  encoder.SetSpeedOptions(options.encoding_speed, options.decoding_speed);
  draco::EncoderBuffer buffer;
  const draco::Status status = encoder.EncodeMeshToBuffer(mesh, &buffer);
  if (!status.ok()) throw InputError(fmt::format("Draco encoder: {}", status.error_msg_string()));
  return std::string(buffer.data(), buffer.size());
}

std::unique_ptr<draco::Mesh> decode(std::string_view bytes) {
  draco::DecoderBuffer buffer;
  buffer.Init(bytes.data(), bytes.size());
  draco::Decoder decoder;
  auto decoded = decoder.DecodeMeshFromBuffer(&buffer);
  if (!decoded.ok() || !decoded.value()) throw std::logic_error("Draco cannot decode its own output");
  return std::move(decoded).value();
}

std::array<std::uint32_t, 3> canonical(std::array<std::uint32_t, 3> t) {
  // Rotate so the smallest index comes first: the same face whatever corner a decoder starts at.
  while (t[0] > t[1] || t[0] > t[2]) t = {t[1], t[2], t[0]};
  return t;
}

// The decoded mesh of an id-tagged encoding in the soup's order, or nullopt
// when its faces are not the soup's.
std::optional<TriangleSoup> decode_tagged(const std::string& bytes, const TriangleSoup& soup) {
  const std::unique_ptr<draco::Mesh> mesh = decode(bytes);
  const draco::PointAttribute* position = mesh->GetNamedAttribute(draco::GeometryAttribute::POSITION);
  const draco::PointAttribute* ids = mesh->GetNamedAttribute(draco::GeometryAttribute::GENERIC);
  if (position == nullptr || ids == nullptr)
    throw std::logic_error("Draco lost an attribute of its own output");
  TriangleSoup out;
  out.vertices = soup.vertices;  // unreferenced vertices (Draco drops them) keep their place
  std::vector<std::uint32_t> original(mesh->num_points());
  for (draco::PointIndex::ValueType i = 0; i < mesh->num_points(); ++i) {
    std::uint32_t id = 0;
    ids->ConvertValue<std::uint32_t, 1>(ids->mapped_index(draco::PointIndex(i)), &id);
    float xyz[3];
    position->ConvertValue<float, 3>(position->mapped_index(draco::PointIndex(i)), xyz);
    if (id >= soup.vertices.size()) return std::nullopt;
    original[i] = id;
    out.vertices[id] = Vec3(xyz[0], xyz[1], xyz[2]);
  }
  if (mesh->num_faces() != soup.triangles.size()) return std::nullopt;
  std::vector<std::array<std::uint32_t, 3>> decoded_faces, input_faces;
  for (draco::FaceIndex::ValueType f = 0; f < mesh->num_faces(); ++f) {
    const draco::Mesh::Face& face = mesh->face(draco::FaceIndex(f));
    decoded_faces.push_back(
        canonical({original[face[0].value()], original[face[1].value()], original[face[2].value()]}));
  }
  for (const auto& t : soup.triangles) input_faces.push_back(canonical(t));
  std::sort(decoded_faces.begin(), decoded_faces.end());
  std::sort(input_faces.begin(), input_faces.end());
  if (decoded_faces != input_faces) return std::nullopt;
  out.triangles = soup.triangles;
  return out;
}

double max_displacement(const TriangleSoup& a, const TriangleSoup& b) {
  double worst = 0.0;
  for (std::size_t i = 0; i < a.vertices.size(); ++i)
    worst = std::max(worst, (a.vertices[i] - b.vertices[i]).norm());
  return worst;
}

/// Where Draco's position quantization with `bits` puts each vertex of
/// `soup`: the float32 positions a decoder returns. It follows Draco's
/// AttributeQuantizationTransform (float32 arithmetic, Draco's own Quantizer
/// and Dequantizer): the box's minimum corner and its largest extent (1 when
/// zero) set the grid. A prediction only: decode_matched verifies it.
std::vector<std::array<float, 3>> predicted_positions(const TriangleSoup& soup, int bits) {
  std::array<float, 3> lo{}, hi{};
  for (int k = 0; k < 3; ++k) {
    lo[k] = std::numeric_limits<float>::infinity();
    hi[k] = -lo[k];
  }
  for (const Vec3& p : soup.vertices) {
    for (int k = 0; k < 3; ++k) {
      lo[k] = std::min(lo[k], static_cast<float>(p[k]));
      hi[k] = std::max(hi[k], static_cast<float>(p[k]));
    }
  }
  float range = 0.0f;
  for (int k = 0; k < 3; ++k) range = std::max(range, hi[k] - lo[k]);
  if (range == 0.0f) range = 1.0f;
  const auto max_quantized = static_cast<std::int32_t>((std::uint32_t{1} << bits) - 1);
  draco::Quantizer quantizer;
  quantizer.Init(range, max_quantized);
  draco::Dequantizer dequantizer;
  std::vector<std::array<float, 3>> out(soup.vertices.size());
  if (!dequantizer.Init(range, max_quantized)) return {};
  for (std::size_t i = 0; i < soup.vertices.size(); ++i) {
    for (int k = 0; k < 3; ++k) {
      const std::int32_t q = quantizer.QuantizeFloat(static_cast<float>(soup.vertices[i][k]) - lo[k]);
      out[i][k] = dequantizer.DequantizeFloat(q) + lo[k];
    }
  }
  return out;
}

/// The bits of three floats, for exact comparison (+0 and -0 differ, as they may in a file).
struct FloatKey {
  std::uint32_t x, y, z;
  bool operator==(const FloatKey& o) const { return x == o.x && y == o.y && z == o.z; }
};
struct FloatKeyHash {
  std::size_t operator()(const FloatKey& k) const {
    std::uint64_t h = k.x * 0x9E3779B97F4A7C15ull;
    h ^= (h >> 29) + k.y * 0xBF58476D1CE4E5B9ull;
    h ^= (h >> 31) + k.z * 0x94D049BB133111EBull;
    return static_cast<std::size_t>(h ^ (h >> 32));
  }
};
FloatKey key_of(const float xyz[3]) {
  FloatKey k{};
  std::memcpy(&k.x, &xyz[0], 4);
  std::memcpy(&k.y, &xyz[1], 4);
  std::memcpy(&k.z, &xyz[2], 4);
  return k;
}

/// Positions (bit patterns) to indices for up to `n` entries: open
/// addressing with linear probing, at least twice as many slots as entries
/// (one allocation, where a node-based map makes one per entry).
class PositionTable {
 public:
  static constexpr std::uint32_t kNone = std::numeric_limits<std::uint32_t>::max();
  explicit PositionTable(std::size_t n) {
    std::size_t slots = 16;
    while (slots < 2 * n) slots *= 2;
    mask_ = slots - 1;
    slots_.assign(slots, Slot{{}, kNone});
  }
  /// Adds `key` -> `value`; false (and nothing changed) when `key` is there.
  bool insert(const FloatKey& key, std::uint32_t value) {
    for (std::size_t i = FloatKeyHash{}(key)&mask_;; i = (i + 1) & mask_) {
      if (slots_[i].value == kNone) {
        slots_[i] = {key, value};
        return true;
      }
      if (slots_[i].key == key) return false;
    }
  }
  /// The value of `key`, or kNone.
  std::uint32_t find(const FloatKey& key) const {
    for (std::size_t i = FloatKeyHash{}(key)&mask_;; i = (i + 1) & mask_) {
      if (slots_[i].value == kNone || slots_[i].key == key) return slots_[i].value;
    }
  }

 private:
  struct Slot {
    FloatKey key;
    std::uint32_t value;
  };
  std::size_t mask_ = 0;
  std::vector<Slot> slots_;
};

/// Draco's predicted positions (predicted_positions) for the bit count a
/// fit looked at last, computed once, whether each bit count puts two
/// vertices that faces use at one position, and which vertices faces use.
class Predictions {
 public:
  explicit Predictions(const TriangleSoup& soup) : soup_(soup), referenced_(soup.vertices.size(), 0) {
    for (const auto& t : soup.triangles) referenced_[t[0]] = referenced_[t[1]] = referenced_[t[2]] = 1;
  }
  /// Empty when Draco's dequantizer refuses the grid.
  const std::vector<std::array<float, 3>>& positions(int bits) {
    if (bits != bits_) {
      positions_ = predicted_positions(soup_, bits);
      bits_ = bits;
    }
    return positions_;
  }
  bool collide(int bits) {
    const auto known = collide_.find(bits);
    if (known != collide_.end()) return known->second;
    const std::vector<std::array<float, 3>>& predicted = positions(bits);
    bool found = false;
    if (predicted.size() == soup_.vertices.size()) {
      PositionTable seen(soup_.vertices.size());
      for (std::size_t i = 0; i < soup_.vertices.size() && !found; ++i)
        found = referenced_[i] && !seen.insert(key_of(predicted[i].data()), static_cast<std::uint32_t>(i));
    }
    collide_.emplace(bits, found);
    return found;
  }
  const std::vector<char>& referenced() const { return referenced_; }

 private:
  const TriangleSoup& soup_;
  std::vector<char> referenced_;
  int bits_ = -1;
  std::vector<std::array<float, 3>> positions_;
  std::map<int, bool> collide_;
};

/// The mesh that `bytes` (an encoding of `soup` without ids, `bits` of
/// quantization) decode to, in the soup's vertex order and with the soup's
/// triangles; nullopt when the correspondence cannot be established this way
/// (the caller then falls back to an id-tagged encoding).
///
/// Why the result is exactly the decoded file: each decoded point p_j is
/// assigned the input vertex sigma(j) whose predicted decoded position equals
/// p_j bit for bit. The assignment is accepted only when sigma is a bijection
/// from the decoded points onto the referenced input vertices (no decoded
/// position repeats, every referenced vertex finds a point) and sigma maps
/// the decoded faces one to one onto the soup's faces, each with its
/// orientation (the same cyclic order). Then relabelling by sigma turns the
/// decoded mesh into the returned one: the same faces over the same
/// positions. The prediction is only a guess; the checks make it a proof.
std::optional<TriangleSoup> decode_matched(const std::string& bytes, const TriangleSoup& soup, int bits,
                                           Predictions& predictions) {
  const std::unique_ptr<draco::Mesh> mesh = decode(bytes);
  const draco::PointAttribute* position = mesh->GetNamedAttribute(draco::GeometryAttribute::POSITION);
  if (position == nullptr) throw std::logic_error("Draco lost the positions of its own output");
  const std::size_t np = mesh->num_points();
  if (mesh->num_faces() != soup.triangles.size()) return std::nullopt;
  std::vector<std::array<float, 3>> decoded(np);
  PositionTable point_at(np);
  for (draco::PointIndex::ValueType j = 0; j < np; ++j) {
    position->ConvertValue<float, 3>(position->mapped_index(draco::PointIndex(j)), decoded[j].data());
    if (!point_at.insert(key_of(decoded[j].data()), j)) return std::nullopt;  // a repeated position
  }
  const std::vector<char>& referenced = predictions.referenced();
  const std::vector<std::array<float, 3>>& predicted = predictions.positions(bits);
  if (predicted.size() != soup.vertices.size()) return std::nullopt;
  constexpr std::uint32_t kNone = std::numeric_limits<std::uint32_t>::max();
  std::vector<std::uint32_t> sigma(np, kNone);  // decoded point -> input vertex
  std::size_t matched = 0;
  for (std::uint32_t i = 0; i < soup.vertices.size(); ++i) {
    if (!referenced[i]) continue;
    const std::uint32_t j = point_at.find(key_of(predicted[i].data()));
    if (j == PositionTable::kNone || sigma[j] != kNone) return std::nullopt;
    sigma[j] = i;
    ++matched;
  }
  if (matched != np) return std::nullopt;
  // The soup's faces by their smallest vertex, in canonical rotation.
  std::vector<std::uint32_t> first(soup.vertices.size() + 1, 0);
  std::vector<std::array<std::uint32_t, 3>> canon(soup.triangles.size());
  for (std::size_t f = 0; f < soup.triangles.size(); ++f) {
    canon[f] = canonical(soup.triangles[f]);
    ++first[canon[f][0] + 1];
  }
  for (std::size_t v = 0; v < soup.vertices.size(); ++v) first[v + 1] += first[v];
  std::vector<std::uint32_t> bucket(soup.triangles.size());
  {
    std::vector<std::uint32_t> fill(first.begin(), first.end() - 1);
    for (std::uint32_t f = 0; f < soup.triangles.size(); ++f) bucket[fill[canon[f][0]]++] = f;
  }
  std::vector<char> used(soup.triangles.size(), 0);
  for (draco::FaceIndex::ValueType f = 0; f < mesh->num_faces(); ++f) {
    const draco::Mesh::Face& face = mesh->face(draco::FaceIndex(f));
    const std::array<std::uint32_t, 3> t =
        canonical({sigma[face[0].value()], sigma[face[1].value()], sigma[face[2].value()]});
    bool found = false;
    for (std::uint32_t b = first[t[0]]; b < first[t[0] + 1] && !found; ++b) {
      if (canon[bucket[b]] == t && !used[bucket[b]]) {
        used[bucket[b]] = 1;
        found = true;
      }
    }
    if (!found) return std::nullopt;
  }
  TriangleSoup out;
  out.vertices = soup.vertices;  // unreferenced vertices (Draco drops them) keep their place
  for (std::size_t j = 0; j < np; ++j)
    out.vertices[sigma[j]] = Vec3(decoded[j][0], decoded[j][1], decoded[j][2]);
  out.triangles = soup.triangles;
  return out;
}

}  // namespace

std::string encode_draco(const TriangleSoup& soup, const DracoOptions& options) {
  require_indices_in_range(soup);
  const BoundingBox box = box_of(soup);
  return encode_draco_bits(soup, draco_quantization(box.lo, box.hi, options.tolerance).bits, options);
}

std::string encode_draco_bits(const TriangleSoup& soup, int bits, const DracoOptions& options) {
  require_in_range("draco bits", bits, 1, 30);
  require_indices_in_range(soup);
  return encode(*draco_mesh(soup, false), bits, options);
}

namespace {

/// The least any quantization can move a vertex: decoded coordinates are
/// float32, so each referenced vertex moves at least to its nearest float32
/// point (the cast rounds to nearest).
double float32_floor(const TriangleSoup& soup) {
  std::vector<char> referenced(soup.vertices.size(), 0);
  for (const auto& t : soup.triangles) referenced[t[0]] = referenced[t[1]] = referenced[t[2]] = 1;
  double floor = 0.0;
  for (std::size_t i = 0; i < soup.vertices.size(); ++i) {
    if (!referenced[i]) continue;
    const Vec3& p = soup.vertices[i];
    floor = std::max(floor, (rounded_to_float32(p) - p).norm());
  }
  return floor;
}

/// The most quantization bits worth trying: the fewest (from `first`) whose
/// step is at most half a float32 unit in the last place of the largest
/// coordinate. More bits cannot bring the decoded float32 positions nearer
/// (every extent is at most twice the largest coordinate, so this is never
/// more than 26), and Draco's encoder needs memory in proportion to the
/// number of quantization levels (about 3 bytes each: 3.3 GB at 30 bits).
int useful_bits(const BoundingBox& box, int first) {
  const double largest = std::max(box.lo.cwiseAbs().maxCoeff(), box.hi.cwiseAbs().maxCoeff());
  const double extent = box.size().maxCoeff();
  if (!(largest > 0.0) || !(extent > 0.0)) return first;
  const double half_ulp = std::ldexp(1.0, std::ilogb(largest) - 24);
  int bits = first;
  while (bits < 30 && extent / (std::ldexp(1.0, bits) - 1.0) > half_ulp) ++bits;
  return bits;
}

/// The most quantization bits whose encoding takes memory in proportion to
/// the mesh: Draco's encoder allocates about 3 bytes per quantization level
/// (55 MB at 24 bits, 3.3 GB at 30), so at most 2^24 levels, or 64 per vertex
/// for larger meshes.
int affordable_bits(const TriangleSoup& soup) {
  int bits = 24;
  while (bits < 30 && std::ldexp(1.0, bits + 1) <= 64.0 * static_cast<double>(soup.vertices.size())) ++bits;
  return bits;
}

}  // namespace

DracoFit fit_draco(const TriangleSoup& soup, double tolerance, const DracoAccept& accept,
                   const std::string& format, const DracoOptions& options) {
  require_positive("draco tolerance", tolerance);
  require_indices_in_range(soup);
  const BoundingBox box = box_of(soup);
  const double extent = box.size().maxCoeff();
  const double largest = std::max(box.lo.cwiseAbs().maxCoeff(), box.hi.cwiseAbs().maxCoeff());
  auto cannot_keep = [&](double best) {
    return OutputError(
        format,
        fmt::format("{}: Draco cannot keep every vertex within the {:.3g} left for this output: at any "
                    "quantization vertices move by up to {:.3g} (float32 positions at coordinates up to "
                    "{:.6g}); raise the tolerance so that at least {:.3g} is left for the outputs, move the "
                    "design nearer the origin, or drop {}",
                    format, tolerance, best, largest, best, format));
  };
  // No quantization moves a vertex less than float32 rounding does: then no try can fit.
  const double floor = float32_floor(soup);
  if (floor > tolerance) throw cannot_keep(floor);
  // The fewest bits whose half step alone fits; float32 rounding is measured, not assumed.
  int first = 1;
  while (first < 30 && std::sqrt(3.0) * 0.5 * extent / (std::ldexp(1.0, first) - 1.0) > tolerance) ++first;
  const int affordable = affordable_bits(soup);
  if (first > affordable) {
    throw OutputError(format,
                      fmt::format("{}: keeping every vertex within the {:.3g} left for this output needs {} "
                                  "bits of Draco quantization, more than the {} whose encoding takes memory "
                                  "in proportion to this mesh; raise the tolerance, or drop {}",
                                  format, tolerance, first, affordable, format));
  }
  const int last = std::min(affordable, std::max(first, useful_bits(box, first)));
  const std::unique_ptr<draco::Mesh> plain = draco_mesh(soup, false);
  std::unique_ptr<draco::Mesh> tagged;  // only when the position match fails
  Predictions predictions(soup);
  double best = std::numeric_limits<double>::infinity();
  bool folded = false;
  // One try: encode as written, decode, match to the input; the fit when it
  // keeps every vertex within the tolerance and `accept` takes it.
  auto attempt = [&](int bits) -> std::optional<DracoFit> {
    // Two vertices at one position: not acceptable, and no need to encode to see it. (Should
    // the prediction be wrong, a quantization that might fit is passed over, nothing worse.)
    if (accept.distinct_positions && predictions.collide(bits)) {
      folded = true;
      return std::nullopt;
    }
    std::string bytes = encode(*plain, bits, options);
    std::optional<TriangleSoup> decoded = decode_matched(bytes, soup, bits, predictions);
    if (!decoded) {
      // The slow exact way: ids give the correspondence, then the id-free
      // file is checked to decode to the same faces and positions.
      if (!tagged) tagged = draco_mesh(soup, true);
      decoded = decode_tagged(encode(*tagged, bits, options), soup);
      if (!decoded) throw std::logic_error(format + ": Draco changed the faces of the mesh");
      require_draco_matches(bytes, DracoFit{bits, 0.0, *decoded, {}});
    }
    const double moved = max_displacement(soup, *decoded);
    best = std::min(best, moved);
    if (moved > tolerance) return std::nullopt;
    if (!accept.accept(*decoded)) {
      folded = true;
      return std::nullopt;
    }
    return DracoFit{bits, moved, std::move(*decoded), std::move(bytes)};
  };
  // The fewest bits that keep vertices apart (when that matters: found by
  // bisection of the quantizer's prediction, no encoding), and the next: the
  // usual answers. Then the fewest whose moves the margin proves harmless
  // (or else the most worth trying), and bisection between the last failure
  // and that success: at most about seven tries, never a scan of every bit
  // count.
  int start = first;
  if (accept.distinct_positions && first < last && predictions.collide(first)) {
    int collide = first;  // bits known to collide; `last` is tried anyway
    int apart = last;
    while (apart - collide > 1) {
      const int middle = collide + (apart - collide) / 2;
      (predictions.collide(middle) ? collide : apart) = middle;
    }
    start = apart;
    folded = true;  // the fewer bits collapse vertices
  }
  for (int bits = start; bits <= std::min(start + 1, last); ++bits) {
    if (std::optional<DracoFit> fit = attempt(bits)) return std::move(*fit);
  }
  int target = last;
  for (int bits = start + 2; bits < last; ++bits) {
    if (draco_max_error(box.lo, box.hi, bits) < accept.margin) {
      target = bits;
      break;
    }
  }
  std::optional<DracoFit> found = start + 1 < last ? attempt(target) : std::nullopt;
  if (!found && target < last) found = attempt(last);
  if (found) {
    int failed = start + 1;
    while (found->bits - failed > 1) {
      const int middle = failed + (found->bits - failed) / 2;
      if (std::optional<DracoFit> fit = attempt(middle)) {
        found = std::move(fit);
      } else {
        failed = middle;
      }
    }
    return std::move(*found);
  }
  if (folded) {
    throw OutputError(format,
                      fmt::format("{}: at every Draco quantization that keeps the vertices within the "
                                  "{:.3g} left for this output, the decoded mesh is no longer valid "
                                  "(faces collapse or fold); raise the tolerance, or drop {}",
                                  format, tolerance, format));
  }
  throw cannot_keep(best);
}

void require_draco_matches(std::string_view bytes, const DracoFit& fit) {
  const std::unique_ptr<draco::Mesh> mesh = decode(bytes);
  const draco::PointAttribute* position = mesh->GetNamedAttribute(draco::GeometryAttribute::POSITION);
  if (position == nullptr || mesh->num_faces() != fit.decoded.triangles.size()) {
    throw std::logic_error("the Draco file differs from the validated mesh");
  }
  auto key = [](const Vec3& p) { return std::array<double, 3>{p.x(), p.y(), p.z()}; };
  std::vector<std::array<double, 3>> written, validated;
  for (draco::FaceIndex::ValueType f = 0; f < mesh->num_faces(); ++f) {
    for (const draco::PointIndex& p : mesh->face(draco::FaceIndex(f))) {
      float xyz[3];
      position->ConvertValue<float, 3>(position->mapped_index(p), xyz);
      written.push_back({xyz[0], xyz[1], xyz[2]});
    }
  }
  for (const auto& t : fit.decoded.triangles) {
    for (const std::uint32_t v : t) validated.push_back(key(fit.decoded.vertices[v]));
  }
  std::sort(written.begin(), written.end());
  std::sort(validated.begin(), validated.end());
  if (written != validated)
    throw std::logic_error("the Draco file's positions differ from the validated mesh");
}

void write_draco(const TriangleSoup& soup, const std::string& path, const DracoOptions& options) {
  write_file_atomically(path, encode_draco(soup, options));
}

void write_draco(const Mesh& mesh, const std::string& path, const DracoOptions& options) {
  write_draco(to_soup(mesh), path, options);
}

}  // namespace fabmesh
