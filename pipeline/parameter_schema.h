#pragma once
// A design's named parameters as a JSON Schema (draft 2020-12), for web
// forms and shop configurators to be generated from: what `fabmesh params
// --json` prints and the studio's GET /api/design carries as `schema`.

#include <functional>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "io/design/design.h"

namespace fabmesh {

/// The schema of the overrides `design` takes by parameter name (`-D
/// NAME=VALUE`, a batch's columns): an object with one property per declared
/// parameter, in the order declared, none other allowed. Each is a number
/// with the value the design was read with as `default`, its declared range
/// as `minimum` and `maximum`, its step as `multipleOf` when the range
/// starts on a multiple of it (a slider's values from the minimum are then
/// exactly the multiples), and its description. Numbers are written in the
/// shortest form that reads back to the same double: a validator comparing
/// multipleOf must read them as decimals (docs/commands.md, `params`).
/// With parameter sets (`parameter_sets:`), a `parameter_set` property
/// (a string, `enum` the set names, `default` the set used) and `examples`:
/// one object per set, its name and its values as the design resolves them
/// with that set alone, which `with_set` gives (the design read again with
/// `-P NAME` only; its errors, a value out of range, pass out). A set for
/// which `with_set` gives nothing has no example.
nlohmann::ordered_json parameter_schema(
    const Design& design, const std::function<std::optional<Design>(const std::string& set)>& with_set);

}  // namespace fabmesh
