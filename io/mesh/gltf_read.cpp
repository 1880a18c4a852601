// parse_gltf: GLB and self-contained .gltf in, over nlohmann::json and libdraco.
//
// Not tinygltf 2.7 (Debian libtinygltf-dev): on hostile input its GLB loader
// reads up to 8 bytes past the BIN chunk (the length check leaves out the
// chunk header), it refuses every Draco primitive unless built with Draco
// (the indices accessor has no bufferView), and its Draco path indexes
// bufferViews, buffers, accessors and attributes with unchecked values from
// the file. Here every index, offset, stride and count is checked against
// what the bytes hold before it is used, and there is no file or network
// code at all.

#include <draco/compression/decode.h>
#include <fmt/format.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <nlohmann/json.hpp>
#include <optional>
#include <vector>

#include "geometry/core/errors.h"
#include "io/mesh/draco.h"
#include "io/mesh/gltf.h"

namespace fabmesh {
namespace {

using Json = nlohmann::json;

constexpr std::uint32_t kJsonChunk = 0x4E4F534Au;
constexpr std::uint32_t kBinChunk = 0x004E4942u;
constexpr const char* kDraco = "KHR_draco_mesh_compression";

enum ComponentType : int {
  kByte = 5120,
  kUnsignedByte = 5121,
  kShort = 5122,
  kUnsignedShort = 5123,
  kUnsignedInt = 5125,
  kFloat = 5126,
};

std::uint32_t u32_at(std::string_view b, std::size_t at) {
  std::uint32_t v = 0;
  for (int i = 0; i < 4; ++i) v |= std::uint32_t{static_cast<unsigned char>(b[at + i])} << (8 * i);
  return v;
}

std::size_t component_size(int type) {
  switch (type) {
    case kByte:
    case kUnsignedByte:
      return 1;
    case kShort:
    case kUnsignedShort:
      return 2;
    case kUnsignedInt:
    case kFloat:
      return 4;
    default:
      return 0;
  }
}

/// One component at `p` (little-endian), normalized as glTF specifies.
double component_at(const unsigned char* p, int type, bool normalized) {
  std::uint32_t u = 0;
  for (std::size_t i = 0; i < component_size(type); ++i) u |= std::uint32_t{p[i]} << (8 * i);
  switch (type) {
    case kByte: {
      const auto v = static_cast<std::int8_t>(u);
      return normalized ? std::max(v / 127.0, -1.0) : v;
    }
    case kUnsignedByte:
      return normalized ? u / 255.0 : u;
    case kShort: {
      const auto v = static_cast<std::int16_t>(u);
      return normalized ? std::max(v / 32767.0, -1.0) : v;
    }
    case kUnsignedShort:
      return normalized ? u / 65535.0 : u;
    case kUnsignedInt:
      return u;
    default: {
      float f;
      std::memcpy(&f, &u, 4);
      return f;
    }
  }
}

/// Decodes standard base64 (padding optional). False on any other character.
bool decode_base64(std::string_view in, std::string& out) {
  out.clear();
  out.reserve(in.size() / 4 * 3 + 3);
  std::uint32_t acc = 0;
  int bits = 0;
  std::size_t i = 0;
  for (; i < in.size() && in[i] != '='; ++i) {
    const char c = in[i];
    int v;
    if (c >= 'A' && c <= 'Z')
      v = c - 'A';
    else if (c >= 'a' && c <= 'z')
      v = c - 'a' + 26;
    else if (c >= '0' && c <= '9')
      v = c - '0' + 52;
    else if (c == '+')
      v = 62;
    else if (c == '/')
      v = 63;
    else
      return false;
    acc = (acc << 6) | static_cast<std::uint32_t>(v);
    bits += 6;
    if (bits >= 8) {
      bits -= 8;
      out.push_back(static_cast<char>((acc >> bits) & 0xffu));
    }
  }
  for (; i < in.size(); ++i) {
    if (in[i] != '=') return false;
  }
  return true;
}

/// Extensions a reader of geometry may ignore when a file requires them.
bool harmless_extension(const std::string& e) {
  for (const char* prefix : {"KHR_materials_", "KHR_texture_", "EXT_texture_", "KHR_lights_"}) {
    if (e.rfind(prefix, 0) == 0) return true;
  }
  return e == kDraco || e == "KHR_mesh_quantization";
}

/// An accessor's elements as doubles: count x components, row-major.
struct AccessorValues {
  std::vector<double> values;
  std::size_t count = 0;
};

class GltfReader {
 public:
  GltfReader(const std::string& name, const GltfReadOptions& options) : name_(name), options_(options) {}

