#include "pipeline/load_design.h"

#include "io/design/read_design.h"
#include "pipeline/output_table.h"

namespace fabmesh {

Design load_design(const std::string& path, const std::vector<Override>& overrides) {
  Design design = read_design(path, overrides);
  resolve_outputs(design);
  return design;
}

Design load_design_text(const std::string& yaml_text, const std::string& path,
                        const std::vector<Override>& overrides) {
  Design design = parse_design(yaml_text, path, overrides);
  resolve_outputs(design);
  return design;
}

std::vector<Override> parse_overrides(const std::vector<std::string>& texts) {
  std::vector<Override> out;
  out.reserve(texts.size());
  for (const std::string& t : texts) out.push_back(parse_override(t));
  return out;
}

}  // namespace fabmesh
