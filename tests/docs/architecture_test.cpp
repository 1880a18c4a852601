// docs/architecture.md is the developers' map: every file and folder it names
// must be where it says. A rename that forgets the map fails here.

#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

namespace fs = std::filesystem;

namespace {

const fs::path kSource = FABMESH_SOURCE_DIR;

std::vector<std::string> doc_lines() {
  std::ifstream in(kSource / "docs" / "architecture.md");
  REQUIRE(in);
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

// The `code` spans of a line.
std::vector<std::string> spans(const std::string& line) {
  std::vector<std::string> out;
  for (std::size_t open = line.find('`'); open != std::string::npos; open = line.find('`', open)) {
    const std::size_t close = line.find('`', open + 1);
    if (close == std::string::npos) break;
    out.push_back(line.substr(open + 1, close - open - 1));
    open = close + 1;
  }
  return out;
}

// A span that names a path of the repository: no spaces or code, no placeholder.
bool is_path(const std::string& span) {
  static const std::regex path(R"([A-Za-z0-9_.\-]+(/[A-Za-z0-9_.\-]+)*/?)");
  if (!std::regex_match(span, path)) return false;
  for (const char* placeholder : {"NAME", "PART", "DIGEST", "MAJOR"}) {
    if (span.find(placeholder) != std::string::npos) return false;
  }
  return true;
}

bool has_file_ending(const std::string& span) {
  static const std::regex ending(R"(.*\.(h|cpp|md|sh|py|mjs|js|cmake|yaml|in|pyi|txt)$)");
  return std::regex_match(span, ending);
}

const std::set<std::string> kTopFolders = {"geometry", "io",      "pipeline", "api",        "python",
                                           "tests",    "scripts", "cmake",    "docs",       "configs",
                                           "bench",    "fuzz",    "examples", "completion", "tools"};

std::string first_part(const std::string& path) { return path.substr(0, path.find('/')); }

}  // namespace

TEST_CASE("docs: every path docs/architecture.md names exists", "[docs]") {
  std::string section;  // the folder of a "### geometry/" section, whose tables name files within it
  std::size_t checked = 0;
  for (const std::string& line : doc_lines()) {
    if (line.rfind("## ", 0) == 0) section.clear();
    if (line.rfind("### ", 0) == 0) {
      const std::string title = line.substr(4);
      section =
          title.size() > 1 && title.back() == '/' && kTopFolders.count(title.substr(0, title.size() - 1))
              ? title
              : "";
    }
    const std::vector<std::string> names = spans(line);
    // In a section's table, the first cell is a folder or file of the section, the rest within it.
    std::string row_folder;
    const bool row = line.rfind("| `", 0) == 0 && !section.empty();
    for (std::size_t i = 0; i < names.size(); ++i) {
      const std::string& name = names[i];
      if (!is_path(name)) continue;
      fs::path expected;
      if (kTopFolders.count(first_part(name)) != 0 && name.find('/') != std::string::npos) {
        expected = kSource / name;
      } else if (row && i == 0) {
        expected = kSource / section / name;
        row_folder = name.back() == '/' ? section + name : section;
      } else if (row && has_file_ending(name)) {
        expected = kSource / (row_folder.empty() ? section : row_folder) / name;
      } else {
        continue;  // a word in code (a type, a key), not a path
      }
      INFO("docs/architecture.md names `" << name << "`: " << expected.string());
      CHECK(fs::exists(expected));
      ++checked;
    }
    // Links to other pages of docs/.
    static const std::regex link(R"(\]\(([a-z_./]+\.md)(#[a-z0-9-]*)?\))");
    for (auto it = std::sregex_iterator(line.begin(), line.end(), link); it != std::sregex_iterator(); ++it) {
      INFO("docs/architecture.md links " << (*it)[1]);
      CHECK(fs::exists(kSource / "docs" / (*it)[1].str()));
      ++checked;
    }
  }
  CHECK(checked > 150);  // the map names many files; a parser that finds few is broken
}