  GltfContent read(std::string_view bytes) {
    std::string_view json_text = bytes;
    if (bytes.substr(0, 4) == "glTF") json_text = split_glb(bytes);
    try {
      doc_ = Json::parse(json_text.begin(), json_text.end());
    } catch (const Json::exception& e) {
      fail(fmt::format("not glTF JSON: {}", e.what()));
    }
    if (!doc_.is_object() || !doc_.contains("asset") || !doc_["asset"].is_object()) {
      fail("not a glTF document (no 'asset' object)");
    }
    const Json& version = doc_["asset"].value("version", Json());
    if (!version.is_string() || version.get<std::string>().substr(0, 2) != "2.") {
      fail(fmt::format("asset.version is {}, fabmesh reads glTF 2.x", version.dump()));
    }
    for (const Json& e : array(doc_, "extensionsRequired", "")) {
      if (!e.is_string()) fail("extensionsRequired holds a non-string");
      if (!harmless_extension(e.get<std::string>())) {
        fail(
            fmt::format("the file requires the extension {}, which changes how geometry is stored and "
                        "which fabmesh does not read",
                        e.get<std::string>()));
      }
    }
    load_buffers();
    GltfContent content;
    walk_scene(content);
    return content;
  }

 private:
  [[noreturn]] void fail(const std::string& message) const {
    throw FileError(name_, 0, 0, fmt::format("{}: {}", name_, message));
  }

  // ------------------------------------------------------------ container

  /// Checks the GLB header and chunks; returns the JSON chunk, keeps the BIN chunk.
  std::string_view split_glb(std::string_view b) {
    if (b.size() < 20) fail("truncated GLB header");
    if (u32_at(b, 4) != 2) fail(fmt::format("GLB version {}, fabmesh reads version 2", u32_at(b, 4)));
    if (u32_at(b, 8) != b.size()) {
      fail(fmt::format("the GLB header states {} bytes but the file has {} (truncated?)", u32_at(b, 8),
                       b.size()));
    }
    const std::uint64_t json_length = u32_at(b, 12);
    if (u32_at(b, 16) != kJsonChunk) fail("the first GLB chunk is not JSON");
    if (20 + json_length > b.size()) fail("the GLB JSON chunk runs past the end of the file");
    std::uint64_t at = 20 + json_length;
    while (at < b.size()) {  // further chunks: the first BIN one is the buffer, others are ignored
      if (b.size() - at < 8) fail("truncated GLB chunk header");
      const std::uint64_t length = u32_at(b, at);
      if (length > b.size() - at - 8) fail("a GLB chunk runs past the end of the file");
      if (u32_at(b, at + 4) == kBinChunk && !has_bin_) {
        bin_ = b.substr(at + 8, length);
        has_bin_ = true;
      }
      at += 8 + length;
    }
    return b.substr(20, json_length);
  }

  // ------------------------------------------------------------ typed JSON

  const Json& array(const Json& o, const char* key, const std::string& where) const {
    static const Json kEmpty = Json::array();
    const auto it = o.find(key);
    if (it == o.end()) return kEmpty;
    if (!it->is_array()) fail(fmt::format("{}{} is not an array", where, key));
    return *it;
  }

  std::optional<std::uint64_t> optional_uint(const Json& o, const char* key, const std::string& where) const {
    const auto it = o.find(key);
    if (it == o.end()) return std::nullopt;
    if (!it->is_number_unsigned())
      fail(fmt::format("{}.{} = {} is not a non-negative integer", where, key, it->dump()));
    return it->get<std::uint64_t>();
  }

