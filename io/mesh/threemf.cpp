#include "io/mesh/threemf.h"

// lib3mf 1.8's plain C interface (Debian lib3mf-dev): its types from the header,
// its functions from the library, loaded when first used (lib3mf() below).
#include <Model/COM/NMR_DLLInterfaces.h>
#include <dlfcn.h>
#include <fmt/format.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <functional>
#include <limits>
#include <map>
#include <optional>
#include <set>
#include <stdexcept>
#include <utility>
#include <vector>

#include "geometry/core/errors.h"
#include "geometry/core/units.h"
#include "io/mesh/zip_archive.h"

// lib3mf 1.8.1 leaks what libzip's zip_fopen_index allocates for each part
// it opens (160 bytes, 3 or 4 parts per read: lib3mf issue #180, fixed in
// lib3mf 2.0 by pull request #190); fabmesh cannot free it. LeakSanitizer
// builds (fuzzers, FABMESH_SANITIZE) ignore leaks from libzip, which only
// lib3mf uses. Matched by module: libzip has no frame pointers, so the
// allocation stack stops there.
#if defined(__SANITIZE_ADDRESS__)
#define FABMESH_LSAN_HOOK 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define FABMESH_LSAN_HOOK 1
#endif
#endif
#ifdef FABMESH_LSAN_HOOK
extern "C" const char* __lsan_default_suppressions() { return "leak:libzip.so\n"; }
#endif

