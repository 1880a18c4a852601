#pragma once
// Values written into CSV files (a batch's summary.csv).

#include <string>
#include <string_view>

namespace fabmesh {

/// `text` as one CSV cell (RFC 4180) that a spreadsheet shows as text:
/// - quoted, with quotes doubled, when it holds a comma, a quote, a line
///   break or a leading or trailing space;
/// - a leading ' when it starts with = + - @ or a tab and is not a number, so
///   that a spreadsheet does not run it as a formula (a name like
///   `=HYPERLINK(...)` from a manifest stays text); numbers such as -0.3 are
///   left as they are;
/// - a NUL or another control character but tab, CR and LF becomes U+FFFD,
///   which CSV readers accept (Python's csv module rejects a NUL).
std::string csv_cell(std::string_view text);

}  // namespace fabmesh
