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

#include <fmt/format.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <nlohmann/json.hpp>
#include <optional>
#include <vector>

#include "geometry/core/errors.h"
#include "io/mesh/draco.h"
#include "io/mesh/gltf.h"
#include "io/mesh/gltf_document.h"

namespace fabmesh {
namespace {

using Json = nlohmann::json;

constexpr const char* kDraco = "KHR_draco_mesh_compression";

/// Extensions a reader of geometry may ignore when a file requires them.
bool harmless_extension(const std::string& e) {
  for (const char* prefix : {"KHR_materials_", "KHR_texture_", "EXT_texture_", "KHR_lights_"}) {
    if (e.rfind(prefix, 0) == 0) return true;
  }
  return e == kDraco || e == "KHR_mesh_quantization";
}

/// Walks the scene of a glTF document into a soup, within the budget.
class GltfReader {
 public:
  GltfReader(const GltfDocument& doc, const GltfReadOptions& options) : doc_(doc), options_(options) {}

  GltfContent read() const {
    for (const Json& e : doc_.array(doc_.root(), "extensionsRequired", "")) {
      if (!e.is_string()) doc_.fail("extensionsRequired holds a non-string");
      if (!harmless_extension(e.get<std::string>())) {
        doc_.fail(
            fmt::format("the file requires the extension {}, which changes how geometry is stored and "
                        "which fabmesh does not read",
                        e.get<std::string>()));
      }
    }
    GltfContent content;
    walk_scene(content);
    return content;
  }

 private:
  // ------------------------------------------------------------ primitives

  std::size_t vertex_budget() const { return 3 * options_.max_triangles; }

