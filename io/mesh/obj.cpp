#include "io/mesh/obj.h"

#include <fmt/format.h>

#include <algorithm>
#include <cstdint>
#include <limits>
#include <map>
#include <numeric>
#include <optional>
#include <tuple>
#include <utility>
#include <vector>

#include "geometry/core/disjoint_sets.h"
#include "geometry/core/errors.h"
#include "geometry/mesh/halfedge_mesh.h"
#include "io/file.h"
#include "io/mesh/text_scanner.h"

namespace fabmesh {
namespace {

/// The vertex part of a face corner ("7", "7/2", "7//3", "7/2/3").
std::string_view vertex_part(std::string_view corner) {
  const std::size_t slash = corner.find('/');
  return slash == std::string_view::npos ? corner : corner.substr(0, slash);
}

/// Leading and trailing blanks removed.
std::string trimmed(std::string_view text) {
  const std::size_t first = text.find_first_not_of(" \t\r");
  if (first == std::string_view::npos) return "";
  const std::size_t last = text.find_last_not_of(" \t\r");
  return std::string(text.substr(first, last - first + 1));
}

/// The `o` objects and `g` groups of an OBJ file as its records declare
/// them: each face's group, a group being one `g` name within one `o`.
class ObjGroups {
 public:
  struct Group {
    std::size_t object = 0;  ///< the ordinal of its `o` record (0: before any)
    std::string object_name;
    std::string name;
  };

  void start_object(std::string name) {
    ++object_;
    object_name_ = std::move(name);
    group_name_ = "default";
    current_.reset();
  }
  void start_group(std::string name) {
    group_name_ = name.empty() ? "default" : std::move(name);
    current_.reset();
  }
  void add_faces(std::size_t count) {
    if (!current_) current_ = group_index();
    face_group_.insert(face_group_.end(), count, *current_);
  }
  const std::vector<Group>& groups() const { return groups_; }
  const std::vector<std::uint32_t>& face_group() const { return face_group_; }

 private:
  std::uint32_t group_index() {
    const auto key = std::make_pair(object_, group_name_);
    const auto [it, added] = index_.emplace(key, static_cast<std::uint32_t>(groups_.size()));
    if (added) groups_.push_back({object_, object_name_, group_name_});
    return it->second;
  }

