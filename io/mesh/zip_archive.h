#pragma once
// The little of the zip format that 3MF handling needs besides lib3mf:
// listing a package's parts, reading a small one, and adding a stored part.

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace fabmesh {

/// One entry of a zip archive's central directory.
struct ZipEntry {
  std::string name;
  std::uint16_t method = 0;  ///< 0 stored, 8 deflated
  std::uint32_t crc32 = 0;
  std::uint64_t compressed_size = 0;
  std::uint64_t uncompressed_size = 0;
  std::uint64_t local_header_offset = 0;
};

/// The central directory of a zip archive (zip64 records understood), or
/// nullopt when `bytes` is not a zip archive whose directory lies within it.
std::optional<std::vector<ZipEntry>> zip_entries(std::string_view bytes);

/// The content of `entry` (stored or deflated), or nullopt when it does not
/// fit the archive, is larger than `max_size`, uses another method, or its
/// data is corrupt (size or CRC mismatch).
std::optional<std::string> zip_read(std::string_view bytes, const ZipEntry& entry, std::size_t max_size);

/// `bytes` with a stored entry `name` holding `data` added, or nullopt when
/// the archive is zip64 or not a zip archive. The other entries are kept
/// byte for byte.
std::optional<std::string> zip_append_stored(std::string_view bytes, const std::string& name,
                                             std::string_view data);

/// A new zip archive holding `entries` (name, content) stored uncompressed,
/// in order, with no timestamps. \throw InputError when a name or the
/// archive is too large for a plain (not zip64) archive.
std::string zip_stored(const std::vector<std::pair<std::string, std::string>>& entries);

}  // namespace fabmesh