  std::uint64_t required_uint(const Json& o, const char* key, const std::string& where) const {
    const auto v = optional_uint(o, key, where);
    if (!v) fail(fmt::format("{} has no {}", where, key));
    return *v;
  }

  /// doc_[kind][i] as an object; fails naming `kind`[i] when absent.
  const Json& element(const char* kind, std::uint64_t i) const {
    const Json& all = array(doc_, kind, "");
    if (i >= all.size())
      fail(fmt::format("{}[{}] is referred to but there are {} {}", kind, i, all.size(), kind));
    if (!all[i].is_object()) fail(fmt::format("{}[{}] is not an object", kind, i));
    return all[i];
  }

  // ------------------------------------------------------------ buffers

  void load_buffers() {
    const Json& all = array(doc_, "buffers", "");
    decoded_.resize(all.size());
    for (std::size_t i = 0; i < all.size(); ++i) {
      const std::string where = fmt::format("buffers[{}]", i);
      const Json& buffer = element("buffers", i);
      const std::uint64_t length = required_uint(buffer, "byteLength", where);
      const auto uri = buffer.find("uri");
      std::string_view data;
      if (uri == buffer.end()) {
        if (i != 0 || !has_bin_) fail(where + " has no uri and is not the GLB's BIN chunk");
        data = bin_;
      } else {
        if (!uri->is_string()) fail(where + ".uri is not a string");
        const std::string& text = uri->get_ref<const std::string&>();
        const std::size_t comma = text.find(',');
        if (text.rfind("data:", 0) != 0 || comma == std::string::npos) {
          fail(fmt::format(
              "{} is in the external file '{}': fabmesh reads only self-contained glTF (a .glb, or "
              "a .gltf whose buffers are data: URIs) and never opens other files",
              where, text.substr(0, 200)));
        }
        if (text.substr(0, comma).find(";base64") == std::string::npos)
          fail(where + " is a data: URI but not base64");
        if (!decode_base64(std::string_view(text).substr(comma + 1), decoded_[i]))
          fail(where + ": bad base64");
        data = decoded_[i];
      }
      if (length > data.size()) {
        fail(fmt::format("{}.byteLength = {} but it holds {} bytes", where, length, data.size()));
      }
      buffers_.push_back(data.substr(0, length));
    }
  }

  /// The bytes of bufferView `index` and its stride (0: tightly packed).
  std::string_view view(std::uint64_t index, std::size_t& stride) const {
    const std::string where = fmt::format("bufferViews[{}]", index);
    const Json& v = element("bufferViews", index);
    const std::uint64_t buffer = required_uint(v, "buffer", where);
    if (buffer >= buffers_.size()) fail(fmt::format("{}.buffer = {} does not exist", where, buffer));
    const std::uint64_t offset = optional_uint(v, "byteOffset", where).value_or(0);
    const std::uint64_t length = required_uint(v, "byteLength", where);
    const std::string_view data = buffers_[buffer];
    if (offset > data.size() || length > data.size() - offset) {
      fail(fmt::format("{} (offset {}, length {}) does not fit buffer {} of {} bytes", where, offset, length,
                       buffer, data.size()));
    }
    stride = optional_uint(v, "byteStride", where).value_or(0);
    if (stride != 0 && (stride < 4 || stride > 252 || stride % 4 != 0)) {
      fail(fmt::format("{}.byteStride = {} is not a multiple of 4 in [4, 252]", where, stride));
    }
    return data.substr(offset, length);
  }

  // ------------------------------------------------------------ accessors

  /// Fails unless `count` elements of `element_size` bytes, `stride` apart
  /// from `offset`, fit in `bytes`.
  void require_fit(std::string_view bytes, std::uint64_t offset, std::size_t stride, std::size_t count,
                   std::size_t element_size, const std::string& where) const {
    if (offset > bytes.size() || element_size > bytes.size() - offset ||
        (count > 1 && (count - 1) > (bytes.size() - offset - element_size) / stride)) {
      fail(fmt::format(
          "{}: {} elements of {} bytes (stride {}) from offset {} do not fit its {}-byte bufferView", where,
          count, element_size, stride, offset, bytes.size()));
    }
  }

