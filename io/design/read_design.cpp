#include "io/design/read_design.h"

#include <fmt/format.h>

#include <filesystem>
#include <type_traits>
#include <utility>

#include "io/design/yaml/fields.h"
#include "io/design/yaml/read_countertop.h"
#include "io/design/yaml/read_curve.h"
#include "io/design/yaml/read_surface.h"
#include "io/design/yaml/read_vessel.h"
#include "io/file.h"

namespace fabmesh {
namespace {

constexpr std::size_t kMaxDesignBytes = 64u << 20;

template <class Body>
struct KindTag {};

// One reader per kind: a DesignBody alternative without one does not compile.
CurveDesign read_kind(KindTag<CurveDesign>, const yaml::Fields& f, const YAML::Node& root) {
  return CurveDesign{read_curve(f, f.required(root, "curve", "curve"), "curve")};
}
VesselDesign read_kind(KindTag<VesselDesign>, const yaml::Fields& f, const YAML::Node& root) {
  return read_vessel(f, root);
}
CountertopDesign read_kind(KindTag<CountertopDesign>, const yaml::Fields& f, const YAML::Node& root) {
  return read_countertop(f, root);
}
SurfaceDesign read_kind(KindTag<SurfaceDesign>, const yaml::Fields& f, const YAML::Node& root) {
  return read_surface(f, root);
}

// The alternative of DesignBody whose kKind is `kind`, read from `root`.
template <std::size_t I = 0>
DesignBody read_body(const std::string& kind, const yaml::Fields& f, const YAML::Node& root) {
  if constexpr (I == std::variant_size_v<DesignBody>) {
    std::string names;
    for (const std::string& n : kind_names()) names += (names.empty() ? "" : ", ") + n;
    f.fail(root["kind"], "kind", fmt::format("'{}' is not one of: {}", kind, names));
  } else {
    using Body = std::variant_alternative_t<I, DesignBody>;
    if (kind != Body::kKind) return read_body<I + 1>(kind, f, root);
    f.require_map(root, "", key_group(Body::kKind));
    return read_kind(KindTag<Body>{}, f, root);
  }
}

DesignCommon read_common(const yaml::Fields& f, const YAML::Node& root) {
  DesignCommon c;
  c.path = f.path();
  c.name = f.text_or(root, "name", "name", std::filesystem::path(f.path()).stem().string());
  c.units = f.choice(root["units"].IsDefined() ? root["units"] : YAML::Node("mm"), "units",
                     {"mm", "cm", "m", "in"});
  c.tolerance = f.number_or(root, "tolerance", "tolerance", 0.01);
  if (c.tolerance <= 0.0)
    f.fail(root["tolerance"], "tolerance", fmt::format("tolerance = {:g} must be > 0", c.tolerance));
  if (root["outputs"].IsDefined()) {
    const YAML::Node outs = root["outputs"];
    f.require_list(outs, "outputs", 1);
    for (std::size_t i = 0; i < outs.size(); ++i) {
      const std::string field = fmt::format("outputs[{}]", i);
      const YAML::Mark m = outs[i].Mark();
      c.outputs.push_back({f.text(outs[i], field), f.label(outs[i], field), m.line + 1, m.column + 1});
    }
  }
  return c;
}

}  // namespace

Design parse_design(const std::string& text, const std::string& path) {
  const yaml::Fields f(path);
  YAML::Node root;
  try {
    std::vector<YAML::Node> documents = YAML::LoadAll(text);
    if (documents.size() > 1) {
      const YAML::Mark m = documents[1].Mark();
      throw FileError(path, m.line + 1, m.column + 1,
                      fmt::format("{}:{}:{}: a design file holds one YAML document; a second one starts here",
                                  path, m.line + 1, m.column + 1));
    }
    if (!documents.empty()) root = documents.front();
  } catch (const YAML::Exception& e) {
    throw FileError(
        path, e.mark.line + 1, e.mark.column + 1,
        fmt::format("{}:{}:{}: invalid YAML: {}", path, e.mark.line + 1, e.mark.column + 1, e.msg));
  }
  if (!root.IsMap()) throw FileError(path, 0, 0, fmt::format("{}: a design file must be a YAML map", path));
  const std::string kind = f.text(f.required(root, "kind", "kind"), "kind");
  Design d;
  d.common = read_common(f, root);
  d.body = read_body(kind, f, root);
  return d;
}

Design read_design(const std::string& path) {
  return parse_design(read_file(path, kMaxDesignBytes, "design file"), path);
}

}  // namespace fabmesh