  std::size_t object_ = 0;
  std::string object_name_;
  std::string group_name_ = "default";
  std::optional<std::uint32_t> current_;
  std::map<std::pair<std::size_t, std::string>, std::uint32_t> index_;
  std::vector<Group> groups_;
  std::vector<std::uint32_t> face_group_;
};

/// Parses the records; with `groups`, also the group of every triangle.
TriangleSoup parse_records(std::string_view bytes, const std::string& name, ObjGroups* groups) {
  TextScanner scan(bytes, name);
  TriangleSoup soup;
  std::vector<std::uint32_t> polygon;
  std::int64_t max_forward = 0;  // largest 1-based index beyond the vertices read so far
  int max_forward_line = 0;
  std::string_view line;
  while (scan.next_content_line(line, '#')) {
    std::string_view rest = line;
    const std::string_view key = next_token(rest);
    if (key == "v") {
      Vec3 p;
      for (int a = 0; a < 3; ++a) p[a] = scan.to_double(next_token(rest), "vertex coordinate");
      if (soup.vertices.size() >= std::numeric_limits<std::uint32_t>::max()) scan.fail("too many vertices");
      soup.vertices.push_back(p);
    } else if (key == "f") {
      polygon.clear();
      const auto nv = static_cast<std::int64_t>(soup.vertices.size());
      for (std::string_view corner = next_token(rest); !corner.empty(); corner = next_token(rest)) {
        std::int64_t i = scan.to_int(vertex_part(corner), "face vertex index");
        if (i == 0) scan.fail("face vertex index 0 (OBJ indices start at 1)");
        if (i < 0) {
          if (-i > nv) scan.fail(fmt::format("relative index {} but only {} vertices precede it", i, nv));
          i = nv + i;
        } else {
          if (i > std::numeric_limits<std::uint32_t>::max())
            scan.fail(fmt::format("face vertex index {} too large", i));
          if (i > nv && i > max_forward) {
            max_forward = i;
            max_forward_line = scan.line();
          }
          i -= 1;
        }
        polygon.push_back(static_cast<std::uint32_t>(i));
      }
      if (polygon.size() < 3) scan.fail(fmt::format("face has {} corners, needs at least 3", polygon.size()));
      for (std::size_t k = 1; k + 1 < polygon.size(); ++k) {
        soup.triangles.push_back({polygon[0], polygon[k], polygon[k + 1]});
      }
      if (groups != nullptr) groups->add_faces(polygon.size() - 2);
    } else if (groups != nullptr && key == "o") {
      groups->start_object(trimmed(rest));
    } else if (groups != nullptr && key == "g") {
      groups->start_group(trimmed(rest));
    }
    // vt, vn, s, usemtl, mtllib, l, p ...: not geometry of the surface.
  }
  if (max_forward > static_cast<std::int64_t>(soup.vertices.size())) {
    throw FileError(name, max_forward_line, 0,
                    fmt::format("{}:{}: face refers to vertex {} but the file has {} vertices", name,
                                max_forward_line, max_forward, soup.vertices.size()));
  }
  return soup;
}

}  // namespace

TriangleSoup parse_obj(std::string_view bytes, const std::string& name) {
  return parse_records(bytes, name, nullptr);
}

namespace {

/// Per vertex: the smallest index of a vertex with exactly equal finite
/// coordinates (itself when there is none, or it is not finite).
std::vector<std::uint32_t> coincident_representatives(const TriangleSoup& soup) {
  std::vector<std::uint32_t> order;
  for (std::uint32_t i = 0; i < soup.vertices.size(); ++i) {
    if (soup.vertices[i].allFinite()) order.push_back(i);
  }
  const auto less = [&](std::uint32_t a, std::uint32_t b) {
    const Vec3& p = soup.vertices[a];
    const Vec3& q = soup.vertices[b];
    return std::tie(p.x(), p.y(), p.z()) < std::tie(q.x(), q.y(), q.z());
  };
  std::stable_sort(order.begin(), order.end(), less);
  std::vector<std::uint32_t> representative(soup.vertices.size());
  std::iota(representative.begin(), representative.end(), std::uint32_t{0});
  for (std::size_t k = 1; k < order.size(); ++k) {
    if (!less(order[k - 1], order[k])) representative[order[k]] = representative[order[k - 1]];
  }
  return representative;
}

/// Unites the groups of one `o` that share a vertex (by index or coordinates).
DisjointSets<std::uint32_t> shells(const TriangleSoup& soup, const ObjGroups& groups) {
  DisjointSets<std::uint32_t> sets(groups.groups().size());
  const std::vector<std::uint32_t> representative = coincident_representatives(soup);
  std::vector<std::uint32_t> owner(soup.vertices.size(), std::numeric_limits<std::uint32_t>::max());
  for (std::size_t f = 0; f < soup.triangles.size(); ++f) {
    const std::uint32_t group = groups.face_group()[f];
    for (const std::uint32_t v : soup.triangles[f]) {
      std::uint32_t& first = owner[representative[v]];
      if (first == std::numeric_limits<std::uint32_t>::max()) {
        first = group;
      } else if (groups.groups()[first].object == groups.groups()[group].object) {
        sets.unite(first, group);
      }
    }
  }
  return sets;
}

}  // namespace

ObjContent parse_obj_objects(std::string_view bytes, const std::string& name) {
  ObjGroups groups;
  ObjContent content;
  content.soup = parse_records(bytes, name, &groups);
  const std::vector<ObjGroups::Group>& declared = groups.groups();
  if (declared.size() < 2) {  // one group at most: one object, no shells to tell apart
    if (!declared.empty()) {
      const ObjGroups::Group& only = declared.front();
      content.object_names.push_back(only.object_name.empty() ? only.name : only.object_name);
    }
    content.face_object.assign(content.soup.triangles.size(), 0);
    return content;
  }
  DisjointSets<std::uint32_t> sets = shells(content.soup, groups);
  std::vector<std::size_t> shells_of_object(declared.empty() ? 0 : declared.back().object + 1, 0);
  for (std::uint32_t g = 0; g < declared.size(); ++g) {
    if (sets.find(g) == g) ++shells_of_object[declared[g].object];
  }
  std::vector<std::uint32_t> object_of_shell(declared.size(), std::numeric_limits<std::uint32_t>::max());
  content.face_object.reserve(content.soup.triangles.size());
  for (const std::uint32_t g : groups.face_group()) {
    const std::uint32_t shell = sets.find(g);
    std::uint32_t& object = object_of_shell[shell];
    if (object == std::numeric_limits<std::uint32_t>::max()) {
      const ObjGroups::Group& first = declared[shell];
      object = static_cast<std::uint32_t>(content.object_names.size());
      if (shells_of_object[first.object] == 1 && !first.object_name.empty()) {
        content.object_names.push_back(first.object_name);
      } else {
        content.object_names.push_back(first.object_name.empty() ? first.name
                                                                 : first.object_name + "/" + first.name);
      }
    }
    content.face_object.push_back(object);
  }
  return content;
}

std::string encode_obj(const TriangleSoup& soup) {
  require_indices_in_range(soup);
  fmt::memory_buffer out;
  fmt::format_to(std::back_inserter(out), "# written by fabmesh\n");
  for (const Vec3& p : soup.vertices)
    fmt::format_to(std::back_inserter(out), "v {} {} {}\n", p.x(), p.y(), p.z());
  for (const auto& t : soup.triangles) {
    fmt::format_to(std::back_inserter(out), "f {} {} {}\n", t[0] + 1ull, t[1] + 1ull, t[2] + 1ull);
  }
  return fmt::to_string(out);
}

void write_obj(const TriangleSoup& soup, const std::string& path) {
  write_file_atomically(path, encode_obj(soup));
}

void write_obj(const Mesh& mesh, const std::string& path) { write_obj(to_soup(mesh), path); }

}  // namespace fabmesh