  /// Calls take(i, pointer to element i) for elements that require_fit accepted.
  template <typename Take>
  static void for_each_element(std::string_view bytes, std::uint64_t offset, std::size_t stride,
                               std::size_t count, Take&& take) {
    const auto* base = reinterpret_cast<const unsigned char*>(bytes.data()) + offset;
    for (std::size_t i = 0; i < count; ++i) take(i, base + i * stride);
  }

  /// Accessor `index` as numbers: `components` per element of one of
  /// `types`, normalized only when `allow_normalized`, at most `max_count`
  /// elements (checked before anything is allocated).
  AccessorValues accessor(std::uint64_t index, const char* type, std::size_t components,
                          std::initializer_list<int> types, bool allow_normalized,
                          std::size_t max_count) const {
    const std::string where = fmt::format("accessors[{}]", index);
    const Json& a = element("accessors", index);
    const std::uint64_t count = required_uint(a, "count", where);
    const std::uint64_t component_type = required_uint(a, "componentType", where);
    const auto t = a.find("type");
    if (t == a.end() || !t->is_string() || *t != type) fail(fmt::format("{}.type must be {}", where, type));
    if (std::find(types.begin(), types.end(), static_cast<int>(component_type)) == types.end()) {
      fail(fmt::format("{}.componentType = {} is not allowed here", where, component_type));
    }
    const auto normalized_it = a.find("normalized");
    const bool normalized =
        normalized_it != a.end() && normalized_it->is_boolean() && normalized_it->get<bool>();
    if (normalized && (!allow_normalized || component_type == kFloat))
      fail(where + " must not be normalized");
    if (count == 0) fail(where + ".count is 0");
    if (count > max_count) fail(fmt::format("{}.count = {} exceeds the reader's budget", where, count));
    const int ct = static_cast<int>(component_type);
    const std::size_t element_size = components * component_size(ct);
    std::string_view bytes;
    std::size_t stride = 0;
    const std::uint64_t offset = optional_uint(a, "byteOffset", where).value_or(0);
    const auto view_index = optional_uint(a, "bufferView", where);
    if (view_index) {
      bytes = view(*view_index, stride);
      if (stride != 0 && stride < element_size)
        fail(fmt::format("{}: bufferView stride {} < element size", where, stride));
      if (stride == 0) stride = element_size;
      require_fit(bytes, offset, stride, count, element_size, where);
    }
    AccessorValues out;
    out.count = count;
    out.values.assign(count * components, 0.0);  // no bufferView: zeros (then sparse)
    auto store = [&](std::size_t i, const unsigned char* p) {
      for (std::size_t k = 0; k < components; ++k) {
        out.values[i * components + k] = component_at(p + k * component_size(ct), ct, normalized);
      }
    };
    if (view_index) for_each_element(bytes, offset, stride, count, store);
    if (a.contains("sparse")) apply_sparse(a["sparse"], where + ".sparse", out, element_size, store);
    return out;
  }

  template <typename Store>
  void apply_sparse(const Json& s, const std::string& where, const AccessorValues& out,
                    std::size_t element_size, Store& store) const {
    if (!s.is_object() || !s.contains("indices") || !s.contains("values")) fail(where + " is malformed");
    const std::uint64_t count = required_uint(s, "count", where);
    if (count == 0 || count > out.count)
      fail(fmt::format("{}.count = {} is not in [1, {}]", where, count, out.count));
    const Json& indices = s["indices"];
    const Json& values = s["values"];
    if (!indices.is_object() || !values.is_object()) fail(where + " is malformed");
    const int it = static_cast<int>(required_uint(indices, "componentType", where + ".indices"));
    if (it != kUnsignedByte && it != kUnsignedShort && it != kUnsignedInt)
      fail(where + ".indices: bad componentType");
    std::size_t stride = 0;
    const std::string_view index_bytes =
        view(required_uint(indices, "bufferView", where + ".indices"), stride);
    const std::uint64_t index_offset = optional_uint(indices, "byteOffset", where + ".indices").value_or(0);
    require_fit(index_bytes, index_offset, component_size(it), count, component_size(it), where + ".indices");
    const std::string_view value_bytes = view(required_uint(values, "bufferView", where + ".values"), stride);
    const std::uint64_t value_offset = optional_uint(values, "byteOffset", where + ".values").value_or(0);
    require_fit(value_bytes, value_offset, element_size, count, element_size, where + ".values");
    std::vector<std::size_t> targets(count);
    for_each_element(
        index_bytes, index_offset, component_size(it), count, [&](std::size_t i, const unsigned char* p) {
          const double target = component_at(p, it, false);
          if (target >= static_cast<double>(out.count)) {
            fail(fmt::format("{}.indices[{}] = {} is not below the count {}", where, i, target, out.count));
          }
          targets[i] = static_cast<std::size_t>(target);
        });
    for_each_element(value_bytes, value_offset, element_size, count,
                     [&](std::size_t i, const unsigned char* p) { store(targets[i], p); });
  }

