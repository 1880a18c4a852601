#include "io/mesh/zip_archive.h"

#include <zlib.h>

#include <limits>

#include "geometry/core/errors.h"

namespace fabmesh {
namespace {

constexpr std::string_view kLocalHeader("PK\x03\x04", 4);
constexpr std::string_view kCentralHeader("PK\x01\x02", 4);
constexpr std::string_view kEndOfDirectory("PK\x05\x06", 4);
constexpr std::string_view kZip64Locator("PK\x06\x07", 4);
constexpr std::string_view kZip64End("PK\x06\x06", 4);

std::uint64_t le(std::string_view b, std::size_t at, int bytes) {
  std::uint64_t v = 0;
  for (int i = 0; i < bytes; ++i) v |= std::uint64_t{static_cast<unsigned char>(b[at + i])} << (8 * i);
  return v;
}

void put(std::string& out, std::uint64_t v, int bytes) {
  for (int i = 0; i < bytes; ++i) out.push_back(static_cast<char>((v >> (8 * i)) & 0xffu));
}

/// The end-of-central-directory record: 22 bytes and a comment of up to 65535, at the end.
std::optional<std::size_t> find_end_of_directory(std::string_view b) {
  if (b.size() < 22) return std::nullopt;
  const std::size_t earliest = b.size() > 22 + 0xffff ? b.size() - 22 - 0xffff : 0;
  for (std::size_t at = b.size() - 22;; --at) {
    if (b.substr(at, 4) == kEndOfDirectory && at + 22 + le(b, at + 20, 2) == b.size()) return at;
    if (at == earliest) return std::nullopt;
  }
}

struct Directory {
  std::size_t end = 0;       ///< offset of the end-of-central-directory record
  std::uint64_t offset = 0;  ///< of the central directory
  std::uint64_t size = 0;    ///< of the central directory, bytes
  std::uint64_t entries = 0;
  bool zip64 = false;
};

std::optional<Directory> directory(std::string_view b) {
  if (b.substr(0, 4) != kLocalHeader) return std::nullopt;
  const auto end = find_end_of_directory(b);
  if (!end) return std::nullopt;
  Directory d;
  d.end = *end;
  d.entries = le(b, *end + 10, 2);
  d.size = le(b, *end + 12, 4);
  d.offset = le(b, *end + 16, 4);
  if ((d.offset == 0xffffffffu || d.entries == 0xffffu || d.size == 0xffffffffu) && *end >= 20 &&
      b.substr(*end - 20, 4) == kZip64Locator) {
    const std::uint64_t record = le(b, *end - 20 + 8, 8);
    if (record > b.size() || b.size() - record < 56 || b.substr(record, 4) != kZip64End) return std::nullopt;
    d.entries = le(b, record + 32, 8);
    d.size = le(b, record + 40, 8);
    d.offset = le(b, record + 48, 8);
    d.zip64 = true;
  }
  if (d.offset > b.size() || d.size > b.size() - d.offset) return std::nullopt;
  return d;
}

/// Replaces the 0xffffffff fields of `e` from its zip64 extra field.
bool read_zip64_extra(std::string_view extra, ZipEntry& e, bool u, bool c, bool o) {
  for (std::size_t at = 0; at + 4 <= extra.size();) {
    const std::uint64_t id = le(extra, at, 2);
    const std::uint64_t size = le(extra, at + 2, 2);
    if (size > extra.size() - at - 4) return false;
    if (id == 1) {
      std::size_t k = at + 4;
      for (auto [wanted, field] :
           {std::pair{u, &e.uncompressed_size}, {c, &e.compressed_size}, {o, &e.local_header_offset}}) {
        if (!wanted) continue;
        if (k + 8 > at + 4 + size) return false;
        *field = le(extra, k, 8);
        k += 8;
      }
      return true;
    }
    at += 4 + size;
  }
  return !(u || c || o);
}

/// The local header and data of a stored entry, and its central directory
/// record for a local header at `local_offset`.
std::pair<std::string, std::string> stored_entry(const std::string& name, std::string_view data,
                                                 std::uint64_t local_offset) {
  const auto crc = static_cast<std::uint32_t>(
      crc32(0L, reinterpret_cast<const Bytef*>(data.data()), static_cast<uInt>(data.size())));
  std::string local;
  local += kLocalHeader;
  put(local, 20, 2);  // version needed: 2.0
  put(local, 0, 2);   // flags
  put(local, 0, 2);   // stored
  put(local, 0, 4);   // time and date: none, as lib3mf writes
  put(local, crc, 4);
  put(local, data.size(), 4);
  put(local, data.size(), 4);
  put(local, name.size(), 2);
  put(local, 0, 2);
  local += name;
  local += data;
  std::string central;
  central += kCentralHeader;
  put(central, 20, 2);             // version made by
  central += local.substr(4, 26);  // version needed .. extra length, as in the local header
  put(central, 0, 2);              // comment length
  put(central, 0, 2);              // disk
  put(central, 0, 2);              // internal attributes
  put(central, 0, 4);              // external attributes
  put(central, local_offset, 4);
  central += name;
  return {std::move(local), std::move(central)};
}

}  // namespace

std::optional<std::vector<ZipEntry>> zip_entries(std::string_view b) {
  const auto d = directory(b);
  if (!d) return std::nullopt;
  std::vector<ZipEntry> entries;
  std::uint64_t at = d->offset;
  const std::uint64_t end = d->offset + d->size;
  for (std::uint64_t n = 0; n < d->entries; ++n) {
    if (end - at < 46 || b.substr(at, 4) != kCentralHeader) return std::nullopt;
    const std::uint64_t name_length = le(b, at + 28, 2);
    const std::uint64_t extra_length = le(b, at + 30, 2);
    const std::uint64_t comment_length = le(b, at + 32, 2);
    if (end - at - 46 < name_length + extra_length + comment_length) return std::nullopt;
    ZipEntry e;
    e.method = static_cast<std::uint16_t>(le(b, at + 10, 2));
    e.crc32 = static_cast<std::uint32_t>(le(b, at + 16, 4));
    e.compressed_size = le(b, at + 20, 4);
    e.uncompressed_size = le(b, at + 24, 4);
    e.local_header_offset = le(b, at + 42, 4);
    e.name = std::string(b.substr(at + 46, name_length));
    if (!read_zip64_extra(b.substr(at + 46 + name_length, extra_length), e,
                          e.uncompressed_size == 0xffffffffu, e.compressed_size == 0xffffffffu,
                          e.local_header_offset == 0xffffffffu)) {
      return std::nullopt;
    }
    entries.push_back(std::move(e));
    at += 46 + name_length + extra_length + comment_length;
  }
  return entries;
}

std::optional<std::string> zip_read(std::string_view b, const ZipEntry& e, std::size_t max_size) {
  if (e.uncompressed_size > max_size) return std::nullopt;
  const std::uint64_t h = e.local_header_offset;
  if (h > b.size() || b.size() - h < 30 || b.substr(h, 4) != kLocalHeader) return std::nullopt;
  const std::uint64_t data = h + 30 + le(b, h + 26, 2) + le(b, h + 28, 2);
  if (data > b.size() || e.compressed_size > b.size() - data) return std::nullopt;
  const std::string_view in = b.substr(data, e.compressed_size);
  std::string out;
  if (e.method == 0) {
    out = std::string(in);
  } else if (e.method == 8) {
    out.resize(e.uncompressed_size);
    z_stream z{};
    if (inflateInit2(&z, -MAX_WBITS) != Z_OK) return std::nullopt;
    z.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(in.data()));
    z.avail_in = static_cast<uInt>(std::min<std::uint64_t>(in.size(), std::numeric_limits<uInt>::max()));
    z.next_out = reinterpret_cast<Bytef*>(out.data());
    z.avail_out = static_cast<uInt>(out.size());
    const int status = inflate(&z, Z_FINISH);
    const std::uint64_t produced = z.total_out;
    inflateEnd(&z);
    if (status != Z_STREAM_END || produced != e.uncompressed_size) return std::nullopt;
  } else {
    return std::nullopt;
  }
  if (out.size() != e.uncompressed_size) return std::nullopt;
  const uLong crc = crc32(0L, reinterpret_cast<const Bytef*>(out.data()), static_cast<uInt>(out.size()));
  if (crc != e.crc32) return std::nullopt;
  return out;
}

