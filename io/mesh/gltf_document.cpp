#include "io/mesh/gltf_document.h"

#include <fmt/format.h>

#include <algorithm>
#include <cstring>

#include "geometry/core/errors.h"

namespace fabmesh {
namespace {

using Json = nlohmann::json;

constexpr std::uint32_t kJsonChunk = 0x4E4F534Au;
constexpr std::uint32_t kBinChunk = 0x004E4942u;

std::uint32_t u32_at(std::string_view b, std::size_t at) {
  std::uint32_t v = 0;
  for (int i = 0; i < 4; ++i) v |= std::uint32_t{static_cast<unsigned char>(b[at + i])} << (8 * i);
  return v;
}

std::size_t component_size(int type) {
  switch (type) {
    case kGltfByte:
    case kGltfUnsignedByte:
      return 1;
    case kGltfShort:
    case kGltfUnsignedShort:
      return 2;
    case kGltfUnsignedInt:
    case kGltfFloat:
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
    case kGltfByte: {
      const auto v = static_cast<std::int8_t>(u);
      return normalized ? std::max(v / 127.0, -1.0) : v;
    }
    case kGltfUnsignedByte:
      return normalized ? u / 255.0 : u;
    case kGltfShort: {
      const auto v = static_cast<std::int16_t>(u);
      return normalized ? std::max(v / 32767.0, -1.0) : v;
    }
    case kGltfUnsignedShort:
      return normalized ? u / 65535.0 : u;
    case kGltfUnsignedInt:
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

/// Stores element `i` at `p` into out.values.
void store(GltfAccessorValues& out, std::size_t i, const unsigned char* p, int component_type,
           std::size_t components, bool normalized) {
  for (std::size_t k = 0; k < components; ++k) {
    out.values[i * components + k] =
        component_at(p + k * component_size(component_type), component_type, normalized);
  }
}

/// Calls take(i, pointer to element i) for elements that require_fit accepted.
template <typename Take>
void for_each_element(std::string_view bytes, std::uint64_t offset, std::size_t stride, std::size_t count,
                      Take&& take) {
  const auto* base = reinterpret_cast<const unsigned char*>(bytes.data()) + offset;
  for (std::size_t i = 0; i < count; ++i) take(i, base + i * stride);
}

}  // namespace

GltfDocument::GltfDocument(std::string_view bytes, const std::string& name) : name_(name) {
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
  load_buffers();
  size_ = bytes.size();
  for (const std::string& d : decoded_) size_ += d.size();
}

void GltfDocument::fail(const std::string& message) const {
  throw FileError(name_, 0, 0, fmt::format("{}: {}", name_, message));
}

/// Checks the GLB header and chunks; returns the JSON chunk, keeps the BIN chunk.
std::string_view GltfDocument::split_glb(std::string_view b) {
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

const GltfDocument::Json& GltfDocument::array(const Json& o, const char* key,
                                              const std::string& where) const {
  static const Json empty_array = Json::array();  // immutable
  const auto it = o.find(key);
  if (it == o.end()) return empty_array;
  if (!it->is_array()) fail(fmt::format("{}{} is not an array", where, key));
  return *it;
}

std::optional<std::uint64_t> GltfDocument::optional_uint(const Json& o, const char* key,
                                                         const std::string& where) const {
  const auto it = o.find(key);
  if (it == o.end()) return std::nullopt;
  if (!it->is_number_unsigned())
    fail(fmt::format("{}.{} = {} is not a non-negative integer", where, key, it->dump()));
  return it->get<std::uint64_t>();
}

std::uint64_t GltfDocument::required_uint(const Json& o, const char* key, const std::string& where) const {
  const auto v = optional_uint(o, key, where);
  if (!v) fail(fmt::format("{} has no {}", where, key));
  return *v;
}

/// doc_[kind][i] as an object; fails naming `kind`[i] when absent.
const GltfDocument::Json& GltfDocument::element(const char* kind, std::uint64_t i) const {
  const Json& all = array(doc_, kind, "");
  if (i >= all.size())
    fail(fmt::format("{}[{}] is referred to but there are {} {}", kind, i, all.size(), kind));
  if (!all[i].is_object()) fail(fmt::format("{}[{}] is not an object", kind, i));
  return all[i];
}

void GltfDocument::load_buffers() {
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
        fail(
            fmt::format("{} is in the external file '{}': fabmesh reads only self-contained glTF (a .glb, or "
                        "a .gltf whose buffers are data: URIs) and never opens other files",
                        where, text.substr(0, 200)));
      }
      if (text.substr(0, comma).find(";base64") == std::string::npos)
        fail(where + " is a data: URI but not base64");
      if (!decode_base64(std::string_view(text).substr(comma + 1), decoded_[i])) fail(where + ": bad base64");
      data = decoded_[i];
    }
    if (length > data.size()) {
      fail(fmt::format("{}.byteLength = {} but it holds {} bytes", where, length, data.size()));
    }
    buffers_.push_back(data.substr(0, length));
  }
}

/// The bytes of bufferView `index` and its stride (0: tightly packed).
std::string_view GltfDocument::view(std::uint64_t index, std::size_t& stride) const {
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

/// Fails unless `count` elements of `element_size` bytes, `stride` apart
/// from `offset`, fit in `bytes`.
void GltfDocument::require_fit(std::string_view bytes, std::uint64_t offset, std::size_t stride,
                               std::size_t count, std::size_t element_size, const std::string& where) const {
  if (offset > bytes.size() || element_size > bytes.size() - offset ||
      (count > 1 && (count - 1) > (bytes.size() - offset - element_size) / stride)) {
    fail(fmt::format(
        "{}: {} elements of {} bytes (stride {}) from offset {} do not fit its {}-byte bufferView", where,
        count, element_size, stride, offset, bytes.size()));
  }
}

GltfAccessorValues GltfDocument::accessor(std::uint64_t index, const GltfAccessorRequest& request) const {
  const std::string where = fmt::format("accessors[{}]", index);
  const Json& a = element("accessors", index);
  const std::uint64_t count = required_uint(a, "count", where);
  const std::uint64_t component_type = required_uint(a, "componentType", where);
  const auto t = a.find("type");
  if (t == a.end() || !t->is_string() || *t != request.type) {
    fail(fmt::format("{}.type must be {}", where, request.type));
  }
  const std::vector<int>& allowed = request.component_types;
  if (std::find(allowed.begin(), allowed.end(), static_cast<int>(component_type)) == allowed.end()) {
    fail(fmt::format("{}.componentType = {} is not allowed here", where, component_type));
  }
  const auto normalized_it = a.find("normalized");
  const bool normalized =
      normalized_it != a.end() && normalized_it->is_boolean() && normalized_it->get<bool>();
  if (normalized && (!request.allow_normalized || component_type == kGltfFloat)) {
    fail(where + " must not be normalized");
  }
  if (count == 0) fail(where + ".count is 0");
  if (count > request.max_count) fail(fmt::format("{}.count = {} exceeds the reader's budget", where, count));
  const auto view_index = optional_uint(a, "bufferView", where);
  // Without a bufferView the elements are zeros no byte of the file carries: bound them by the file's
  // size, as every reader bounds a declared count by the bytes behind it.
  if (!view_index && count > size_) {
    fail(
        fmt::format("{}.count = {} without a bufferView: more elements than the {} bytes of the file could "
                    "describe",
                    where, count, size_));
  }
  const int ct = static_cast<int>(component_type);
  const std::size_t components = request.components;
  const std::size_t element_size = components * component_size(ct);
  std::string_view bytes;
  std::size_t stride = 0;
  const std::uint64_t offset = optional_uint(a, "byteOffset", where).value_or(0);
  if (view_index) {
    bytes = view(*view_index, stride);
    if (stride != 0 && stride < element_size) {
      fail(fmt::format("{}: bufferView stride {} < element size {}", where, stride, element_size));
    }
    if (stride == 0) stride = element_size;
    require_fit(bytes, offset, stride, count, element_size, where);
  }
  GltfAccessorValues out;
  out.count = count;
  out.values.assign(count * components, 0.0);  // no bufferView: zeros (then sparse)
  if (view_index) {
    for_each_element(bytes, offset, stride, count, [&](std::size_t i, const unsigned char* p) {
      store(out, i, p, ct, components, normalized);
    });
  }
  if (a.contains("sparse")) apply_sparse(a["sparse"], where + ".sparse", out, ct, components, normalized);
  return out;
}

void GltfDocument::apply_sparse(const Json& s, const std::string& where, GltfAccessorValues& out,
                                int component_type, std::size_t components, bool normalized) const {
  if (!s.is_object() || !s.contains("indices") || !s.contains("values")) fail(where + " is malformed");
  const std::uint64_t count = required_uint(s, "count", where);
  if (count == 0 || count > out.count)
    fail(fmt::format("{}.count = {} is not in [1, {}]", where, count, out.count));
  const Json& indices = s["indices"];
  const Json& values = s["values"];
  if (!indices.is_object() || !values.is_object()) fail(where + " is malformed");
  const int it = static_cast<int>(required_uint(indices, "componentType", where + ".indices"));
  if (it != kGltfUnsignedByte && it != kGltfUnsignedShort && it != kGltfUnsignedInt) {
    fail(where + ".indices: bad componentType");
  }
  std::size_t stride = 0;
  const std::string_view index_bytes = view(required_uint(indices, "bufferView", where + ".indices"), stride);
  const std::uint64_t index_offset = optional_uint(indices, "byteOffset", where + ".indices").value_or(0);
  require_fit(index_bytes, index_offset, component_size(it), count, component_size(it), where + ".indices");
  const std::size_t element_size = components * component_size(component_type);
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
                   [&](std::size_t i, const unsigned char* p) {
                     store(out, targets[i], p, component_type, components, normalized);
                   });
}

}  // namespace fabmesh