  // ------------------------------------------------------------ primitives

  std::size_t vertex_budget() const { return 3 * options_.max_triangles; }

  void require_budget(const GltfContent& c, std::size_t vertices, std::size_t triangles) const {
    if (c.soup.triangles.size() + triangles > options_.max_triangles ||
        c.soup.vertices.size() + vertices > vertex_budget() ||
        c.soup.vertices.size() + vertices > std::numeric_limits<std::uint32_t>::max()) {
      fail(fmt::format("more than {} triangles or {} vertices (nodes instance meshes; the reader's budget)",
                       options_.max_triangles, vertex_budget()));
    }
  }

  /// Appends `vertices` placed by `world` and the triangles of `indices`
  /// read as `mode` (4 list, 5 strip, 6 fan).
  void append(const std::vector<Vec3>& vertices, const std::vector<std::uint32_t>& indices, int mode,
              const Eigen::Affine3d& world, const std::string& where, GltfContent& c) const {
    std::vector<std::array<std::uint32_t, 3>> triangles;
    const std::size_t n = indices.size();
    if (mode == 4) {
      if (n % 3 != 0) fail(fmt::format("{}: {} indices is not a multiple of 3", where, n));
      for (std::size_t i = 0; i + 2 < n; i += 3)
        triangles.push_back({indices[i], indices[i + 1], indices[i + 2]});
    } else {
      for (std::size_t i = 0; i + 2 < n; ++i) {
        std::array<std::uint32_t, 3> t =
            mode == 5
                ? std::array<std::uint32_t, 3>{indices[i], indices[i + 1 + i % 2], indices[i + 2 - i % 2]}
                : std::array<std::uint32_t, 3>{indices[i + 1], indices[i + 2], indices[0]};
        // Strips and fans stitch with repeated indices: those are no faces.
        if (t[0] != t[1] && t[1] != t[2] && t[0] != t[2]) triangles.push_back(t);
      }
    }
    for (const std::uint32_t i : indices) {
      if (i >= vertices.size()) fail(fmt::format("{}: index {} but {} vertices", where, i, vertices.size()));
    }
    require_budget(c, vertices.size(), triangles.size());
    const bool mirrored = world.linear().determinant() < 0;
    const auto base = static_cast<std::uint32_t>(c.soup.vertices.size());
    for (const Vec3& p : vertices) {
      const Vec3 q = world * p;
      if (!q.allFinite()) fail(fmt::format("{}: a position is not finite after the node transforms", where));
      c.soup.vertices.push_back(q);
    }
    for (auto t : triangles) {
      if (mirrored) std::swap(t[1], t[2]);
      c.soup.triangles.push_back({base + t[0], base + t[1], base + t[2]});
    }
  }

