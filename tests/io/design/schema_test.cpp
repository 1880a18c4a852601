#include "io/design/schema.h"

#include <catch2/catch.hpp>
#include <fstream>
#include <set>
#include <sstream>
#include <string>

using namespace fabmesh;

namespace {

std::string reference() {
  std::ifstream in(std::string(FABMESH_SOURCE_DIR) + "/docs/design-files.md");
  REQUIRE(in);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// The part of the reference after "<!-- keys: NAME -->", up to the next marker.
std::string section(const std::string& doc, const std::string& name) {
  const std::string marker = "<!-- keys: " + name + " -->";
  const std::size_t start = doc.find(marker);
  if (start == std::string::npos) return "";
  const std::size_t end = doc.find("<!-- keys: ", start + marker.size());
  return doc.substr(start, end == std::string::npos ? std::string::npos : end - start);
}

}  // namespace

TEST_CASE("schema: every key the design reader accepts is documented in its section of the reference",
          "[io][design][docs]") {
  const std::string doc = reference();
  for (const KeyGroup& group : design_key_groups()) {
    INFO("key group " << group.name);
    const std::string text = section(doc, group.name);
    REQUIRE_FALSE(text.empty());
    for (const std::string& key : group.keys) {
      INFO("key " << key);
      // A table row naming the key (the common keys are named together in the kinds' tables).
      const bool row = text.find("| `" + key + "`") != std::string::npos ||
                       text.find(", `" + key + "`") != std::string::npos ||
                       text.find("`" + key + "`, ") != std::string::npos;
      CHECK(row);
    }
  }
}

TEST_CASE("schema: every key section of the reference names a group the reader has", "[io][design][docs]") {
  const std::string doc = reference();
  std::set<std::string> names;
  for (const KeyGroup& g : design_key_groups()) names.insert(g.name);
  std::size_t pos = 0, sections = 0;
  while ((pos = doc.find("<!-- keys: ", pos)) != std::string::npos) {
    const std::size_t end = doc.find(" -->", pos);
    const std::string name = doc.substr(pos + 11, end - pos - 11);
    INFO(name);
    CHECK(names.count(name) == 1);
    ++sections;
    pos = end;
  }
  CHECK(sections == names.size());
}
