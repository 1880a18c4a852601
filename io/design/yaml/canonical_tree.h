#pragma once
// The canonical text of a resolved design tree: what a batch variant's
// content key hashes (io/design/design_source.h). Private to io/design.

#include <yaml-cpp/yaml.h>

#include <string>

namespace fabmesh::yaml {

/// The canonical text of `root`: maps with their keys sorted, sequences in
/// order, scalars verbatim (quoted or plain, with any explicit tag), no
/// comments, layout or anchors; the file a `polyline: {file: NAME}` reads
/// (NAME relative to `design_folder` unless absolute) is replaced by the
/// file's bytes, its name left out. Two trees with the same canonical text
/// read into the same design; an unreadable file is marked as such.
/// \throw FileError (naming `path`) when the text would exceed 256 MiB (a design
/// that expands through YAML aliases)
std::string canonical_tree(const YAML::Node& root, const std::string& path, const std::string& design_folder);

}  // namespace fabmesh::yaml
