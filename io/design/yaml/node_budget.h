#pragma once
// A bound on the size of a YAML tree, checked before yaml-cpp builds it.
// yaml-cpp spends about 470 bytes per node (scalar, list or map), so a small
// file of short values ("0,0,0,...") becomes a tree hundreds of times its
// size; counting the nodes with the event parser first (memory proportional
// to the nesting depth) keeps a design's memory proportional to its content.
// Private to io/design.

#include <cstddef>
#include <string>

namespace fabmesh::yaml {

/// The deepest nesting of lists and maps a design may have (its own deepest
/// is a handful of levels); beyond it yaml-cpp's own guard would say only
/// "bad file".
inline constexpr std::size_t kMaxYamlDepth = 64;

/// Throws FileError unless the YAML `text` holds at most `max_nodes` nodes
/// (scalars, lists and maps, keys included, in every document), each alias
/// counted as the nodes of what it stands for (so aliases cannot multiply a
/// small file into a huge tree), and no alias stands for a node that contains
/// it, and lists and maps are nested at most kMaxYamlDepth deep. The message starts "path:line:column:" where
/// the count passed the limit (or at the alias), or "-D TEXT:" when `override_text` is given (the text is
/// then an override's value). \throw FileError; YAML::Exception for text that is not YAML
void require_node_budget(const std::string& text, const std::string& path, std::size_t max_nodes,
                         const std::string& override_text = "");

}  // namespace fabmesh::yaml
