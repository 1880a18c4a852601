// escape_markup: hostile names (quotes, markup, shell syntax, control
// characters, NUL, invalid UTF-8) stay text in an element and in quoted
// attributes: a strict scanner reads back exactly one element whose text and
// attributes are the name, with the control characters XML forbids and
// invalid UTF-8 as U+FFFD and everything else unchanged.

#include "io/pictures/markup.h"

#include <catch2/catch.hpp>
#include <string>
#include <vector>

#include "tests/io/pictures/xml_scan.h"

using namespace fabmesh;

namespace {

const std::string kReplacement = "\xEF\xBF\xBD";  // U+FFFD

/// What escape_markup promises the reader gets back for `text`: valid UTF-8
/// unchanged, except the control characters XML forbids (below 0x20 but tab,
/// line feed and carriage return) as U+FFFD.
std::string expected_text(const std::string& text) {
  std::string out;
  for (const char c : text) {
    const auto u = static_cast<unsigned char>(c);
    out += (u < 0x20 && c != '\t' && c != '\n' && c != '\r') ? kReplacement : std::string(1, c);
  }
  return out;
}

}  // namespace

TEST_CASE("escape_markup: hostile names stay text in elements and in quoted attributes",
          "[io][pictures][markup]") {
  const std::vector<std::string> names{"plain",
                                       "",
                                       "<script>alert(1)</script>",
                                       "\"><img src=x onerror=alert(1)>",
                                       "it's 'single' & \"double\"",
                                       "$(touch PWNED)",
                                       "`touch PWNED`",
                                       "a;b|c&&d",
                                       "m\ntouch PWNED\n.yaml",
                                       std::string("nul\0inside", 10),
                                       "tab\tcr\rbell\a\x1b[0m",
                                       "&amp; &lt;not an entity&gt;",
                                       "]]><!-- -->",
                                       "caf\xC3\xA9 \xE2\x82\xAC \xF0\x9F\x98\x80"};
  for (const std::string& name : names) {
    INFO("name of " << name.size() << " bytes");
    const std::string escaped = escape_markup(name);
    CHECK(escaped.find('<') == std::string::npos);
    CHECK(escaped.find('"') == std::string::npos);
    CHECK(escaped.find('\'') == std::string::npos);
    CHECK(escaped.find('\0') == std::string::npos);
    const std::string doc =
        "<root><item a=\"" + escaped + "\" b='" + escaped + "'>" + escaped + "</item></root>";
    const std::vector<test::XmlElement> all = test::scan_xml(doc);
    REQUIRE(all.size() == 2);
    CHECK(all[1].name == "item");
    CHECK(all[1].text == expected_text(name));
    CHECK(all[1].attr("a") == expected_text(name));
    CHECK(all[1].attr("b") == expected_text(name));
  }
  // Invalid UTF-8 becomes U+FFFD, one per bad byte at most, never a raw byte.
  const std::string bad = escape_markup("x\xFF\xC3(y");
  CHECK(bad.find('\xFF') == std::string::npos);
  CHECK(bad.find(kReplacement) != std::string::npos);
}
