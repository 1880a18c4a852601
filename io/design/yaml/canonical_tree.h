#pragma once
// The canonical text of a resolved design tree: what a batch variant's
// content key hashes (io/design/design_source.h). Private to io/design.

#include <yaml-cpp/yaml.h>

#include <string>
#include <vector>

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

/// canonical_tree, and `blanked` receives the same text with the value of
/// each entry of the root map whose plain key is in `blank` written as `*`
/// (a key that is absent stays absent). Two trees with the same blanked text
/// read into designs that differ at most where those keys' values are read.
std::string canonical_tree(const YAML::Node& root, const std::string& path, const std::string& design_folder,
                           const std::vector<std::string>& blank, std::string& blanked);

}  // namespace fabmesh::yaml
