// Drawing sheets: how a dimension is drawn, the text height that reads on
// A3, and the DXF of a sheet (a block of geometry per DIMENSION).

#include "io/cutting/sheet.h"

#include <catch2/catch.hpp>
#include <cmath>

#include "io/cutting/dxf.h"

using namespace fabmesh;

namespace {

std::size_t count(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

}  // namespace

TEST_CASE("sheet: a horizontal dimension measures along x, its line through the point given", "[sheet]") {
  const SheetDimension d{"DIMENSIONS", {0.0, 0.0}, {1000.0, 30.0}, {200.0, -50.0}, 0.0};
  const DimensionGraphic g = dimension_graphic(d, 10.0);
  CHECK(g.value == 1000.0);
  CHECK(g.text == "1000");
  REQUIRE(g.lines.size() == 3);  // two extension lines, then the dimension line
  CHECK(g.lines[2][0] == Vec2(0.0, -50.0));
  CHECK(g.lines[2][1] == Vec2(1000.0, -50.0));
  // Extension lines start half a text height off the points and end half a height past the line.
  CHECK(g.lines[0][0] == Vec2(0.0, -5.0));
  CHECK(g.lines[0][1] == Vec2(0.0, -55.0));
  CHECK(g.lines[1][0] == Vec2(1000.0, 25.0));
  REQUIRE(g.arrows.size() == 2);
  CHECK(g.arrows[0][0] == Vec2(0.0, -50.0));
  CHECK(g.arrows[1][0] == Vec2(1000.0, -50.0));
  CHECK(g.arrows[0][1].x() == Approx(10.0));  // pointing outwards: the head's base is inside
  CHECK(g.text_at == Vec2(500.0, -46.0));
}

TEST_CASE("sheet: vertical and turned dimensions measure along their direction", "[sheet]") {
  const DimensionGraphic v = dimension_graphic({"D", {5.0, 0.0}, {5.0, 620.0}, {-20.0, 0.0}, 90.0}, 4.0);
  CHECK(v.value == 620.0);
  CHECK(v.lines.back()[0] == Vec2(-20.0, 0.0));
  CHECK(v.lines.back()[1] == Vec2(-20.0, 620.0));
  CHECK(v.text_at.x() < -20.0);  // text on the far side of the line, reading upwards
  const DimensionGraphic t =
      dimension_graphic({"D", {0.0, 0.0}, {300.0, 400.0}, {0.0, 0.0}, 53.13010235415598}, 4.0);
  CHECK(t.value == Approx(500.0).epsilon(1e-12));
  CHECK(t.text == "500");
  // On its own line: no extension lines.
  CHECK(t.lines.size() == 1);
}

TEST_CASE("sheet: lengths as a shop reads them", "[sheet]") {
  CHECK(shop_number(2400.0) == "2400");
  CHECK(shop_number(649.9999999999998) == "650");
  CHECK(shop_number(12.3456) == "12.346");
  CHECK(shop_number(-0.0001) == "0");
  CHECK(shop_number(0.5) == "0.5");
}

TEST_CASE("sheet: the text height that prints at 3 mm on A3", "[sheet]") {
  // A box of 400 x 277 mm fits A3 less its border at full size.
  CHECK(readable_text_height({0.0, 0.0}, {400.0, 277.0}, "mm", {420.0, 297.0}, 3.0) == Approx(3.0));
  // Twice as big: half the scale, twice the height; turned boxes fit turned.
  CHECK(readable_text_height({0.0, 0.0}, {554.0, 800.0}, "mm", {420.0, 297.0}, 3.0) == Approx(6.0));
  // In inches: 400 mm is 15.748 in; 3 mm is 0.11811 in.
  CHECK(readable_text_height({0.0, 0.0}, {400.0 / 25.4, 277.0 / 25.4}, "in", {420.0, 297.0}, 3.0) ==
        Approx(3.0 / 25.4));
}

TEST_CASE("sheet: its DXF writes each dimension with a block of its own, texts and layers", "[sheet]") {
  Sheet sheet;
  sheet.layers = {{"PIECE", 7, "black"}, {"DIMENSIONS", 1, "red"}, {"LABELS", 3, "green"}};
  sheet.loops.push_back({"PIECE", polygon_loop({{0, 0}, {1000, 0}, {1000, 600}, {0, 600}}, "p", true)});
  sheet.dimensions.push_back({"DIMENSIONS", {0, 0}, {1000, 0}, {0, -30}, 0.0});
  sheet.dimensions.push_back({"DIMENSIONS", {0, 0}, {0, 600}, {-30, 0}, 90.0});
  sheet.texts.push_back({"LABELS", {500, 700}, 12.0, "piece & <one>", true});
  sheet.text_height = 12.0;
  const std::string dxf = encode_dxf_sheet(sheet);
  CHECK(count(dxf, "\nDIMENSION\n") == 2);
  // Its block record, its block (groups 2 and 3) and its DIMENSION (group 2).
  CHECK(count(dxf, "\n*D1\n") == 4);
  CHECK(count(dxf, "\n*D2\n") == 4);
  CHECK(count(dxf, "\n*D3\n") == 0);
  CHECK(count(dxf, "\nTEXT\n") == 3);   // the label and each dimension's text in its block
  CHECK(count(dxf, "\nSOLID\n") == 4);  // two arrowheads each
  for (const char* layer : {"\nPIECE\n", "\nDIMENSIONS\n", "\nLABELS\n"}) CHECK(count(dxf, layer) >= 2);
  const std::string svg = encode_sheet_svg(sheet, "mm", "t");
  CHECK(count(svg, "class=\"dimension\"") == 2);
  CHECK(svg.find("piece &amp; &lt;one&gt;") != std::string::npos);
  CHECK(svg.find(">1000</text>") != std::string::npos);
  CHECK(svg.find(">600</text>") != std::string::npos);
}
