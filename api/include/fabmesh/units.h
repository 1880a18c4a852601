#pragma once
// Units of length: designs say theirs, files record or imply theirs.

#include <string_view>

namespace fabmesh {
namespace api {

/// A unit of length, named as designs and files name it.
enum class Unit { mm, cm, m, inch };

/// "mm", "cm", "m", "in" (inch).
const char* to_string(Unit unit);

/// The unit named `name` ("mm", "cm", "m", "in").
/// \throw InputError ("units") for any other name
Unit unit_named(std::string_view name);

}  // namespace api
#ifndef FABMESH_BUILDING_LIBRARY
using namespace api;  // fabmesh::Unit, ...
#endif
}  // namespace fabmesh
