#pragma once
// A glTF 2.0 document (.glb or .gltf) with checked access to its JSON and
// binary data, for parse_gltf. Every index, offset, stride and count taken
// from the file is checked against what the bytes hold before it is used.
// No file or network access: buffers must be in the bytes (GLB BIN chunk or
// base64 data: URIs).

#include <cstddef>
#include <cstdint>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace fabmesh {

/// glTF accessor component types (accessor.componentType).
inline constexpr int kGltfByte = 5120;
inline constexpr int kGltfUnsignedByte = 5121;
inline constexpr int kGltfShort = 5122;
inline constexpr int kGltfUnsignedShort = 5123;
inline constexpr int kGltfUnsignedInt = 5125;
inline constexpr int kGltfFloat = 5126;

/// An accessor's elements as doubles: count x components, row-major.
struct GltfAccessorValues {
  std::vector<double> values;
  std::size_t count = 0;
};

/// What an accessor must be for its use (POSITION, indices).
struct GltfAccessorRequest {
  const char* type = "VEC3";         ///< glTF accessor type: "SCALAR", "VEC3"
  std::size_t components = 3;        ///< of that type
  std::vector<int> component_types;  ///< allowed kGltf* component types
  bool allow_normalized = false;
  std::size_t max_count = 0;  ///< budget, checked before anything is allocated
};

/// The JSON and buffers of one glTF document.
class GltfDocument {
 public:
  using Json = nlohmann::json;

  /// Splits a GLB (header and chunks checked) or takes the bytes as .gltf
  /// JSON, parses it, requires asset.version 2.x and decodes every buffer.
  /// \param name the path, for messages
  /// \throw FileError naming `name` for anything malformed, and for a buffer
  /// in an external file.
  GltfDocument(std::string_view bytes, const std::string& name);

  /// Throws FileError(name, "name: message").
  [[noreturn]] void fail(const std::string& message) const;

  const Json& root() const { return doc_; }
  const std::string& name() const { return name_; }

  /// o[key] as an array (an empty one when absent). `where` prefixes messages.
  const Json& array(const Json& o, const char* key, const std::string& where) const;
  /// o[key] as a non-negative integer, nullopt when absent.
  std::optional<std::uint64_t> optional_uint(const Json& o, const char* key, const std::string& where) const;
  /// o[key] as a non-negative integer; fails when absent.
  std::uint64_t required_uint(const Json& o, const char* key, const std::string& where) const;
  /// root[kind][i] as an object (kind: "nodes", "meshes", ...); fails when absent.
  const Json& element(const char* kind, std::uint64_t i) const;

  /// The bytes of bufferView `index`, and its byteStride (0: tightly packed).
  std::string_view view(std::uint64_t index, std::size_t& stride) const;

  /// Accessor `index` read as numbers (normalized integers mapped to [-1, 1]
  /// or [0, 1] as glTF specifies), sparse substitution applied; an accessor
  /// without bufferView starts from zeros. Its count is checked against
  /// request.max_count and, without a bufferView (no byte of the file behind
  /// its elements), against the document's size in bytes, before anything is
  /// allocated: a few bytes of JSON cannot declare gigabytes of zeros.
  GltfAccessorValues accessor(std::uint64_t index, const GltfAccessorRequest& request) const;

 private:
  std::string_view split_glb(std::string_view bytes);
  void load_buffers();
  void require_fit(std::string_view bytes, std::uint64_t offset, std::size_t stride, std::size_t count,
                   std::size_t element_size, const std::string& where) const;
  void apply_sparse(const Json& sparse, const std::string& where, GltfAccessorValues& out, int component_type,
                    std::size_t components, bool normalized) const;

  const std::string& name_;
  Json doc_;
  std::string_view bin_;
  bool has_bin_ = false;
  std::vector<std::string> decoded_;       ///< payloads of data: URIs
  std::vector<std::string_view> buffers_;  ///< every buffer's bytes (BIN chunk or decoded_)
  std::size_t size_ = 0;                   ///< bytes of the file and of its decoded data: URIs
};

}  // namespace fabmesh