  void append_draco(const Json& ext, const std::string& where, const Eigen::Affine3d& world,
                    GltfContent& c) const {
    if (!ext.is_object()) fail(where + " is not an object");
    std::size_t stride = 0;
    const std::string_view bytes = view(required_uint(ext, "bufferView", where), stride);
    const auto attributes = ext.find("attributes");
    if (attributes == ext.end() || !attributes->is_object()) fail(where + " has no attributes");
    required_uint(*attributes, "POSITION", where + ".attributes");
    TriangleSoup decoded;
    try {
      decoded = parse_draco(bytes, name_);
    } catch (const FileError& e) {
      fail(fmt::format("{}: {}", where, e.what()));
    }
    std::vector<std::uint32_t> indices;
    indices.reserve(3 * decoded.triangles.size());
    for (const auto& t : decoded.triangles) indices.insert(indices.end(), t.begin(), t.end());
    append(decoded.vertices, indices, 4, world, where, c);
  }

  void append_primitive(const Json& p, const std::string& where, const Eigen::Affine3d& world,
                        GltfContent& c) const {
    if (!p.is_object()) fail(where + " is not an object");
    const std::uint64_t mode = optional_uint(p, "mode", where).value_or(4);
    if (mode <= 3) {
      ++c.skipped_primitives;
      return;
    }
    if (mode > 6) fail(fmt::format("{}.mode = {} is not a glTF primitive mode", where, mode));
    ++c.primitives;
    const auto extensions = p.find("extensions");
    if (extensions != p.end() && extensions->is_object() && extensions->contains(kDraco)) {
      if (mode != 4) fail(where + ": a Draco primitive must be a triangle list (mode 4)");
      ++c.draco_primitives;
      append_draco((*extensions)[kDraco], where + ".extensions." + kDraco, world, c);
      return;
    }
    const auto attributes = p.find("attributes");
    if (attributes == p.end() || !attributes->is_object()) fail(where + " has no attributes");
    const std::size_t budget = vertex_budget() - c.soup.vertices.size();
    const AccessorValues pos =
        accessor(required_uint(*attributes, "POSITION", where + ".attributes"), "VEC3", 3,
                 {kFloat, kByte, kUnsignedByte, kShort, kUnsignedShort}, true, budget);
    std::vector<Vec3> vertices(pos.count);
    for (std::size_t i = 0; i < pos.count; ++i) {
      vertices[i] = Vec3(pos.values[3 * i], pos.values[3 * i + 1], pos.values[3 * i + 2]);
    }
    std::vector<std::uint32_t> indices;
    if (const auto index = optional_uint(p, "indices", where)) {
      const AccessorValues idx = accessor(*index, "SCALAR", 1, {kUnsignedByte, kUnsignedShort, kUnsignedInt},
                                          false, 3 * options_.max_triangles + 2);
      indices.assign(idx.values.begin(), idx.values.end());  // integers < 2^32: exact
    } else {
      indices.resize(pos.count);
      for (std::size_t i = 0; i < pos.count; ++i) indices[i] = static_cast<std::uint32_t>(i);
    }
    append(vertices, indices, static_cast<int>(mode), world, where, c);
  }

  // ------------------------------------------------------------ nodes

  std::vector<double> numbers(const Json& node, const char* key, std::size_t n,
                              const std::string& where) const {
    const auto it = node.find(key);
    if (it == node.end()) return {};
    if (!it->is_array() || it->size() != n)
      fail(fmt::format("{}.{} is not an array of {} numbers", where, key, n));
    std::vector<double> v;
    for (const Json& x : *it) {
      if (!x.is_number()) fail(fmt::format("{}.{} holds a non-number", where, key));
      v.push_back(x.get<double>());
    }
    return v;
  }

  Eigen::Affine3d local_transform(const Json& node, const std::string& where) const {
    Eigen::Affine3d a = Eigen::Affine3d::Identity();
    const std::vector<double> m = numbers(node, "matrix", 16, where);
    const std::vector<double> t = numbers(node, "translation", 3, where);
    const std::vector<double> r = numbers(node, "rotation", 4, where);
    const std::vector<double> s = numbers(node, "scale", 3, where);
    if (!m.empty()) {
      if (!t.empty() || !r.empty() || !s.empty())
        fail(where + " has both a matrix and translation/rotation/scale");
      if (m[3] != 0 || m[7] != 0 || m[11] != 0 || m[15] != 1) fail(where + ".matrix is not affine");
      for (int col = 0; col < 4; ++col) {
        for (int row = 0; row < 3; ++row) a.matrix()(row, col) = m[4 * col + row];  // column-major
      }
      return a;
    }
    if (!t.empty()) a.translate(Vec3(t[0], t[1], t[2]));
    if (!r.empty()) {
      Eigen::Quaterniond q(r[3], r[0], r[1], r[2]);  // glTF stores (x, y, z, w)
      if (!(q.norm() > 0) || !std::isfinite(q.norm())) fail(where + ".rotation is not a rotation");
      a.rotate(q.normalized());
    }
    if (!s.empty()) a.scale(Vec3(s[0], s[1], s[2]));
    return a;
  }