  void require_budget(const GltfContent& c, std::size_t vertices, std::size_t triangles) const {
    if (c.soup.triangles.size() + triangles > options_.max_triangles ||
        c.soup.vertices.size() + vertices > vertex_budget() ||
        c.soup.vertices.size() + vertices > std::numeric_limits<std::uint32_t>::max()) {
      doc_.fail(
          fmt::format("more than {} triangles or {} vertices (nodes instance meshes; the reader's budget)",
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
      if (n % 3 != 0) doc_.fail(fmt::format("{}: {} indices is not a multiple of 3", where, n));
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
      if (i >= vertices.size())
        doc_.fail(fmt::format("{}: index {} but {} vertices", where, i, vertices.size()));
    }
    require_budget(c, vertices.size(), triangles.size());
    const bool mirrored = world.linear().determinant() < 0;
    const auto base = static_cast<std::uint32_t>(c.soup.vertices.size());
    for (const Vec3& p : vertices) {
      const Vec3 q = world * p;
      if (!q.allFinite())
        doc_.fail(fmt::format("{}: a position is not finite after the node transforms", where));
      c.soup.vertices.push_back(q);
    }
    for (auto t : triangles) {
      if (mirrored) std::swap(t[1], t[2]);
      c.soup.triangles.push_back({base + t[0], base + t[1], base + t[2]});
    }
  }

  void append_draco(const Json& ext, const std::string& where, const Eigen::Affine3d& world,
                    GltfContent& c) const {
    if (!ext.is_object()) doc_.fail(where + " is not an object");
    std::size_t stride = 0;
    const std::string_view bytes = doc_.view(doc_.required_uint(ext, "bufferView", where), stride);
    const auto attributes = ext.find("attributes");
    if (attributes == ext.end() || !attributes->is_object()) doc_.fail(where + " has no attributes");
    doc_.required_uint(*attributes, "POSITION", where + ".attributes");
    TriangleSoup decoded;
    try {
      decoded = parse_draco(bytes, doc_.name(), options_.max_triangles);
    } catch (const FileError& e) {
      doc_.fail(fmt::format("{}: {}", where, e.what()));
    }
    std::vector<std::uint32_t> indices;
    indices.reserve(3 * decoded.triangles.size());
    for (const auto& t : decoded.triangles) indices.insert(indices.end(), t.begin(), t.end());
    append(decoded.vertices, indices, 4, world, where, c);
  }

  void append_primitive(const Json& p, const std::string& where, const Eigen::Affine3d& world,
                        GltfContent& c) const {
    if (!p.is_object()) doc_.fail(where + " is not an object");
    const std::uint64_t mode = doc_.optional_uint(p, "mode", where).value_or(4);
    if (mode <= 3) {
      ++c.skipped_primitives;
      return;
    }
    if (mode > 6) doc_.fail(fmt::format("{}.mode = {} is not a glTF primitive mode", where, mode));
    ++c.primitives;
    const auto extensions = p.find("extensions");
    if (extensions != p.end() && extensions->is_object() && extensions->contains(kDraco)) {
      if (mode != 4) doc_.fail(where + ": a Draco primitive must be a triangle list (mode 4)");
      ++c.draco_primitives;
      append_draco((*extensions)[kDraco], where + ".extensions." + kDraco, world, c);
      return;
    }
    const auto attributes = p.find("attributes");
    if (attributes == p.end() || !attributes->is_object()) doc_.fail(where + " has no attributes");
    const std::size_t budget = vertex_budget() - c.soup.vertices.size();
    GltfAccessorRequest positions;  // float, or KHR_mesh_quantization's (normalized) integers
    positions.component_types = {kGltfFloat, kGltfByte, kGltfUnsignedByte, kGltfShort, kGltfUnsignedShort};
    positions.allow_normalized = true;
    positions.max_count = budget;
    const GltfAccessorValues pos =
        doc_.accessor(doc_.required_uint(*attributes, "POSITION", where + ".attributes"), positions);
    std::vector<Vec3> vertices(pos.count);
    for (std::size_t i = 0; i < pos.count; ++i) {
      vertices[i] = Vec3(pos.values[3 * i], pos.values[3 * i + 1], pos.values[3 * i + 2]);
    }
    std::vector<std::uint32_t> indices;
    if (const auto index = doc_.optional_uint(p, "indices", where)) {
      GltfAccessorRequest request;
      request.type = "SCALAR";
      request.components = 1;
      request.component_types = {kGltfUnsignedByte, kGltfUnsignedShort, kGltfUnsignedInt};
      request.max_count = 3 * options_.max_triangles + 2;
      const GltfAccessorValues idx = doc_.accessor(*index, request);
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
      doc_.fail(fmt::format("{}.{} is not an array of {} numbers", where, key, n));
    std::vector<double> v;
    for (const Json& x : *it) {
      if (!x.is_number()) doc_.fail(fmt::format("{}.{} holds a non-number", where, key));
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
        doc_.fail(where + " has both a matrix and translation/rotation/scale");
      if (m[3] != 0 || m[7] != 0 || m[11] != 0 || m[15] != 1) doc_.fail(where + ".matrix is not affine");
      for (int col = 0; col < 4; ++col) {
        for (int row = 0; row < 3; ++row) a.matrix()(row, col) = m[4 * col + row];  // column-major
      }
      return a;
    }
    if (!t.empty()) a.translate(Vec3(t[0], t[1], t[2]));
    if (!r.empty()) {
      Eigen::Quaterniond q(r[3], r[0], r[1], r[2]);  // glTF stores (x, y, z, w)
      if (!(q.norm() > 0) || !std::isfinite(q.norm())) doc_.fail(where + ".rotation is not a rotation");
      a.rotate(q.normalized());
    }
    if (!s.empty()) a.scale(Vec3(s[0], s[1], s[2]));
    return a;
  }

  std::vector<std::uint64_t> indices_in(const Json& o, const char* key, const std::string& where) const {
    std::vector<std::uint64_t> out;
    for (const Json& x : doc_.array(o, key, where + ".")) {
      if (!x.is_number_unsigned())
        doc_.fail(fmt::format("{}.{} holds {}, not an index", where, key, x.dump()));
      out.push_back(x.get<std::uint64_t>());
    }
    return out;
  }

  /// The "name" string of `o`, or "" when it has none.
  static std::string name_of(const Json& o) {
    const auto name = o.find("name");
    return name != o.end() && name->is_string() ? name->get<std::string>() : std::string();
  }

  /// GltfInstance::name of node `index` (which has mesh `mesh`).
  std::string instance_name(const Json& node, std::uint64_t index, std::uint64_t mesh) const {
    if (std::string name = name_of(node); !name.empty()) return name;
    const std::string mesh_name = name_of(doc_.element("meshes", mesh));
    return mesh_name.empty() ? fmt::format("node {}", index) : fmt::format("{} (node {})", mesh_name, index);
  }

  void walk_scene(GltfContent& c) const {
    const std::size_t node_count = doc_.array(doc_.root(), "nodes", "").size();
    std::vector<std::uint64_t> roots;
    const Json& scenes = doc_.array(doc_.root(), "scenes", "");
    if (!scenes.empty()) {
      const std::uint64_t s = doc_.optional_uint(doc_.root(), "scene", "the document").value_or(0);
      roots = indices_in(doc_.element("scenes", s), "nodes", fmt::format("scenes[{}]", s));
    } else {
      std::vector<char> is_child(node_count, 0);
      for (std::size_t i = 0; i < node_count; ++i) {
        for (const std::uint64_t k :
             indices_in(doc_.element("nodes", i), "children", fmt::format("nodes[{}]", i))) {
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
      const Json& node = doc_.element("nodes", index);
      if (visited[index]) doc_.fail(where + " is reached twice: the node hierarchy must be a forest");
      visited[index] = 1;
      const Eigen::Affine3d world = parent * local_transform(node, where);
      if (const auto mesh = doc_.optional_uint(node, "mesh", where)) {
        const GltfInstance instance{instance_name(node, index, *mesh), c.soup.vertices.size(),
                                    c.soup.triangles.size()};
        const std::string mesh_where = fmt::format("meshes[{}]", *mesh);
        const Json& primitives = doc_.array(doc_.element("meshes", *mesh), "primitives", mesh_where + ".");
        for (std::size_t k = 0; k < primitives.size(); ++k) {
          append_primitive(primitives[k], fmt::format("{}.primitives[{}]", mesh_where, k), world, c);
        }
        if (c.soup.triangles.size() > instance.first_triangle) {
          c.instances.push_back(instance);
          if (!world.matrix().isIdentity(0.0)) {
            ++c.transformed_instances;
            if (world.linear().determinant() < 0) ++c.mirrored_instances;
          }
        }
      }
      const std::vector<std::uint64_t> children = indices_in(node, "children", where);
      for (auto it = children.rbegin(); it != children.rend(); ++it) stack.emplace_back(*it, world);
    }
    if (!scenes.empty()) return;  // nodes no scene lists are not drawn
    // Without scenes every node is drawn from the roots: one not reached is a
    // child of a cycle of children (a node its own ancestor), never a forest.
    for (std::size_t i = 0; i < node_count; ++i) {
      if (!visited[i]) {
        doc_.fail(
            fmt::format("nodes[{}] lies on a cycle of children (or under one), so it has no root: the "
                        "node hierarchy must be a forest",
                        i));
      }
    }
  }

  const GltfDocument& doc_;
  const GltfReadOptions& options_;
};

}  // namespace

GltfContent parse_gltf(std::string_view bytes, const std::string& name, const GltfReadOptions& options) {
  const GltfDocument doc(bytes, name);
  return GltfReader(doc, options).read();
}

}  // namespace fabmesh