std::optional<std::string> zip_append_stored(std::string_view b, const std::string& name,
                                             std::string_view data) {
  const auto d = directory(b);
  if (!d || d->zip64 || name.size() > 0xffff || data.size() > 0xfffffff0u || d->entries >= 0xffff)
    return std::nullopt;
  const std::uint64_t local_offset = d->offset;
  const auto [local, central] = stored_entry(name, data, local_offset);
  if (local_offset + local.size() > 0xffffffffu) return std::nullopt;
  std::string out(b.substr(0, local_offset));
  out += local;
  out += b.substr(d->offset, d->size);
  out += central;
  std::string eocd(b.substr(d->end));
  const std::uint64_t entries = d->entries + 1;
  const std::uint64_t size = d->size + central.size();
  const std::uint64_t offset = local_offset + local.size();
  const auto set = [&eocd](std::size_t at, std::uint64_t value, int bytes) {
    for (int i = 0; i < bytes; ++i) eocd[at + i] = static_cast<char>((value >> (8 * i)) & 0xffu);
  };
  set(8, entries, 2);  // entries on this disk
  set(10, entries, 2);
  set(12, size, 4);
  set(16, offset, 4);
  return out + eocd;
}

std::string zip_stored(const std::vector<std::pair<std::string, std::string>>& entries) {
  std::string locals;
  std::string centrals;
  for (const auto& [name, data] : entries) {
    if (name.size() > 0xffff || locals.size() + 30 + name.size() + data.size() > 0xffffffffu ||
        entries.size() >= 0xffff) {
      throw InputError("zip: the archive would need zip64");
    }
    const auto [local, central] = stored_entry(name, data, locals.size());
    locals += local;
    centrals += central;
  }
  std::string out = locals + centrals;
  out += kEndOfDirectory;
  put(out, 0, 2);  // this disk
  put(out, 0, 2);  // disk of the directory
  put(out, entries.size(), 2);
  put(out, entries.size(), 2);
  put(out, centrals.size(), 4);
  put(out, locals.size(), 4);
  put(out, 0, 2);  // comment length
  return out;
}

}  // namespace fabmesh