namespace fabmesh {
namespace {

// ---------------------------------------------------------------- lib3mf, loaded on first use

// lib3mf and the libzip and libcrypto it links make about half of the symbol
// binding of a process start, though only runs that write or read 3MF use
// them: the functions fabmesh calls are looked up in lib3MF.so.1 (its
// soname) the first time, with dlopen, and kept for the process.
#define FABMESH_LIB3MF_FUNCTIONS(F)            \
  F(lib3mf_builditem_getobjectresource)        \
  F(lib3mf_builditem_getobjecttransform)       \
  F(lib3mf_builditem_hasobjecttransform)       \
  F(lib3mf_builditem_setuuidutf8)              \
  F(lib3mf_builditemiterator_getcurrent)       \
  F(lib3mf_builditemiterator_movenext)         \
  F(lib3mf_component_getobjectresource)        \
  F(lib3mf_component_gettransform)             \
  F(lib3mf_component_hastransform)             \
  F(lib3mf_componentsobject_getcomponent)      \
  F(lib3mf_componentsobject_getcomponentcount) \
  F(lib3mf_createmodel)                        \
  F(lib3mf_getlasterror)                       \
  F(lib3mf_meshobject_gettrianglecount)        \
  F(lib3mf_meshobject_gettriangleindices)      \
  F(lib3mf_meshobject_getvertexcount)          \
  F(lib3mf_meshobject_getvertices)             \
  F(lib3mf_meshobject_setgeometry)             \
  F(lib3mf_model_addbuilditem)                 \
  F(lib3mf_model_addmeshobject)                \
  F(lib3mf_model_addmetadatautf8)              \
  F(lib3mf_model_getbuilditems)                \
  F(lib3mf_model_getunit)                      \
  F(lib3mf_model_queryreader)                  \
  F(lib3mf_model_querywriter)                  \
  F(lib3mf_model_setbuilduuidutf8)             \
  F(lib3mf_model_setunit)                      \
  F(lib3mf_object_getnameutf8)                 \
  F(lib3mf_object_iscomponentsobject)          \
  F(lib3mf_object_ismeshobject)                \
  F(lib3mf_object_setnameutf8)                 \
  F(lib3mf_object_setuuidutf8)                 \
  F(lib3mf_reader_readfrombuffer)              \
  F(lib3mf_release)                            \
  F(lib3mf_resource_getresourceid)             \
  F(lib3mf_writer_writetocallback)

struct Lib3mf {
// NOLINTNEXTLINE(bugprone-macro-parentheses): a declaration, not an expression
#define FABMESH_LIB3MF_POINTER(name) decltype(&NMR::name) name = nullptr;
  FABMESH_LIB3MF_FUNCTIONS(FABMESH_LIB3MF_POINTER)
#undef FABMESH_LIB3MF_POINTER
  std::string error;  ///< why lib3mf could not be loaded; empty when it was
};

Lib3mf load_lib3mf() {
  Lib3mf l;
  void* handle = dlopen(FABMESH_LIB3MF_SONAME, RTLD_NOW | RTLD_LOCAL);
  if (handle == nullptr) {
    const char* why = dlerror();
    l.error = fmt::format("3MF: lib3mf ({}) could not be loaded: {}", FABMESH_LIB3MF_SONAME,
                          why != nullptr ? why : "unknown reason");
    return l;
  }
#define FABMESH_LIB3MF_LOOKUP(name)                                      \
  l.name = reinterpret_cast<decltype(&NMR::name)>(dlsym(handle, #name)); \
  if (l.name == nullptr && l.error.empty())                              \
    l.error = fmt::format("3MF: {} has no function {}", FABMESH_LIB3MF_SONAME, #name);
  FABMESH_LIB3MF_FUNCTIONS(FABMESH_LIB3MF_LOOKUP)
#undef FABMESH_LIB3MF_LOOKUP
  return l;
}

/// lib3mf's functions. \throw std::runtime_error when lib3mf is not installed
const Lib3mf& lib3mf() {
  static const Lib3mf l = load_lib3mf();
  if (!l.error.empty()) throw std::runtime_error(l.error);
  return l;
}

/// Owns one lib3mf object handle.
class Handle {
 public:
  Handle() = default;
  ~Handle() {
    if (p_ != nullptr) lib3mf().lib3mf_release(p_);
  }
  Handle(const Handle&) = delete;
  Handle& operator=(const Handle&) = delete;
  NMR::PLib3MFBase* get() const { return p_; }
  NMR::PLib3MFBase** out() { return &p_; }

 private:
  NMR::PLib3MFBase* p_ = nullptr;
};

/// lib3mf's message for the last failure on `instance`.
std::string last_error(NMR::PLib3MFBase* instance) {
  DWORD code = 0;
  LPCSTR message = nullptr;
  if (instance == nullptr || lib3mf().lib3mf_getlasterror(instance, &code, &message) != LIB3MF_OK ||
      message == nullptr) {
    return "unknown lib3mf error";
  }
  return fmt::format("{} (lib3mf error {:#x})", message, code);
}

// ---------------------------------------------------------------- units

struct Unit {
  const char* name;
  DWORD lib3mf;
  double metres;
};

// 3MF's units: fabmesh's own (geometry/core/units.h) and two more.
constexpr std::array<Unit, 6> kUnits = {{{"micron", NMR::MODELUNIT_MICROMETER, 1e-6},
                                         {"mm", NMR::MODELUNIT_MILLIMETER, metres_per_unit("mm")},
                                         {"cm", NMR::MODELUNIT_CENTIMETER, metres_per_unit("cm")},
                                         {"m", NMR::MODELUNIT_METER, metres_per_unit("m")},
                                         {"in", NMR::MODELUNIT_INCH, metres_per_unit("in")},
                                         {"ft", NMR::MODELUNIT_FOOT, 0.3048}}};

const Unit& unit_named(const std::string& units) {
  for (const Unit& u : kUnits) {
    if (units == u.name) return u;
  }
  throw InputError(fmt::format("3MF: units = '{}' is not one of micron, mm, cm, m, in, ft", units));
}

// ---------------------------------------------------------------- writing

/// The largest |coordinate| lib3mf 1.8 can write: it converts x * 1e6 to a
/// 64-bit integer (undefined behaviour beyond 9.2e18).
constexpr double kMaxCoordinate = 1e9;

void require_writable(const ThreeMfObject& object, std::size_t index) {
  const std::string what = fmt::format("3MF object {} '{}'", index, object.name);
  if (object.soup.triangles.empty()) throw InputError(what + " has no triangle");
  if (object.soup.vertices.size() > std::numeric_limits<std::uint32_t>::max() ||
      object.soup.triangles.size() > std::numeric_limits<std::uint32_t>::max()) {
    throw InputError(what + " has more vertices or triangles than 3MF can index");
  }
  require_indices_in_range(object.soup);
  for (std::size_t i = 0; i < object.soup.vertices.size(); ++i) {
    const Vec3& p = object.soup.vertices[i];
    if (!p.allFinite() || p.cwiseAbs().maxCoeff() >= kMaxCoordinate) {
      throw InputError(fmt::format("{}: vertex {} = ({}, {}, {}) is not finite or not below {} in magnitude",
                                   what, i, p.x(), p.y(), p.z(), kMaxCoordinate));
    }
  }
}

/// A 64-bit mix of words (splitmix64's finalizer over a running state).
class Hasher {
 public:
  explicit Hasher(std::uint64_t seed) : state_(seed) {}
  void add(std::uint64_t word) {
    state_ ^= word + 0x9e3779b97f4a7c15ULL + (state_ << 6) + (state_ >> 2);
    state_ = mix(state_);
  }
  void add(const std::string& s) {
    add(s.size());
    for (char c : s) add(static_cast<unsigned char>(c));
  }
  std::uint64_t value() const { return mix(state_); }

 private:
  static std::uint64_t mix(std::uint64_t z) {
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
  }
  std::uint64_t state_;
};

/// A content hash of what is written (title, unit, every object's name and
/// float32 geometry): the seed of the UUIDs, so that equal input gives equal
/// bytes and different models get different UUIDs.
std::array<std::uint64_t, 2> content_hash(const std::vector<ThreeMfObject>& objects,
                                          const ThreeMfOptions& o) {
  Hasher a(0x3f4d46ULL);
  Hasher b(0x666162ULL);
  for (Hasher* h : {&a, &b}) {
    h->add(o.title);
    h->add(o.units);
    for (const ThreeMfObject& object : objects) {
      h->add(object.name);
      for (const Vec3& p : object.soup.vertices) {
        for (int k = 0; k < 3; ++k) {
          const float f = static_cast<float>(p[k]);
          std::uint32_t bits;
          std::memcpy(&bits, &f, 4);
          h->add(bits);
        }
      }
      for (const auto& t : object.soup.triangles) h->add((std::uint64_t{t[0]} << 32) ^ (t[1] * 31ULL) ^ t[2]);
    }
  }
  return {a.value(), b.value()};
}

/// A version-8 (RFC 9562: custom) UUID from the content hash, a role
/// ("object", "item", "build") and an index.
std::string uuid(const std::array<std::uint64_t, 2>& hash, const std::string& role, std::size_t index) {
  Hasher a(hash[0]);
  Hasher b(hash[1]);
  for (Hasher* h : {&a, &b}) {
    h->add(role);
    h->add(index);
  }
  std::uint64_t hi = a.value();
  std::uint64_t lo = b.value();
  hi = (hi & ~0xf000ULL) | 0x8000ULL;        // version 8
  lo = (lo & ~(3ULL << 62)) | (2ULL << 62);  // variant 10
  return fmt::format("{:08x}-{:04x}-{:04x}-{:04x}-{:012x}", hi >> 32, (hi >> 16) & 0xffff, hi & 0xffff,
                     lo >> 48, lo & 0xffffffffffffULL);
}

void check(LIB3MFRESULT result, NMR::PLib3MFBase* instance, const char* what) {
  if (result != LIB3MF_OK)
    throw std::runtime_error(fmt::format("3MF writer: {}: {}", what, last_error(instance)));
}

void add_object(NMR::PLib3MFModel* model, const ThreeMfObject& object,
                const std::array<std::uint64_t, 2>& hash, std::size_t index) {
  std::vector<NMR::MODELMESHVERTEX> vertices(object.soup.vertices.size());
  for (std::size_t i = 0; i < vertices.size(); ++i) {
    for (int k = 0; k < 3; ++k) vertices[i].m_fPosition[k] = static_cast<float>(object.soup.vertices[i][k]);
  }
  std::vector<NMR::MODELMESHTRIANGLE> triangles(object.soup.triangles.size());
  for (std::size_t i = 0; i < triangles.size(); ++i) {
    for (int k = 0; k < 3; ++k) triangles[i].m_nIndices[k] = object.soup.triangles[i][k];
  }
  Handle mesh;
  check(lib3mf().lib3mf_model_addmeshobject(model, mesh.out()), model, "add mesh object");
  check(lib3mf().lib3mf_object_setnameutf8(mesh.get(), object.name.c_str()), mesh.get(), "object name");
  check(lib3mf().lib3mf_object_setuuidutf8(mesh.get(), uuid(hash, "object", index).c_str()), mesh.get(),
        "object UUID");
  check(
      lib3mf().lib3mf_meshobject_setgeometry(mesh.get(), vertices.data(), static_cast<DWORD>(vertices.size()),
                                             triangles.data(), static_cast<DWORD>(triangles.size())),
      mesh.get(), "mesh geometry");
  Handle item;
  check(lib3mf().lib3mf_model_addbuilditem(model, mesh.get(), nullptr, item.out()), model, "add build item");
  check(lib3mf().lib3mf_builditem_setuuidutf8(item.get(), uuid(hash, "item", index).c_str()), item.get(),
        "build item UUID");
}

/// The bytes lib3mf writes, and its seeks (it patches zip headers). The
/// callbacks have lib3mf's ExportStream_WriteCallbackType and
/// ExportStream_SeekCallbackType signatures; they return 0 for success.
struct Sink {
  std::string bytes;
  std::size_t position = 0;
};

std::uint32_t sink_write(unsigned char* data, std::uint32_t size, void* user) {
  Sink& sink = *static_cast<Sink*>(user);
  if (sink.position + size > sink.bytes.size()) sink.bytes.resize(sink.position + size);
  std::memcpy(sink.bytes.data() + sink.position, data, size);
  sink.position += size;
  return 0;
}

std::uint32_t sink_seek(std::uint64_t position, void* user) {
  Sink& sink = *static_cast<Sink*>(user);
  if (position > sink.bytes.size()) return 1;
  sink.position = static_cast<std::size_t>(position);
  return 0;
}

// ---------------------------------------------------------------- reading

/// Components may nest; 3MF forbids cycles (an object refers only to objects
/// defined before it) but the depth is bounded all the same.
constexpr int kMaxComponentDepth = 64;

/// Object instances (meshes and components objects, each placed once per
/// path from a build item) expanded at most: components of components
/// multiply, and instances of an empty mesh cost time without adding a
/// triangle the budget would count.
constexpr std::uint64_t kMaxComponentVisits = 1000000;

Eigen::Affine3d to_affine(const NMR::MODELTRANSFORM& t) {
  Eigen::Affine3d a = Eigen::Affine3d::Identity();
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) a.linear()(r, c) = t.m_fFields[r][c];
    a.translation()[r] = t.m_fFields[r][3];
  }
  return a;
}

/// Expands build items into soups, within the triangle budget.
class ModelReader {
 public:
  ModelReader(const std::string& name, const ThreeMfReadOptions& options) : name_(name), options_(options) {}

  [[noreturn]] void fail(const std::string& message) const {
    throw FileError(name_, 0, 0, fmt::format("{}: {}", name_, message));
  }
  void check(LIB3MFRESULT result, NMR::PLib3MFBase* instance, const char* what) const {
    if (result != LIB3MF_OK) fail(fmt::format("{}: {}", what, last_error(instance)));
  }

  std::string object_name(NMR::PLib3MFModelObjectResource* object) const {
    ULONG needed = 0;
    check(lib3mf().lib3mf_object_getnameutf8(object, nullptr, 0, &needed), object, "object name");
    std::string text(needed + 1, '\0');
    check(lib3mf().lib3mf_object_getnameutf8(object, text.data(), needed + 1, &needed), object,
          "object name");
    text.resize(std::strlen(text.c_str()));
    return text;
  }

  /// Appends `object` (a mesh, or components resolved recursively) placed by `transform`.
  void append(NMR::PLib3MFModelObjectResource* object, const Eigen::Affine3d& transform, int depth,
              TriangleSoup& out) {
    if (depth > kMaxComponentDepth) fail(fmt::format("components nest deeper than {}", kMaxComponentDepth));
    BOOL is_mesh = false;
    BOOL is_components = false;
    check(lib3mf().lib3mf_object_ismeshobject(object, &is_mesh), object, "object type");
    check(lib3mf().lib3mf_object_iscomponentsobject(object, &is_components), object, "object type");
    if (is_mesh) {
      append_mesh(object, transform, out);
    } else if (is_components) {
      DWORD count = 0;
      check(lib3mf().lib3mf_componentsobject_getcomponentcount(object, &count), object, "components");
      for (DWORD i = 0; i < count; ++i) {
        Handle component;
        check(lib3mf().lib3mf_componentsobject_getcomponent(object, i, component.out()), object, "component");
        Handle child;
        check(lib3mf().lib3mf_component_getobjectresource(component.get(), child.out()), component.get(),
              "component object");
        BOOL has_transform = false;
        check(lib3mf().lib3mf_component_hastransform(component.get(), &has_transform), component.get(),
              "transform");
        Eigen::Affine3d local = Eigen::Affine3d::Identity();
        if (has_transform) {
          NMR::MODELTRANSFORM t;
          check(lib3mf().lib3mf_component_gettransform(component.get(), &t), component.get(), "transform");
          local = to_affine(t);
        }
        append(child.get(), transform * local, depth + 1, out);
      }
    }
  }

 private:
  void append_mesh(NMR::PLib3MFModelMeshObject* mesh, const Eigen::Affine3d& transform, TriangleSoup& out) {
    DWORD nv = 0;
    DWORD nt = 0;
    check(lib3mf().lib3mf_meshobject_getvertexcount(mesh, &nv), mesh, "vertex count");
    check(lib3mf().lib3mf_meshobject_gettrianglecount(mesh, &nt), mesh, "triangle count");
    triangles_ += nt;
    vertices_ += nv;
    if (triangles_ > options_.max_triangles || vertices_ > 3 * options_.max_triangles) {
      fail(fmt::format(
          "more than {} triangles or {} vertices (components instance meshes; the reader's budget)",
          options_.max_triangles, 3 * options_.max_triangles));
    }
    if (out.vertices.size() + nv > std::numeric_limits<std::uint32_t>::max()) fail("too many vertices");
    std::vector<NMR::MODELMESHVERTEX> vertices(nv);
    std::vector<NMR::MODELMESHTRIANGLE> triangles(nt);
    if (nv > 0)
      check(lib3mf().lib3mf_meshobject_getvertices(mesh, vertices.data(), nv, nullptr), mesh, "vertices");
    if (nt > 0) {
      check(lib3mf().lib3mf_meshobject_gettriangleindices(mesh, triangles.data(), nt, nullptr), mesh,
            "triangles");
    }
    const auto base = static_cast<std::uint32_t>(out.vertices.size());
    out.vertices.reserve(out.vertices.size() + nv);
    for (const NMR::MODELMESHVERTEX& v : vertices) {
      const Vec3 p = transform * Vec3(v.m_fPosition[0], v.m_fPosition[1], v.m_fPosition[2]);
      if (!p.allFinite())
        fail(fmt::format("vertex {} is not finite (after its transforms)", out.vertices.size() - base));
      out.vertices.push_back(p);
    }
    const bool mirrored = transform.linear().determinant() < 0;
    out.triangles.reserve(out.triangles.size() + nt);
    for (const NMR::MODELMESHTRIANGLE& t : triangles) {
      for (const DWORD i : t.m_nIndices) {
        if (i >= nv) fail(fmt::format("a triangle refers to vertex {} of a mesh with {} vertices", i, nv));
      }
      const std::uint32_t a = base + t.m_nIndices[0];
      const std::uint32_t b = base + t.m_nIndices[1];
      const std::uint32_t c = base + t.m_nIndices[2];
      out.triangles.push_back(mirrored ? std::array<std::uint32_t, 3>{a, c, b}
                                       : std::array<std::uint32_t, 3>{a, b, c});
    }
  }

  const std::string& name_;
  const ThreeMfReadOptions& options_;
  std::size_t triangles_ = 0;
  std::size_t vertices_ = 0;
};

/// The value of attribute `name` in the XML start tag `tag`, or "".
std::string attribute(std::string_view tag, const std::string& name) {
  for (std::size_t at = tag.find(name); at != std::string_view::npos; at = tag.find(name, at + 1)) {
    std::size_t k = at + name.size();
    const bool starts = at > 0 && std::isspace(static_cast<unsigned char>(tag[at - 1]));
    while (k < tag.size() && std::isspace(static_cast<unsigned char>(tag[k]))) ++k;
    if (!starts || k >= tag.size() || tag[k] != '=') continue;
    ++k;
    while (k < tag.size() && std::isspace(static_cast<unsigned char>(tag[k]))) ++k;
    if (k >= tag.size() || (tag[k] != '"' && tag[k] != '\'')) continue;
    const std::size_t close = tag.find(tag[k], k + 1);
    if (close == std::string_view::npos) return "";
    return std::string(tag.substr(k + 1, close - k - 1));
  }
  return "";
}

/// What expanding an object makes (its instances counted as visits), saturating at kSaturated.
constexpr std::uint64_t kSaturated = std::uint64_t{1} << 62;
struct Expansion {
  std::uint64_t triangles = 0, vertices = 0, visits = 0;
  Expansion operator+(const Expansion& o) const {
    const auto sum = [](std::uint64_t a, std::uint64_t b) { return std::min(a + b, kSaturated); };
    return {sum(triangles, o.triangles), sum(vertices, o.vertices), sum(visits, o.visits)};
  }
};

/// An object of a model part as its XML declares it.
struct DeclaredObject {
  std::uint64_t triangles = 0, vertices = 0;
  std::vector<std::string> components;  ///< the objectid of each component
};

/// Fails unless the build of the 3MF model part `xml` expands within
/// `max_triangles` (and 3 x as many vertices) and kMaxComponentVisits object
/// instances. Worked out from the XML's own counts, once per object, before
/// lib3mf reads the part: lib3mf itself walks every path through the
/// components of each build item while reading it (ten levels of 20
/// components are 20^10 paths), and so would the expansion after it.
void require_bounded_expansion(std::string_view xml, const ModelReader& reader, std::size_t max_triangles) {
  std::map<std::string, DeclaredObject, std::less<>> objects;
  std::vector<std::string> items;
  DeclaredObject* current = nullptr;
  for (std::size_t at = xml.find('<'); at != std::string_view::npos; at = xml.find('<', at + 1)) {
    const std::size_t end = xml.find('>', at);
    if (end == std::string_view::npos) break;
    const std::string_view tag = xml.substr(at + 1, end - at - 1);
    std::string_view name = tag.substr(0, std::min(tag.size(), tag.find_first_of(" \t\r\n/")));
    const bool closing = !tag.empty() && tag.front() == '/';
    if (closing) name = tag.substr(1, std::min(tag.size(), tag.find_first_of(" \t\r\n>", 1)) - 1);
    if (const std::size_t colon = name.find(':'); colon != std::string_view::npos)
      name.remove_prefix(colon + 1);
    if (closing) {
      if (name == "object") current = nullptr;
    } else if (name == "object") {
      current = &objects[attribute(tag, "id")];
    } else if (current != nullptr && name == "triangle") {
      ++current->triangles;
    } else if (current != nullptr && name == "vertex") {
      ++current->vertices;
    } else if (current != nullptr && name == "component") {
      current->components.push_back(attribute(tag, "objectid"));
    } else if (name == "item") {
      items.push_back(attribute(tag, "objectid"));
    }
    at = end;
  }
  std::map<std::string, Expansion, std::less<>> known;
  std::set<std::string, std::less<>> open;  // on the current path: a cycle when met again
  const std::function<Expansion(const std::string&, int)> expansion = [&](const std::string& id, int depth) {
    if (depth > kMaxComponentDepth)
      reader.fail(fmt::format("components nest deeper than {}", kMaxComponentDepth));
    if (const auto k = known.find(id); k != known.end()) return k->second;
    const auto object = objects.find(id);
    if (object == objects.end()) return Expansion{0, 0, 1};  // lib3mf names the missing object
    if (!open.insert(id).second) reader.fail(fmt::format("object {} is its own component (a cycle)", id));
    Expansion e{object->second.triangles, object->second.vertices, 1};
    for (const std::string& child : object->second.components) e = e + expansion(child, depth + 1);
    open.erase(id);
    known.emplace(id, e);
    return e;
  };
  Expansion build;
  for (const std::string& item : items) build = build + expansion(item, 0);
  if (build.visits > kMaxComponentVisits) {
    reader.fail(fmt::format(
        "its build places {} object instances through components (components of components multiply), more "
        "than the {} fabmesh expands",
        build.visits >= kSaturated ? std::string("over 10^18") : std::to_string(build.visits),
        kMaxComponentVisits));
  }
  if (build.triangles > max_triangles || build.vertices > 3 * std::uint64_t{max_triangles}) {
    reader.fail(
        fmt::format("its build would make more than {} triangles or {} vertices (components instance meshes; "
                    "the reader's "
                    "budget)",
                    max_triangles, 3 * max_triangles));
  }
}

/// PrusaSlicer 2.5's command line (no OpenGL, so no thumbnail) writes a root
/// relationship to Metadata/thumbnail.png without that part, and lib3mf 1.8
/// refuses a package whose thumbnail part is missing. The package with an
/// empty part added under that name, and the name; nullopt when the package
/// has no such dangling relationship.
std::optional<std::pair<std::string, std::string>> add_missing_thumbnail(std::string_view bytes) {
  const auto entries = zip_entries(bytes);
  if (!entries) return std::nullopt;
  const auto has = [&](const std::string& name) {
    return std::any_of(entries->begin(), entries->end(), [&](const ZipEntry& e) { return e.name == name; });
  };
  const auto rels = std::find_if(entries->begin(), entries->end(),
                                 [](const ZipEntry& e) { return e.name == "_rels/.rels"; });
  if (rels == entries->end()) return std::nullopt;
  const auto text = zip_read(bytes, *rels, 1 << 20);
  if (!text) return std::nullopt;
  for (std::size_t at = text->find("<Relationship"); at != std::string::npos;
       at = text->find("<Relationship", at + 1)) {
    const std::string_view tag = std::string_view(*text).substr(at, text->find('>', at) - at);
    if (attribute(tag, "Type") !=
        "http://schemas.openxmlformats.org/package/2006/relationships/metadata/thumbnail") {
      continue;
    }
    std::string target = attribute(tag, "Target");
    if (!target.empty() && target.front() == '/') target.erase(0, 1);
    if (target.empty() || has(target)) continue;
    auto repaired = zip_append_stored(bytes, target, "");
    if (repaired) return std::make_pair(std::move(*repaired), target);
  }
  return std::nullopt;
}

std::string unit_name(DWORD lib3mf_unit, double& metres) {
  for (const Unit& u : kUnits) {
    if (u.lib3mf == lib3mf_unit) {
      metres = u.metres;
      return u.name;
    }
  }
  metres = 0.001;
  return "mm";
}

}  // namespace

double threemf_metres_per_unit(const std::string& units) { return unit_named(units).metres; }

double threemf_max_error(double max_abs_coordinate) {
  const double m = std::abs(max_abs_coordinate);
  // float32 rounding of x, of the product x * 1e6 (relative 2^-24 each) and
  // of the reader's parse: 3 * 2^-24 |x|, doubled as a margin; the truncation
  // to 6 decimals moves at most 1e-6 (one unit of the last decimal).
  const double per_axis = 1e-6 + 6.0 * std::ldexp(m, -24);
  return std::sqrt(3.0) * per_axis;
}

std::string encode_3mf(const std::vector<ThreeMfObject>& objects, const ThreeMfOptions& options) {
  const Unit& unit = unit_named(options.units);
  if (objects.empty()) throw InputError("3MF: no object to write");
  for (std::size_t i = 0; i < objects.size(); ++i) require_writable(objects[i], i);
  const std::array<std::uint64_t, 2> hash = content_hash(objects, options);

  Handle model;
  if (lib3mf().lib3mf_createmodel(model.out()) != LIB3MF_OK)
    throw std::runtime_error("3MF writer: lib3mf_createmodel failed");
  check(lib3mf().lib3mf_model_setunit(model.get(), unit.lib3mf), model.get(), "unit");
  if (!options.title.empty()) {
    check(lib3mf().lib3mf_model_addmetadatautf8(model.get(), "Title", options.title.c_str()), model.get(),
          "Title");
  }
  check(lib3mf().lib3mf_model_addmetadatautf8(model.get(), "Application", "fabmesh"), model.get(),
        "Application");
  for (std::size_t i = 0; i < objects.size(); ++i) add_object(model.get(), objects[i], hash, i);
  check(lib3mf().lib3mf_model_setbuilduuidutf8(model.get(), uuid(hash, "build", 0).c_str()), model.get(),
        "build UUID");

  Handle writer;
  check(lib3mf().lib3mf_model_querywriter(model.get(), "3mf", writer.out()), model.get(), "query writer");
  Sink sink;
  check(lib3mf().lib3mf_writer_writetocallback(writer.get(), reinterpret_cast<void*>(&sink_write),
                                               reinterpret_cast<void*>(&sink_seek), &sink),
        writer.get(), "write");
  return std::move(sink.bytes);
}

}  // namespace fabmesh

namespace fabmesh {

std::string threemf_package(std::string_view model_xml) {
  const std::string types =
      R"(<?xml version="1.0" encoding="UTF-8"?>)"
      R"(<Types xmlns="http://schemas.openxmlformats.org/package/2006/content-types">)"
      R"(<Default Extension="rels" ContentType="application/vnd.openxmlformats-package.relationships+xml"/>)"
      R"(<Default Extension="model" ContentType="application/vnd.ms-package.3dmanufacturing-3dmodel+xml"/>)"
      R"(</Types>)";
  const std::string rels =
      R"(<?xml version="1.0" encoding="UTF-8"?>)"
      R"(<Relationships xmlns="http://schemas.openxmlformats.org/package/2006/relationships">)"
      R"(<Relationship Target="/3D/3dmodel.model" Id="rel0" )"
      R"(Type="http://schemas.microsoft.com/3dmanufacturing/2013/01/3dmodel"/></Relationships>)";
  return zip_stored(
      {{"[Content_Types].xml", types}, {"_rels/.rels", rels}, {"3D/3dmodel.model", std::string(model_xml)}});
}

bool looks_like_3mf(std::string_view bytes) {
  const auto entries = zip_entries(bytes);
  if (!entries) return false;
  return std::any_of(entries->begin(), entries->end(), [](const ZipEntry& e) {
    std::string name = e.name;
    std::transform(name.begin(), name.end(), name.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return name.size() > 6 && name.compare(name.size() - 6, 6, ".model") == 0;
  });
}

ThreeMfContent parse_3mf(std::string_view bytes, const std::string& name, const ThreeMfReadOptions& options) {
  ModelReader reader(name, options);
  if (bytes.size() < 4 || bytes.substr(0, 4) != std::string_view("PK\x03\x04", 4)) {
    reader.fail("not a 3MF file (a 3MF package is a zip archive, starting with 'PK')");
  }
  Handle model;
  if (lib3mf().lib3mf_createmodel(model.out()) != LIB3MF_OK)
    throw std::runtime_error("3MF reader: lib3mf_createmodel failed");
  ThreeMfContent content;
  const auto read = [&](std::string_view package) {
    Handle lib_reader;
    reader.check(lib3mf().lib3mf_model_queryreader(model.get(), "3mf", lib_reader.out()), model.get(),
                 "query reader");
    // lib3mf copies the buffer (CImportStream_Memory) and never writes to it.
    auto* data = reinterpret_cast<BYTE*>(const_cast<char*>(package.data()));
    const LIB3MFRESULT result = lib3mf().lib3mf_reader_readfrombuffer(lib_reader.get(), data, package.size());
    return result == LIB3MF_OK ? std::string() : last_error(lib_reader.get());
  };
  // The model parts' components are bounded before lib3mf reads them (it expands them while reading).
  if (const auto entries = zip_entries(bytes)) {
    constexpr std::size_t kMaxScannedPart = std::size_t{1} << 31;
    for (const ZipEntry& entry : *entries) {
      std::string lower = entry.name;
      std::transform(lower.begin(), lower.end(), lower.begin(),
                     [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
      if (lower.size() <= 6 || lower.compare(lower.size() - 6, 6, ".model") != 0) continue;
      if (const auto xml = zip_read(bytes, entry, kMaxScannedPart))
        require_bounded_expansion(*xml, reader, options.max_triangles);
    }
  }
  const std::string error = read(bytes);
  if (!error.empty()) {
    const auto repaired = add_missing_thumbnail(bytes);
    if (!repaired || !read(repaired->first).empty()) reader.fail("not a readable 3MF package: " + error);
    content.warnings.push_back(fmt::format(
        "the package refers to a thumbnail '{}' it does not contain (PrusaSlicer's command line writes such "
        "packages): ignored",
        repaired->second));
  }

  DWORD unit = NMR::MODELUNIT_MILLIMETER;
  reader.check(lib3mf().lib3mf_model_getunit(model.get(), &unit), model.get(), "unit");
  content.unit = unit_name(unit, content.metres_per_unit);

  Handle items;
  reader.check(lib3mf().lib3mf_model_getbuilditems(model.get(), items.out()), model.get(), "build items");
  while (true) {
    BOOL has_next = false;
    reader.check(lib3mf().lib3mf_builditemiterator_movenext(items.get(), &has_next), items.get(),
                 "build items");
    if (!has_next) break;
    Handle item;
    reader.check(lib3mf().lib3mf_builditemiterator_getcurrent(items.get(), item.out()), items.get(),
                 "build item");
    Handle object;
    reader.check(lib3mf().lib3mf_builditem_getobjectresource(item.get(), object.out()), item.get(),
                 "build item object");
    BOOL has_transform = false;
    reader.check(lib3mf().lib3mf_builditem_hasobjecttransform(item.get(), &has_transform), item.get(),
                 "transform");
    Eigen::Affine3d transform = Eigen::Affine3d::Identity();
    if (has_transform) {
      NMR::MODELTRANSFORM t;
      reader.check(lib3mf().lib3mf_builditem_getobjecttransform(item.get(), &t), item.get(), "transform");
      transform = to_affine(t);
    }
    ThreeMfObject body;
    body.name = reader.object_name(object.get());
    DWORD id = 0;
    reader.check(lib3mf().lib3mf_resource_getresourceid(object.get(), &id), object.get(), "object id");
    body.resource_id = id;
    reader.append(object.get(), transform, 0, body.soup);
    content.objects.push_back(std::move(body));
  }
  if (content.objects.empty()) reader.fail("the 3MF build has no items (nothing to make)");
  return content;
}

TriangleSoup merged_soup(const ThreeMfContent& content) {
  TriangleSoup soup;
  for (const ThreeMfObject& object : content.objects) {
    if (soup.vertices.size() + object.soup.vertices.size() > std::numeric_limits<std::uint32_t>::max()) {
      throw InputError("3MF: the objects together have more vertices than a soup can index");
    }
    const auto base = static_cast<std::uint32_t>(soup.vertices.size());
    soup.vertices.insert(soup.vertices.end(), object.soup.vertices.begin(), object.soup.vertices.end());
    for (const auto& t : object.soup.triangles)
      soup.triangles.push_back({t[0] + base, t[1] + base, t[2] + base});
  }
  return soup;
}

}  // namespace fabmesh
