#pragma once
// A design file parsed once and resolved with many override sets: the
// variants of a batch, each with the canonical text its content key hashes.

#include <memory>
#include <string>
#include <vector>

#include "io/design/design.h"
#include "io/design/overrides.h"

namespace fabmesh {

/// A design's canonical text with the values of some root keys left out.
struct BlankedText {
  std::vector<std::string> keys;  ///< plain root keys ("thickness")
  std::string text;               ///< the canonical text, each of their values written as `*`
};

/// A design's YAML text, parsed once. resolve() gives what
/// parse_design(text, path, overrides) gives, without parsing again, and the
/// design's canonical resolved text. Safe to resolve from several threads.
class DesignSource {
 public:
  /// Parses `text`, the content of the design file at `path` (`path` names it
  /// in messages, gives the default name, and is the folder of the files the
  /// design reads). \throw FileError for YAML errors or a root that is not a map
  DesignSource(const std::string& text, std::string path);
  /// Reads the design file at `path` (read_design_text: at most 16 MiB) and parses it. \throw FileError
  static DesignSource read(const std::string& path);
  DesignSource(DesignSource&&) noexcept;
  DesignSource& operator=(DesignSource&&) noexcept;
  ~DesignSource();

  const std::string& path() const;
  /// The design's `name:` as written when it is a plain scalar, else the file's stem.
  std::string name() const;
  /// The names of the design's parameter sets (`parameter_sets:` keys), in
  /// file order; empty when it declares none (a malformed map too: resolving fails on it).
  std::vector<std::string> parameter_set_names() const;

  /// The design with `overrides` applied in order, read and validated as
  /// read_design does (the same errors, naming the overrides).
  /// `canonical`, when given, receives the canonical text of the resolved
  /// design as soon as the overrides are applied (so a variant whose value is
  /// out of range still has one), and is left empty when they cannot be.
  /// The canonical text: maps with sorted keys, scalars verbatim (quoted or
  /// plain), sequences in order; no comments, layout, anchors or file path;
  /// the bytes of every file the design reads (`polyline: {file: ...}`) in
  /// place of its name. Designs with equal canonical texts are equal.
  /// `blanked`, when given, receives that canonical text with the values of
  /// the design's root keys `blanked->keys` left out (`blanked->text`): designs
  /// with equal blanked texts differ at most where those keys' values are read.
  /// \throw FileError naming the file, line, column and field, or the override
  Design resolve(const std::vector<Override>& overrides, std::string* canonical = nullptr,
                 BlankedText* blanked = nullptr) const;

  /// Only the canonical text of the design with `overrides` (see resolve),
  /// without reading it. \throw FileError naming an override that cannot be applied
  std::string canonical(const std::vector<Override>& overrides) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace fabmesh
