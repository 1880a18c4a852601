// The library's enums as Python enums whose members are also texts
// (`class Unit(str, Enum)`): fabmesh.Unit.mm == "mm", so code that compared
// the texts of 0.3 keeps working.

#include <string>
#include <utility>
#include <vector>

#include "python/bind.h"

namespace fabmesh_python {
namespace {

// Adds `name` to the module: an enum of str whose members are (member name, value).
void add_text_enum(py::module_& m, const char* name,
                   const std::vector<std::pair<std::string, std::string>>& members, const char* doc) {
  py::list pairs;
  for (const auto& [member, value] : members) pairs.append(py::make_tuple(member, value));
  const py::object builtins = py::module_::import("builtins");
  py::object cls = py::module_::import("enum").attr("Enum")(name, pairs, py::arg("module") = "fabmesh",
                                                            py::arg("type") = builtins.attr("str"));
  cls.attr("__doc__") = doc;
  m.add_object(name, cls);
}

}  // namespace

void bind_enums(py::module_& m) {
  std::vector<std::pair<std::string, std::string>> units;
  for (const fabmesh::Unit u : {fabmesh::Unit::mm, fabmesh::Unit::cm, fabmesh::Unit::m, fabmesh::Unit::inch})
    units.emplace_back(u == fabmesh::Unit::inch ? "inch" : fabmesh::to_string(u), fabmesh::to_string(u));
  add_text_enum(m, "Unit", units, "A unit of length: mm, cm, m, inch (value 'in').");
  std::vector<std::pair<std::string, std::string>> defects;
  for (int k = 0; k <= static_cast<int>(fabmesh::DefectKind::SelfIntersection); ++k) {
    const char* key = fabmesh::to_string(static_cast<fabmesh::DefectKind>(k));
    defects.emplace_back(key, key);
  }
  add_text_enum(m, "DefectKind", defects,
                "A kind of defect a mesh can have (docs/validity.md), named as the JSON reports name it.");
  std::vector<std::pair<std::string, std::string>> roles;
  for (const fabmesh::PartRole r :
       {fabmesh::PartRole::Product, fabmesh::PartRole::MouldSide, fabmesh::PartRole::MouldBase,
        fabmesh::PartRole::Piece, fabmesh::PartRole::Master, fabmesh::PartRole::Case})
    roles.emplace_back(fabmesh::to_string(r), fabmesh::to_string(r));
  add_text_enum(m, "PartRole", roles,
                "What a part of a Result is: the design's own mesh (product), a mould's side or base part, a "
                "kitchen's piece, a vessel's casting master, a mould part's casting case.");
}

}  // namespace fabmesh_python
