#include "pipeline/result.h"

#include <algorithm>

namespace fabmesh {

const char* to_string(PartRole role) {
  switch (role) {
    case PartRole::Product:
      return "product";
    case PartRole::MouldSide:
      return "mould_side";
    case PartRole::MouldBase:
      return "mould_base";
    case PartRole::Piece:
      return "piece";
    case PartRole::Master:
      return "master";
    case PartRole::Case:
      return "case";
  }
  return "product";
}

const Part* product(const Result& result) {
  const auto it = std::find_if(result.parts.begin(), result.parts.end(),
                               [](const Part& p) { return p.role == PartRole::Product; });
  return it == result.parts.end() ? nullptr : &*it;
}

std::vector<const Part*> parts_of(const Result& result, PartRole role) {
  std::vector<const Part*> out;
  for (const Part& p : result.parts) {
    if (p.role == role) out.push_back(&p);
  }
  return out;
}

bool fit(const Result& result) {
  return std::all_of(result.parts.begin(), result.parts.end(), [&](const Part& p) {
    const MeshPurpose purpose = p.role == PartRole::Product ? result.purpose : MeshPurpose::Fabrication;
    return p.validated && fit_for(p.validation, purpose);
  });
}

std::vector<std::string> written_paths(const Result& result) {
  std::vector<std::string> paths;
  paths.reserve(result.files.size());
  for (const OutputFile& f : result.files) paths.push_back(f.path);
  return paths;
}

void append_shares(std::vector<ToleranceShare>& to, const std::string& prefix,
                   const std::vector<ToleranceShare>& shares) {
  for (ToleranceShare s : shares) {
    s.stage = prefix + s.stage;
    to.push_back(std::move(s));
  }
}

}  // namespace fabmesh
