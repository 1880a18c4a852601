#pragma once
// Tables in CSV (RFC 4180): a batch manifest's variants, one per row.

#include <string>
#include <string_view>
#include <vector>

namespace fabmesh {

/// One cell and where it is (1-based line and column of its first character).
struct CsvCell {
  std::string text;  ///< unquoted: "" inside quotes is one ", surrounding spaces of unquoted cells removed
  int line = 0;
  int column = 0;
};

/// A header row and the data rows, each with the header's number of cells.
struct CsvTable {
  std::vector<CsvCell> header;
  std::vector<std::vector<CsvCell>> rows;
};

/// Parses comma-separated text: cells may be quoted with " (holding commas,
/// quotes written "" and line breaks); lines end with LF or CRLF; blank lines
/// are skipped. The first row is the header: its cells must be non-empty and
/// distinct. \param path for messages
/// \throw FileError "path:line:column: message" for an unterminated quote, text after a closing
/// quote, a row whose cell count differs from the header's, or an empty or repeated header
CsvTable parse_csv_table(std::string_view text, const std::string& path);

/// Reads (at most 64 MiB) and parses the file at `path`. \throw FileError
CsvTable read_csv_table(const std::string& path);

}  // namespace fabmesh
