#include "io/mesh/gltf.h"

#include <draco/compression/decode.h>
#include <draco/compression/encode.h>
#include <draco/mesh/mesh.h>
#include <fmt/format.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <nlohmann/json.hpp>
#include <vector>

#include "geometry/core/error_checks.h"

namespace fabmesh {
namespace {

using Json = nlohmann::ordered_json;  // members in the order written: readable, deterministic

constexpr int kUnsignedShort = 5123;
constexpr int kUnsignedInt = 5125;
constexpr int kFloat = 5126;
constexpr int kArrayBuffer = 34962;
constexpr int kElementArrayBuffer = 34963;
constexpr int kTriangles = 4;
constexpr const char* kDraco = "KHR_draco_mesh_compression";

void put_u32(std::string& out, std::uint32_t v) {
  for (int i = 0; i < 4; ++i) out.push_back(static_cast<char>((v >> (8 * i)) & 0xffu));
}

void pad(std::string& s, char c) {
  while (s.size() % 4 != 0) s.push_back(c);
}

/// The GLB container: header, JSON chunk (padded with spaces), BIN chunk
/// (padded with zeros; omitted when empty).
std::string glb_container(std::string json, std::string bin) {
  pad(json, ' ');
  pad(bin, '\0');
  const std::size_t total = 12 + 8 + json.size() + (bin.empty() ? 0 : 8 + bin.size());
  if (total > std::numeric_limits<std::uint32_t>::max()) throw InputError("GLB: the model exceeds 4 GiB");
  std::string out;
  out.reserve(total);
  out += "glTF";
  put_u32(out, 2);
  put_u32(out, static_cast<std::uint32_t>(total));
  put_u32(out, static_cast<std::uint32_t>(json.size()));
  put_u32(out, 0x4E4F534Au);  // "JSON"
  out += json;
  if (!bin.empty()) {
    put_u32(out, static_cast<std::uint32_t>(bin.size()));
    put_u32(out, 0x004E4942u);  // "BIN\0"
    out += bin;
  }
  return out;
}

/// Positions in glTF's frame as float32, checked finite.
std::vector<float> gltf_positions(const TriangleSoup& soup, double scale) {
  const TriangleSoup g = to_gltf_frame(soup, scale);
  std::vector<float> xyz(3 * g.vertices.size());
  for (std::size_t i = 0; i < g.vertices.size(); ++i) {
    for (int k = 0; k < 3; ++k) {
      const double v = g.vertices[i][k];
      if (!std::isfinite(v) || std::abs(v) > std::numeric_limits<float>::max()) {
        throw InputError(fmt::format("GLB: vertex {} has coordinate {} m, not a finite float32", i, v));
      }
      xyz[3 * i + k] = static_cast<float>(v);
    }
  }
  return xyz;
}

/// Exact min/max of float32 xyz triples (as JSON numbers they round-trip).
void add_bounds(Json& accessor, const std::vector<float>& xyz) {
  std::array<float, 3> lo{};
  std::array<float, 3> hi{};
  for (int k = 0; k < 3; ++k) lo[k] = hi[k] = xyz[k];
  for (std::size_t i = 0; i < xyz.size(); i += 3) {
    for (int k = 0; k < 3; ++k) {
      lo[k] = std::min(lo[k], xyz[i + k]);
      hi[k] = std::max(hi[k], xyz[i + k]);
    }
  }
  accessor["min"] = Json::array({double{lo[0]}, double{lo[1]}, double{lo[2]}});
  accessor["max"] = Json::array({double{hi[0]}, double{hi[1]}, double{hi[2]}});
}

/// uint16 indices reach 65534 (65535 is the primitive restart value).
int index_type(std::size_t vertex_count) { return vertex_count <= 65535 ? kUnsignedShort : kUnsignedInt; }

/// The document around one primitive: asset, scene, node, mesh.
Json document(const GlbOptions& options, Json primitive) {
  Json doc;
  doc["asset"] = {{"generator", "fabmesh"}, {"version", "2.0"}};
  doc["scene"] = 0;
  doc["scenes"] = Json::array({{{"name", options.name}, {"nodes", {0}}}});
  doc["nodes"] = Json::array({{{"name", options.name}, {"mesh", 0}}});
  doc["meshes"] =
      Json::array({{{"name", options.name}, {"primitives", Json::array({std::move(primitive)})}}});
  return doc;
}

void put_indices(std::string& bin, const std::array<std::uint32_t, 3>& t, int itype) {
  for (const std::uint32_t i : t) {
    if (itype == kUnsignedShort) {
      bin.push_back(static_cast<char>(i & 0xffu));
      bin.push_back(static_cast<char>(i >> 8));
    } else {
      put_u32(bin, i);
    }
  }
}

/// One primitive per material with faces, each its own index accessor and
/// view (in material order), all on POSITION accessor `positions`; the
/// indices appended to `bin`.
void add_material_primitives(const TriangleSoup& soup, const GlbOptions& options, std::size_t positions,
                             std::string& bin, Json& doc) {
  const int itype = index_type(soup.vertices.size());
  for (std::size_t m = 0; m < options.materials.size(); ++m) {
    const std::size_t start = bin.size();
    std::size_t faces = 0;
    for (std::size_t f = 0; f < soup.triangles.size(); ++f) {
      if (options.face_materials[f] != m) continue;
      put_indices(bin, soup.triangles[f], itype);
      ++faces;
    }
    const GlbMaterial& material = options.materials[m];
    doc["materials"].push_back(
        {{"name", material.name},
         {"pbrMetallicRoughness",
          {{"baseColorFactor", material.rgba}, {"metallicFactor", 0.0}, {"roughnessFactor", 1.0}}},
         {"doubleSided", true}});
    if (faces == 0) continue;
    doc["bufferViews"].push_back({{"buffer", 0},
                                  {"byteOffset", start},
                                  {"byteLength", bin.size() - start},
                                  {"target", kElementArrayBuffer}});
    doc["accessors"].push_back({{"bufferView", doc["bufferViews"].size() - 1},
                                {"componentType", itype},
                                {"count", 3 * faces},
                                {"type", "SCALAR"}});
    doc["meshes"][0]["primitives"].push_back({{"attributes", {{"POSITION", positions}}},
                                              {"indices", doc["accessors"].size() - 1},
                                              {"material", m},
                                              {"mode", kTriangles}});
    pad(bin, '\0');
  }
}

void check_materials(const TriangleSoup& soup, const GlbOptions& options) {
  if (options.materials.empty()) return;
  if (options.draco) throw RangeError("GLB materials", 1.0, "GLB: face materials cannot be Draco-compressed");
  if (options.face_materials.size() != soup.triangles.size()) {
    throw RangeError("GLB face_materials", static_cast<double>(options.face_materials.size()),
                     fmt::format("GLB: {} face materials for {} faces", options.face_materials.size(),
                                 soup.triangles.size()));
  }
  for (const std::uint32_t m : options.face_materials) {
    if (m >= options.materials.size())
      throw RangeError("GLB face_materials", m, fmt::format("GLB: face material {} names no material", m));
  }
}

/// The GLB of `soup` drawn by material (options.materials not empty).
std::string encode_by_material(const TriangleSoup& soup, const GlbOptions& options) {
  const std::vector<float> xyz = gltf_positions(soup, options.scale_to_metres);
  std::string bin;
  for (const float f : xyz) {
    std::uint32_t bits;
    std::memcpy(&bits, &f, 4);
    put_u32(bin, bits);
  }
  Json positions = {
      {"bufferView", 0}, {"componentType", kFloat}, {"count", soup.vertices.size()}, {"type", "VEC3"}};
  add_bounds(positions, xyz);
  Json doc = document(options, Json());
  doc["meshes"][0]["primitives"] = Json::array();
  doc["materials"] = Json::array();
  doc["accessors"] = Json::array({std::move(positions)});
  doc["bufferViews"] = Json::array({{{"buffer", 0}, {"byteLength", bin.size()}, {"target", kArrayBuffer}}});
  add_material_primitives(soup, options, 0, bin, doc);
  doc["buffers"] = Json::array({{{"byteLength", bin.size()}}});
  return glb_container(doc.dump(), std::move(bin));
}

std::string encode_plain(const TriangleSoup& soup, const GlbOptions& options) {
  if (!options.materials.empty()) return encode_by_material(soup, options);
  const std::vector<float> xyz = gltf_positions(soup, options.scale_to_metres);
  const int itype = index_type(soup.vertices.size());
  std::string bin;
  for (const auto& t : soup.triangles) put_indices(bin, t, itype);
  const std::size_t index_bytes = bin.size();
  pad(bin, '\0');
  const std::size_t position_offset = bin.size();
  for (const float f : xyz) {
    std::uint32_t bits;
    std::memcpy(&bits, &f, 4);
    put_u32(bin, bits);
  }
  Json primitive = {{"attributes", {{"POSITION", 1}}}, {"indices", 0}, {"mode", kTriangles}};
  Json doc = document(options, std::move(primitive));
  Json positions = {
      {"bufferView", 1}, {"componentType", kFloat}, {"count", soup.vertices.size()}, {"type", "VEC3"}};
  add_bounds(positions, xyz);
  doc["accessors"] = Json::array({{{"bufferView", 0},
                                   {"componentType", itype},
                                   {"count", 3 * soup.triangles.size()},
                                   {"type", "SCALAR"}},
                                  std::move(positions)});
  doc["bufferViews"] =
      Json::array({{{"buffer", 0}, {"byteLength", index_bytes}, {"target", kElementArrayBuffer}},
                   {{"buffer", 0},
                    {"byteOffset", position_offset},
                    {"byteLength", 4 * xyz.size()},
                    {"target", kArrayBuffer}}});
  doc["buffers"] = Json::array({{{"byteLength", bin.size()}}});
  return glb_container(doc.dump(), std::move(bin));
}

/// Draco-encodes the positions (glTF frame) and faces.
draco::EncoderBuffer draco_encode(const std::vector<float>& xyz, const TriangleSoup& soup,
                                  const GlbOptions& o) {
  draco::Mesh mesh;
  const auto np = static_cast<draco::PointIndex::ValueType>(soup.vertices.size());
  mesh.set_num_points(np);
  draco::GeometryAttribute attribute;
  attribute.Init(draco::GeometryAttribute::POSITION, nullptr, 3, draco::DT_FLOAT32, false, sizeof(float) * 3,
                 0);
  const int id = mesh.AddAttribute(attribute, true, np);
  draco::PointAttribute* position = mesh.attribute(id);
  for (draco::PointIndex::ValueType i = 0; i < np; ++i) {
    position->SetAttributeValue(draco::AttributeValueIndex(i), &xyz[3 * std::size_t{i}]);
  }
  for (const auto& t : soup.triangles) {
    mesh.AddFace({draco::PointIndex(t[0]), draco::PointIndex(t[1]), draco::PointIndex(t[2])});
  }
  draco::Encoder encoder;
  encoder.SetAttributeQuantization(draco::GeometryAttribute::POSITION, o.draco_position_bits);
  encoder.SetSpeedOptions(o.draco_encoding_speed, o.draco_decoding_speed);
  draco::EncoderBuffer buffer;
  const draco::Status status = encoder.EncodeMeshToBuffer(mesh, &buffer);
  if (!status.ok())
    throw InputError(fmt::format("GLB: the Draco encoder refused the mesh: {}", status.error_msg_string()));
  return buffer;
}

std::string encode_draco_glb(const TriangleSoup& soup, const GlbOptions& options) {
  const std::vector<float> xyz = gltf_positions(soup, options.scale_to_metres);
  draco::EncoderBuffer encoded = draco_encode(xyz, soup, options);
  // The accessors describe what a decoder gets: decode to learn the point
  // count (Draco may drop unreferenced points) and the exact min/max.
  draco::DecoderBuffer in;
  in.Init(encoded.data(), encoded.size());
  draco::Decoder decoder;
  auto decoded = decoder.DecodeMeshFromBuffer(&in);
  if (!decoded.ok() || !decoded.value()) throw std::runtime_error("GLB: Draco cannot decode its own output");
  const std::unique_ptr<draco::Mesh> mesh = std::move(decoded).value();
  const draco::PointAttribute* position = mesh->GetNamedAttribute(draco::GeometryAttribute::POSITION);
  if (position == nullptr) throw std::runtime_error("GLB: the decoded Draco mesh has no positions");
  std::vector<float> decoded_xyz(3 * std::size_t{mesh->num_points()});
  for (draco::PointIndex::ValueType i = 0; i < mesh->num_points(); ++i) {
    position->ConvertValue<float, 3>(position->mapped_index(draco::PointIndex(i)),
                                     &decoded_xyz[3 * std::size_t{i}]);
  }

  Json draco_ext = {{"bufferView", 0}, {"attributes", {{"POSITION", position->unique_id()}}}};
  Json primitive = {{"attributes", {{"POSITION", 1}}},
                    {"indices", 0},
                    {"mode", kTriangles},
                    {"extensions", {{kDraco, std::move(draco_ext)}}}};
  Json doc = document(options, std::move(primitive));
  doc["extensionsUsed"] = Json::array({kDraco});
  doc["extensionsRequired"] = Json::array({kDraco});
  Json positions = {{"componentType", kFloat}, {"count", mesh->num_points()}, {"type", "VEC3"}};
  add_bounds(positions, decoded_xyz);
  doc["accessors"] = Json::array({{{"componentType", index_type(mesh->num_points())},
                                   {"count", 3 * std::size_t{mesh->num_faces()}},
                                   {"type", "SCALAR"}},
                                  std::move(positions)});
  doc["bufferViews"] = Json::array({{{"buffer", 0}, {"byteLength", encoded.size()}}});
  std::string bin(encoded.data(), encoded.size());
  pad(bin, '\0');
  doc["buffers"] = Json::array({{{"byteLength", bin.size()}}});
  return glb_container(doc.dump(), std::move(bin));
}

}  // namespace

TriangleSoup to_gltf_frame(const TriangleSoup& soup, double scale_to_metres) {
  TriangleSoup out;
  out.triangles = soup.triangles;
  out.vertices.reserve(soup.vertices.size());
  for (const Vec3& p : soup.vertices) out.vertices.emplace_back(p.x(), p.z(), -p.y());
  for (Vec3& p : out.vertices) p *= scale_to_metres;
  return out;
}

TriangleSoup from_gltf_frame(const TriangleSoup& soup, double units_per_metre) {
  TriangleSoup out;
  out.triangles = soup.triangles;
  out.vertices.reserve(soup.vertices.size());
  for (const Vec3& p : soup.vertices) out.vertices.emplace_back(units_per_metre * Vec3(p.x(), -p.z(), p.y()));
  return out;
}

std::string encode_glb(const TriangleSoup& soup, const GlbOptions& options) {
  require_positive("GLB scale_to_metres", options.scale_to_metres);
  if (options.draco) {
    require_in_range("GLB draco_position_bits", options.draco_position_bits, 1, 30);
    require_in_range("GLB draco_encoding_speed", options.draco_encoding_speed, 0, 10);
    require_in_range("GLB draco_decoding_speed", options.draco_decoding_speed, 0, 10);
  }
  if (soup.triangles.empty()) throw InputError("GLB: the mesh has no triangle");
  if (soup.vertices.size() >= std::numeric_limits<std::uint32_t>::max())
    throw InputError("GLB: too many vertices");
  require_indices_in_range(soup);
  check_materials(soup, options);
  return options.draco ? encode_draco_glb(soup, options) : encode_plain(soup, options);
}

}  // namespace fabmesh
