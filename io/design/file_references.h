#pragma once
// The other files a design names (DXF drawings, CSVs of points), found in its
// YAML tree without reading them: what `fabmesh studio` checks an override
// against before anything is read, so that a request cannot make it read a
// file the design does not name (docs/studio.md, "Security").

#include <string>
#include <vector>

#include "io/design/overrides.h"

namespace fabmesh {

/// One file a design names.
struct FileReference {
  std::string key;  ///< its -D path: "outline.dxf", "holes[1].dxf", "profile.segments[0].polyline.file"
  std::string
      file;  ///< the file, as the reader opens it: absolute (from the design's folder), lexically normal
};

/// Every value of a file key (io/design/yaml/file_keys.h: `polyline.file`,
/// `outline.dxf`, `holes[i].dxf`) in the design `text` of file `path`, after
/// the overrides are put in its tree. Reads no file: not those named, nor
/// `path`. \throw FileError as read_design for text that is not a design's
/// YAML or an override that does not apply
std::vector<FileReference> file_references(const std::string& text, const std::string& path,
                                           const std::vector<Override>& overrides = {});

}  // namespace fabmesh
