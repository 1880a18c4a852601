#include "io/mesh/draco.h"

#include <draco/compression/decode.h>
#include <draco/compression/encode.h>
#include <draco/mesh/mesh.h>
#include <fmt/format.h>

#include <cmath>
#include <limits>

#include "geometry/core/errors.h"
#include "io/file.h"

namespace fabmesh {
namespace {

[[noreturn]] void fail(const std::string& name, const std::string& message) {
  throw FileError(name, 0, 0, fmt::format("{}: {}", name, message));
}

void bounding_box(const TriangleSoup& soup, Vec3& lo, Vec3& hi) {
  lo = Vec3::Zero();
  hi = Vec3::Zero();
  if (soup.vertices.empty()) return;
  lo = hi = soup.vertices.front();
  for (const Vec3& p : soup.vertices) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
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

TriangleSoup parse_draco(std::string_view bytes, const std::string& name) {
  draco::DecoderBuffer buffer;
  buffer.Init(bytes.data(), bytes.size());
  const auto type = draco::Decoder::GetEncodedGeometryType(&buffer);
  if (!type.ok()) fail(name, fmt::format("not a Draco file: {}", type.status().error_msg_string()));
  if (type.value() != draco::TRIANGULAR_MESH) fail(name, "the Draco file holds a point cloud, not a mesh");
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

std::string encode_draco(const TriangleSoup& soup, const DracoOptions& options) {
  require_indices_in_range(soup);
  Vec3 lo;
  Vec3 hi;
  bounding_box(soup, lo, hi);
  const DracoQuantization q = draco_quantization(lo, hi, options.tolerance);

  draco::Mesh mesh;
  const auto np = static_cast<draco::PointIndex::ValueType>(soup.vertices.size());
  mesh.set_num_points(np);
  draco::GeometryAttribute attribute;
  attribute.Init(draco::GeometryAttribute::POSITION, nullptr, 3, draco::DT_FLOAT32, false, sizeof(float) * 3,
                 0);
  const int id = mesh.AddAttribute(attribute, true, np);
  draco::PointAttribute* position = mesh.attribute(id);
  for (draco::PointIndex::ValueType i = 0; i < np; ++i) {
    const Vec3& p = soup.vertices[i];
    const float xyz[3] = {static_cast<float>(p.x()), static_cast<float>(p.y()), static_cast<float>(p.z())};
    position->SetAttributeValue(draco::AttributeValueIndex(i), xyz);
  }
  for (const auto& t : soup.triangles) {
    mesh.AddFace({draco::PointIndex(t[0]), draco::PointIndex(t[1]), draco::PointIndex(t[2])});
  }
  draco::Encoder encoder;
  encoder.SetAttributeQuantization(draco::GeometryAttribute::POSITION, q.bits);
  encoder.SetSpeedOptions(options.encoding_speed, options.decoding_speed);
  draco::EncoderBuffer buffer;
  const draco::Status status = encoder.EncodeMeshToBuffer(mesh, &buffer);
  if (!status.ok()) throw InputError(fmt::format("Draco encoder: {}", status.error_msg_string()));
  return std::string(buffer.data(), buffer.size());
}

std::string encode_draco_accepted(const TriangleSoup& soup, const DracoOptions& options,
                                  const std::function<bool(const TriangleSoup& decoded)>& accept,
                                  const std::string& what) {
  DracoOptions attempt = options;
  for (int extra_bits = 0; extra_bits < 24; ++extra_bits) {
    std::string bytes = encode_draco(soup, attempt);
    if (accept(parse_draco(bytes, what))) return bytes;
    attempt.tolerance *= 0.5;  // one more bit of quantization
  }
  throw ValidationFailed(what + ": no Draco quantization keeps the decoded mesh valid");
}

void write_draco(const TriangleSoup& soup, const std::string& path, const DracoOptions& options) {
  write_file_atomically(path, encode_draco(soup, options));
}

void write_draco(const Mesh& mesh, const std::string& path, const DracoOptions& options) {
  write_draco(to_soup(mesh), path, options);
}

}  // namespace fabmesh
