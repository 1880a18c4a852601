#include "pipeline/load_design.h"

#include "io/design/read_design.h"
#include "pipeline/outputs.h"

namespace fabmesh {

Design load_design(const std::string& path) {
  Design design = read_design(path);
  resolve_outputs(design);
  return design;
}

}  // namespace fabmesh
