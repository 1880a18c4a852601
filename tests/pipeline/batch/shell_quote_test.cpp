// shell_quote: one bash word, on one line, that stands for exactly its text.

#include "pipeline/batch/shell_quote.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <catch2/catch.hpp>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include "geometry/core/errors.h"
#include "tests/pipeline/cli_harness.h"

using namespace fabmesh;

namespace {

// What bash makes of `word`: the script `printf %s WORD` run from a file, its output.
std::string bash_says(const std::filesystem::path& dir, const std::string& word) {
  const std::filesystem::path script = dir / "say.sh";
  std::ofstream(script, std::ios::binary) << "printf %s " << word << "\n";
  std::FILE* pipe = ::popen(fmt::format("cd '{}' && bash say.sh", dir.string()).c_str(), "r");
  REQUIRE(pipe != nullptr);
  std::string out;
  std::array<char, 256> buffer{};
  for (std::size_t n; (n = std::fread(buffer.data(), 1, buffer.size(), pipe)) > 0;)
    out.append(buffer.data(), n);
  ::pclose(pipe);
  return out;
}

}  // namespace

TEST_CASE("shell_quote: hostile names come back from bash unchanged, on one line", "[pipeline][batch]") {
  const std::filesystem::path dir = testing::fresh_dir("shell_quote");
  for (const std::string& text : std::vector<std::string>{"plain",
                                                          "",
                                                          "with space",
                                                          "it's",
                                                          "'",
                                                          "''\\'",
                                                          "\"double\" quotes",
                                                          "$(touch PWNED)",
                                                          "`touch PWNED`",
                                                          "${HOME}",
                                                          "$HOME",
                                                          "a;touch PWNED",
                                                          "m\ntouch PWNED\n.yaml",
                                                          "tab\there",
                                                          "cr\rhere",
                                                          "bell\a\x1b[0m",
                                                          "back\\slash\\n",
                                                          "\x7f",
                                                          "star *",
                                                          "~user",
                                                          "!event",
                                                          "\n",
                                                          "x\x01"
                                                          "1"}) {
    INFO("[" << text << "]");
    const std::string word = shell_quote(text);
    CHECK(std::none_of(word.begin(), word.end(), [](char c) {
      return static_cast<unsigned char>(c) < 0x20 || static_cast<unsigned char>(c) == 0x7F;
    }));
    CHECK(bash_says(dir, word) == text);
  }
  CHECK_FALSE(std::filesystem::exists(dir / "PWNED"));
  CHECK(shell_quote("/m/it's.yaml") == "'/m/it'\\''s.yaml'");
  CHECK(shell_quote("a\nb") == "$'a\\nb'");
  CHECK_THROWS_AS(shell_quote(std::string("nul\0byte", 8)), InputError);
}