  std::vector<std::uint64_t> indices_in(const Json& o, const char* key, const std::string& where) const {
    std::vector<std::uint64_t> out;
    for (const Json& x : array(o, key, where + ".")) {
      if (!x.is_number_unsigned()) fail(fmt::format("{}.{} holds {}, not an index", where, key, x.dump()));
      out.push_back(x.get<std::uint64_t>());
    }
    return out;
  }

  void walk_scene(GltfContent& c) const {
    const std::size_t node_count = array(doc_, "nodes", "").size();
    std::vector<std::uint64_t> roots;
    const Json& scenes = array(doc_, "scenes", "");
    if (!scenes.empty()) {
      const std::uint64_t s = optional_uint(doc_, "scene", "the document").value_or(0);
      roots = indices_in(element("scenes", s), "nodes", fmt::format("scenes[{}]", s));
    } else {
      std::vector<char> is_child(node_count, 0);
      for (std::size_t i = 0; i < node_count; ++i) {
        for (const std::uint64_t k :
             indices_in(element("nodes", i), "children", fmt::format("nodes[{}]", i))) {
          if (k < node_count) is_child[k] = 1;
        }
      }
      for (std::size_t i = 0; i < node_count; ++i) {
        if (!is_child[i]) roots.push_back(i);
      }
    }
    std::vector<char> visited(node_count, 0);
    std::vector<std::pair<std::uint64_t, Eigen::Affine3d>> stack;
    for (auto it = roots.rbegin(); it != roots.rend(); ++it)
      stack.emplace_back(*it, Eigen::Affine3d::Identity());
    while (!stack.empty()) {
      const auto [index, parent] = stack.back();
      stack.pop_back();
      const std::string where = fmt::format("nodes[{}]", index);
      const Json& node = element("nodes", index);
      if (visited[index]) fail(where + " is reached twice: the node hierarchy must be a forest");
      visited[index] = 1;
      const Eigen::Affine3d world = parent * local_transform(node, where);
      if (const auto mesh = optional_uint(node, "mesh", where)) {
        const std::size_t before = c.soup.triangles.size();
        const std::string mesh_where = fmt::format("meshes[{}]", *mesh);
        const Json& primitives = array(element("meshes", *mesh), "primitives", mesh_where + ".");
        for (std::size_t k = 0; k < primitives.size(); ++k) {
          append_primitive(primitives[k], fmt::format("{}.primitives[{}]", mesh_where, k), world, c);
        }
        if (c.soup.triangles.size() > before && !world.matrix().isIdentity(0.0)) {
          ++c.transformed_instances;
          if (world.linear().determinant() < 0) ++c.mirrored_instances;
        }
      }
      const std::vector<std::uint64_t> children = indices_in(node, "children", where);
      for (auto it = children.rbegin(); it != children.rend(); ++it) stack.emplace_back(*it, world);
    }
  }

  const std::string& name_;
  const GltfReadOptions& options_;
  Json doc_;
  std::string_view bin_;
  bool has_bin_ = false;
  std::vector<std::string> decoded_;       ///< payloads of data: URIs
  std::vector<std::string_view> buffers_;  ///< every buffer's bytes (BIN chunk or decoded_)
};

}  // namespace

GltfContent parse_gltf(std::string_view bytes, const std::string& name, const GltfReadOptions& options) {
  return GltfReader(name, options).read(bytes);
}

}  // namespace fabmesh
