// fabmesh's one DXF reader (io/dxf/dxf_reader.h), at the level of group
// codes: lines of any length, the whole file or nothing, numbers that parse
// whole, counts that agree with what follows (issue 43).

#include "io/dxf/dxf_reader.h"

#include <catch2/catch.hpp>
#include <string>
#include <vector>

#include "geometry/core/errors.h"

using namespace fabmesh;

namespace {

std::string section(const std::string& name, const std::string& body) {
  return "0\nSECTION\n2\n" + name + "\n" + body + "0\nENDSEC\n";
}

// A drawing: a header with $INSUNITS 4, then the given entities.
std::string drawing(const std::string& entities) {
  return section("HEADER", "9\n$INSUNITS\n70\n4\n") + section("ENTITIES", entities) + "0\nEOF\n";
}

std::string circle(const std::string& handle, double cx) {
  return "0\nCIRCLE\n5\n" + handle + "\n8\nHOLES\n10\n" + std::to_string(cx) + "\n20\n50\n30\n0\n40\n10\n";
}

// The message of the FileError reading `text` throws; empty when none.
std::string refusal(const std::string& text) {
  try {
    read_dxf_entities(text, "t.dxf");
  } catch (const FileError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST_CASE("dxf reader: lines of any length are read, a comment, a layer or a value", "[io][dxf]") {
  for (const std::size_t length : {1023u, 1024u, 1025u, 4096u, 1u << 20}) {
    INFO(length);
    const std::string layer(length, 'L');
    const std::string text = "999\n" + std::string(length, 'c') + "\n" +
                             drawing("0\nLINE\n8\n" + layer + "\n10\n0\n20\n0\n30\n0\n11\n5\n21\n0\n31\n0\n" +
                                     "0\nTEXT\n8\n0\n1\n" + std::string(length, 't') + "\n");
    const std::vector<DxfEntity> got = read_dxf_entities(text, "t.dxf");
    REQUIRE(got.size() == 2);
    CHECK(got[0].type == "LINE");
    CHECK(got[0].layer == layer);
    CHECK(got[0].points[1].x() == 5.0);
    CHECK(got[1].type == "TEXT");
  }
}

TEST_CASE("dxf reader: a file cut anywhere before its EOF is refused, naming the file and the line",
          "[io][dxf]") {
  const std::string text = drawing(circle("A1", 100) + circle("A2", 200) + circle("A3", 300));
  REQUIRE(read_dxf_entities(text, "t.dxf").size() == 3);
  // Every cut, at a line's end or inside one, short of the final "EOF" line.
  const std::size_t last = text.rfind("EOF");
  for (std::size_t size = 1; size <= last + 2; ++size) {
    INFO("cut after " << size << " bytes: ..."
                      << text.substr(size > 30 ? size - 30 : 0, std::min<std::size_t>(size, 30)));
    const std::string message = refusal(text.substr(0, size));
    CHECK_THAT(message, Catch::StartsWith("t.dxf:"));
  }
  CHECK_THAT(
      refusal(text.substr(0, text.find("0\nENDSEC", text.find("A3")))),
      Catch::Contains("the drawing ends inside its ENTITIES section, before ENDSEC: the file is cut short"));
  CHECK_THAT(refusal(text.substr(0, last)),
             Catch::Matches("t\\.dxf:[0-9]+: group code 0 has no value: the file ends there .*"));
  // What follows the EOF is not read; a last line without its line break is whole.
  CHECK(read_dxf_entities(text + "anything", "t.dxf").size() == 3);
  CHECK(read_dxf_entities(text.substr(0, text.size() - 1), "t.dxf").size() == 3);
  // A section not ended before the EOF, a POLYLINE without its SEQEND.
  CHECK_THAT(refusal(section("HEADER", "") + "0\nSECTION\n2\nENTITIES\n" + circle("B1", 0) + "0\nEOF\n"),
             Catch::Contains("the ENTITIES section has no ENDSEC before this EOF"));
  const std::string polyline = "0\nPOLYLINE\n5\nC1\n8\nX\n66\n1\n70\n1\n0\nVERTEX\n8\nX\n10\n0\n20\n0\n";
  CHECK_THAT(refusal(drawing(polyline + circle("C2", 0))),
             Catch::Contains("POLYLINE #C1 has no SEQEND before this CIRCLE"));
  CHECK_THAT(refusal(drawing("0\nVERTEX\n8\nX\n10\n0\n20\n0\n")),
             Catch::Contains("a VERTEX outside a POLYLINE"));
}

TEST_CASE(
    "dxf reader: a value that does not parse whole, or is not finite, is refused naming its line and group",
    "[io][dxf]") {
  for (const char* bad : {"inf", "-inf", "nan", "xyz", "1000abc", "1000,0", "1e999", "", "0x10", "1 000"}) {
    INFO(bad);
    const std::string text =
        drawing(std::string("0\nLINE\n5\n2F\n8\nX\n10\n") + bad + "\n20\n0\n11\n5\n21\n0\n");
    CHECK(refusal(text) == std::string("t.dxf:22: LINE #2F: group 10: '") + bad + "' is not a finite number");
  }
  CHECK(refusal(drawing("0\nLWPOLYLINE\n5\n3A\n8\nX\n70\n1.5\n10\n0\n20\n0\n")) ==
        "t.dxf:22: LWPOLYLINE #3A: group 70: '1.5' is not a whole number");
  CHECK(refusal(section("HEADER", "9\n$INSUNITS\n70\nmm\n") + "0\nEOF\n") ==
        "t.dxf:8: $INSUNITS: group 70: 'mm' is not a whole number");
  // Numbers as CAD writes them: signs, exponents, spaces around.
  const std::vector<DxfEntity> got =
      read_dxf_entities(drawing("0\nLINE\n8\nX\n10\n  -1.5E+2 \n20\n+3\n11\n.5\n21\n1e-300\n"), "t.dxf");
  REQUIRE(got.size() == 1);
  CHECK(got[0].points[0].x() == -150.0);
  CHECK(got[0].points[0].y() == 3.0);
  CHECK(got[0].points[1].x() == 0.5);
  CHECK(got[0].points[1].y() == 1e-300);
}

TEST_CASE("dxf reader: a polyline reads its own vertices, and counts must agree with what follows",
          "[io][dxf]") {
  // The second LWPOLYLINE has no group 90: its own four vertices, not the first one's.
  const std::string big =
      "0\nLWPOLYLINE\n5\n10\n8\nA\n90\n4\n70\n1\n10\n0\n20\n0\n10\n2100\n20\n0\n10\n2100\n20\n"
      "1100\n10\n0\n20\n1100\n";
  const std::string small =
      "0\nLWPOLYLINE\n5\n11\n8\nB\n70\n1\n10\n0\n20\n0\n42\n0."
      "5\n10\n1000\n20\n0\n10\n1000\n20\n600\n10\n0\n20\n600\n";
  const std::vector<DxfEntity> got = read_dxf_entities(drawing(big + small), "t.dxf");
  REQUIRE(got.size() == 2);
  REQUIRE(got[1].points.size() == 4);
  CHECK(got[1].points[2] == Vec3(1000, 600, 0));
  CHECK(got[1].bulges == std::vector<double>{0.5, 0, 0, 0});
  // A count that disagrees with the entries that follow: cut or inconsistent.
  CHECK(refusal(drawing(
            "0\nLWPOLYLINE\n5\n12\n8\nA\n90\n5\n70\n1\n10\n0\n20\n0\n10\n1\n20\n0\n10\n1\n20\n1\n")) ==
        "t.dxf:15: LWPOLYLINE #12: group 90 gives 5 vertices, but 3 follow (the entity is cut or "
        "inconsistent)");
  const std::string spline =
      "0\nSPLINE\n5\n13\n8\nA\n70\n8\n71\n1\n72\n5\n73\n2\n74\n0\n40\n0\n40\n0\n40\n1\n40\n1\n"
      "10\n0\n20\n0\n30\n0\n10\n1\n20\n1\n30\n0\n";
  CHECK_THAT(refusal(drawing(spline)),
             Catch::EndsWith("SPLINE #13: group 72 gives 5 knots, but 4 follow (the "
                             "entity is cut or inconsistent)"));
  CHECK_THAT(refusal(drawing(
                 "0\nSPLINE\n5\n14\n8\nA\n71\n1\n40\n0\n40\n0\n40\n1\n40\n1\n10\n0\n20\n0\n41\n1\n10\n1\n"
                 "20\n1\n41\n1\n41\n2\n")),
             Catch::EndsWith("SPLINE #14: 3 weights (group 41) for 2 control points"));
  CHECK_THAT(refusal(drawing("0\nLWPOLYLINE\n5\n15\n8\nA\n20\n5\n")),
             Catch::EndsWith("LWPOLYLINE #15: group 20 comes before any point's group 10"));
}

TEST_CASE("dxf reader: sections, blocks, attributes and old-style polylines", "[io][dxf]") {
  // Block definitions are not model space: not read. An INSERT's attributes end with SEQEND.
  const std::string blocks =
      section("BLOCKS", "0\nBLOCK\n2\nB\n0\nLINE\n8\n0\n10\n0\n20\n0\n11\n1\n21\n1\n0\nENDBLK\n");
  const std::string insert = "0\nINSERT\n5\n20\n8\nI\n66\n1\n2\nB\n0\nATTRIB\n8\nI\n1\nx\n0\nSEQEND\n8\nI\n";
  const std::string polyline =
      "0\nPOLYLINE\n5\n21\n8\nP\n66\n1\n10\n0\n20\n0\n30\n2\n70\n1\n"
      "0\nVERTEX\n8\nP\n10\n1\n20\n2\n42\n0.25\n"
      "0\nVERTEX\n8\nP\n70\n16\n10\n9\n20\n9\n"  // a spline frame's control point
      "0\nVERTEX\n8\nP\n10\n3\n20\n4\n"
      "0\nSEQEND\n8\nP\n";
  std::vector<DxfEntity> got;
  const DxfHeader header =
      read_dxf(section("HEADER", "9\n$ACADVER\n1\nAC1015\n9\n$INSUNITS\n70\n6\n") + blocks +
                   section("ENTITIES", insert + polyline + "999\na comment between entities\n") + "0\nEOF\n",
               "t.dxf", [&](const DxfEntity& e) { got.push_back(e); });
  REQUIRE(header.insunits);
  CHECK(*header.insunits == 6);
  std::vector<std::string> types;
  for (const DxfEntity& e : got) types.push_back(e.type);
  CHECK(types == std::vector<std::string>{"INSERT", "ATTRIB", "SEQEND", "POLYLINE"});
  const DxfEntity& p = got.back();
  CHECK(p.handle == "21");
  CHECK(p.flags == 1);
  REQUIRE(p.points.size() == 2);
  CHECK(p.points[0] == Vec3(1, 2, 2));  // at the polyline's elevation
  CHECK(p.points[1] == Vec3(3, 4, 2));
  CHECK(p.bulges == std::vector<double>{0.25, 0});
  CHECK(dxf_entity_name(p) == "POLYLINE #21");
  CHECK(dxf_entity_name(got[1]) == "ATTRIB (line 53)");
}
