#include "io/pictures/html_report.h"

#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <set>

#include "geometry/core/errors.h"
#include "tests/io/pictures/chromium.h"
#include "tests/io/pictures/png_decode.h"
#include "tests/io/pictures/sample_report.h"
#include "tests/io/pictures/xml_scan.h"

using namespace fabmesh;
using test::scan_xml;
using test::select;
using test::XmlElement;

namespace {

ReportRow row(const std::string& name, ReportStatus status, std::optional<std::size_t> triangles) {
  ReportRow r;
  r.name = name;
  r.kind = "vessel";
  r.status = status;
  r.message = "verdict of " + name;
  r.units = "mm";
  r.triangles = triangles;
  if (triangles) {
    r.volume = 1.5 * static_cast<double>(*triangles);
    r.area = 2.0;
    r.max_deviation = 0.01;
    r.bbox = std::array<Vec3, 2>{Vec3(0, 0, 0), Vec3(10, 20, 30)};
    r.timings = {{"build", 0.25}, {"write", 0.5}};
    r.files = {"out/" + name + ".stl"};
    r.preview_png = "out/" + name + ".png";
    r.plot_svg = "out/" + name + ".svg";
  }
  return r;
}

// The table's body rows (their cells as elements).
std::vector<std::vector<const XmlElement*>> table_rows(const std::vector<XmlElement>& page) {
  int tbody = -1;
  for (std::size_t i = 0; i < page.size(); ++i) {
    if (page[i].name == "tbody") tbody = static_cast<int>(i);
  }
  REQUIRE(tbody >= 0);
  std::vector<std::vector<const XmlElement*>> rows;
  std::vector<int> row_index(page.size(), -1);
  for (std::size_t i = 0; i < page.size(); ++i) {
    if (page[i].name == "tr" && page[i].parent == tbody) {
      row_index[i] = static_cast<int>(rows.size());
      rows.emplace_back();
    } else if (page[i].name == "td" && page[i].parent >= 0 && row_index[page[i].parent] >= 0) {
      rows[row_index[page[i].parent]].push_back(&page[i]);
    }
  }
  return rows;
}

// All text inside element `index` (its own and its descendants'), in document order.
std::string deep_text(const std::vector<XmlElement>& page, const XmlElement* e) {
  const int index = static_cast<int>(e - page.data());
  std::string text = e->text;
  for (std::size_t i = index + 1; i < page.size(); ++i) {
    int p = page[i].parent;
    while (p > index) p = page[p].parent;
    if (p != index) break;
    text += page[i].text;
  }
  return text;
}

std::string only_text(const std::vector<XmlElement>& page, const std::string& tag) {
  const auto found = select(page, tag);
  REQUIRE(found.size() == 1);
  return found[0]->text;
}

std::string read_all(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

}  // namespace

TEST_CASE("html report: one table row per design, text escaped, links relative and percent-encoded",
          "[io][pictures][report]") {
  HtmlReport report;
  report.title = "batch <1> & 'two'";
  report.generated_by = "fabmesh \"test\"";
  report.rows = {row("cup <b>&amp;</b> \"x\"", ReportStatus::Ok, 1000),
                 row("plain", ReportStatus::Invalid, 20),
                 row("no mesh", ReportStatus::BadInput, std::nullopt)};
  report.rows[1].files = {"out/with space#and?query:colon.stl"};
  report.rows[1].remarks = {"printed upright: <56.3\u00b0>", "warning: print.bed & more"};
  const std::string html = render_report_html(report);
  const auto page = scan_xml(html);
  CHECK(only_text(page, "title") == report.title);
  const auto rows = table_rows(page);
  REQUIRE(rows.size() == 3);
  const std::size_t columns = select(page, "th").size();
  for (std::size_t i = 0; i < rows.size(); ++i) {
    REQUIRE(rows[i].size() == columns);
    CHECK(rows[i][2]->text == report.rows[i].name);
    CHECK(deep_text(page, rows[i][4]) == to_string(report.rows[i].status));
    CHECK(rows[i][5]->text == report.rows[i].message);
  }
  CHECK(html.find("<b>&amp;</b>") == std::string::npos);
  // Remarks under a verdict: one list item each, escaped.
  CHECK(select(page, "ul", "remarks").size() == 1);
  const auto remarks = select(page, "li");
  REQUIRE(remarks.size() == 2);
  CHECK(remarks[0]->text == report.rows[1].remarks[0]);
  CHECK(remarks[1]->text == report.rows[1].remarks[1]);
  // Thumbnails: lazy, sized, linking to the full image.
  const auto images = select(page, "img");
  CHECK(images.size() == 4);
  for (const XmlElement* img : images) {
    CHECK(img->attr("loading") == "lazy");
    CHECK(img->attr("width") == "120");
    CHECK(img->attr("height") == "90");
    CHECK(page[img->parent].name == "a");
    CHECK(page[img->parent].attr("href") == img->attr("src"));
  }
  CHECK(images[0]->attr("src") == "out/cup%20%3Cb%3E%26amp%3B%3C/b%3E%20%22x%22.png");
  bool encoded = false;
  for (const XmlElement* a : select(page, "a")) {
    encoded = encoded || a->attr("href") == "out/with%20space%23and%3Fquery%3Acolon.stl";
  }
  CHECK(encoded);
  // Missing measures sort last: their data-sort is empty.
  CHECK(rows[2][10]->attr("data-sort").empty());
  CHECK(rows[0][10]->attr("data-sort") == "1000");
}

TEST_CASE("html report: the page needs no network: no external scripts, styles, fonts or images",
          "[io][pictures][report]") {
  HtmlReport report;
  report.rows = {row("a", ReportStatus::Ok, 10), row("b", ReportStatus::Error, std::nullopt)};
  const std::string html = render_report_html(report);
  const auto page = scan_xml(html);
  CHECK(select(page, "link").empty());
  for (const XmlElement* s : select(page, "script")) CHECK(s->attr("src").empty());
  for (const XmlElement& e : page) {
    for (const char* key : {"src", "href"}) {
      const std::string v = e.attr(key);
      CHECK(v.find("//") == std::string::npos);
      CHECK(v.find(':') == std::string::npos);
    }
  }
  CHECK(html.find("@import") == std::string::npos);
  CHECK(html.find("url(") == std::string::npos);
  CHECK(html.find("http") == std::string::npos);
}

TEST_CASE("html report: a batch of 1000 variants stays a light page of lazy thumbnails",
          "[io][pictures][report]") {
  HtmlReport report;
  for (int i = 0; i < 1000; ++i) {
    report.rows.push_back(row("variant-" + std::to_string(i) + "-a-reasonably-long-design-name",
                              i % 10 == 0 ? ReportStatus::Invalid : ReportStatus::Ok, 100000 + i));
  }
  const std::string html = render_report_html(report);
  CHECK(html.size() < 2'000'000);
  const auto page = scan_xml(html);
  CHECK(table_rows(page).size() == 1000);
  const auto images = select(page, "img");
  CHECK(images.size() == 2000);
  for (const XmlElement* img : images) CHECK(img->attr("loading") == "lazy");
  CHECK(render_report_html(report) == html);
}

TEST_CASE("html report: absolute paths, bad timings and bad thumbnail sizes are refused",
          "[io][pictures][report]") {
  HtmlReport report;
  report.rows = {row("a", ReportStatus::Ok, 10)};
  report.rows[0].files = {"/etc/passwd"};
  CHECK_THROWS_WITH(render_report_html(report),
                    Catch::Contains("/etc/passwd") && Catch::Contains("relative"));
  report.rows[0].files = {"a.stl"};
  report.rows[0].timings = {{"build", -1.0}};
  CHECK_THROWS_AS(render_report_html(report), RangeError);
  report.rows[0].timings = {};
  HtmlReportOptions o;
  o.thumbnail_width = 0;
  CHECK_THROWS_AS(render_report_html(report, o), RangeError);
}

TEST_CASE("html report: in Chromium every image loads, no console message appears and headers sort the rows",
          "[io][pictures][report][chromium]") {
  REQUIRE(test::chromium_available());  // Debian package chromium (scripts/install-deps.sh --test)
  // Kept under the build folder for people to look at: report.html, its files and a screenshot.
  const std::string dir = (std::filesystem::path(FABMESH_TEST_TMP) / "pictures-samples" / "report").string();
  const HtmlReport report = test::sample_report(dir);
  const std::string html = render_report_html(report);
  const std::string page_path = dir + "/report.html";
  std::ofstream(page_path, std::ios::binary) << html;

  // A copy with a script that clicks headers and records the row order (names joined by '|').
  const std::string probe =
      "<script>(function(){var h=document.querySelectorAll('#summary thead th');"
      "function names(){return Array.prototype.map.call(document.querySelectorAll('#summary tbody tr'),"
      "function(r){return r.cells[2].textContent;}).join('|');}"
      "h[10].click();document.body.setAttribute('data-by-triangles',names());"
      "h[10].click();document.body.setAttribute('data-by-triangles-desc',names());"
      "h[2].click();document.body.setAttribute('data-by-name',names());})();</script>\n</body>";
  std::string probed = html;
  probed.replace(probed.rfind("</body>"), 7, probe);
  const std::string probe_path = dir + "/report_probe.html";
  std::ofstream(probe_path, std::ios::binary) << probed;

  const test::ChromiumRun run = test::run_chromium(
      "--window-size=1600,1200 --virtual-time-budget=10000 --enable-logging=stderr --v=0 --dump-dom",
      test::file_url(probe_path));
  INFO(run.err);
  REQUIRE(run.code == 0);
  CHECK(run.err.find(":CONSOLE") == std::string::npos);
  const auto dom = scan_xml(run.out, true);
  const XmlElement& body = *select(dom, "body").at(0);
  const std::size_t images = select(scan_xml(html), "img").size();
  CHECK(images == 6);
  CHECK(body.attr("data-images-loaded") == std::to_string(images));
  CHECK(body.attr("data-images-failed") == "0");
  // Triangles ascending, then descending (the row without a mesh stays last), then names.
  std::vector<std::pair<std::size_t, std::string>> by_triangles;
  for (const ReportRow& r : report.rows) {
    if (r.triangles) by_triangles.emplace_back(*r.triangles, r.name);
  }
  std::sort(by_triangles.begin(), by_triangles.end());
  std::string ascending, descending;
  for (const auto& [n, name] : by_triangles) ascending += (ascending.empty() ? "" : "|") + name;
  for (auto it = by_triangles.rbegin(); it != by_triangles.rend(); ++it) {
    descending += (descending.empty() ? "" : "|") + it->second;
  }
  CHECK(body.attr("data-by-triangles") == ascending + "|" + report.rows[3].name);
  CHECK(body.attr("data-by-triangles-desc") == descending + "|" + report.rows[3].name);
  CHECK(body.attr("data-by-name") ==
        "broken <design> & \"quotes\"|countertop_g2_fair_cv|vessel_fair_strain_shell|vessel_golden_shell");

  // The screenshot people look at.
  const std::string shot =
      (std::filesystem::path(FABMESH_TEST_TMP) / "pictures-samples" / "sample_report.png").string();
  std::filesystem::remove(shot);
  const test::ChromiumRun capture =
      test::run_chromium("--window-size=1500,700 --virtual-time-budget=10000 --screenshot='" + shot + "'",
                         test::file_url(page_path));
  REQUIRE(capture.code == 0);
  const test::DecodedPng image = test::decode_png(read_all(shot));
  CHECK(image.width == 1500);
  std::set<std::array<std::uint8_t, 3>> colours;
  for (int y = 0; y < image.height; y += 3) {
    for (int x = 0; x < image.width; x += 3) colours.insert(image.at(x, y));
  }
  CHECK(colours.size() > 50);  // thumbnails rendered, not a blank page
}

TEST_CASE("html report: in Chromium a report of long messages and paths fits a 1500 pixel window",
          "[io][pictures][report][chromium]") {
  REQUIRE(test::chromium_available());  // Debian package chromium (scripts/install-deps.sh --test)
  const std::string dir = (std::filesystem::path(FABMESH_TEST_TMP) / "pictures-samples" / "wide").string();
  std::filesystem::create_directories(dir);
  HtmlReport report = test::sample_report(dir);
  // What a real run's rows hold: a batch variant's long name, a message of several
  // sentences, and files under a deep output folder.
  ReportRow long_row = report.rows.front();
  long_row.name = "countertop_kitchen_island_with_two_sinks_and_a_hob_variant_0042";
  long_row.status = ReportStatus::BadInput;
  long_row.message =
      "countertops/kitchen_island_with_two_sinks_and_a_hob.yaml:41:7: holes[2] (rounded_rect): the cut-out "
      "comes 3.2 mm from holes[1] (ellipse) near (1204.5, 388.25), closer than the router's 12 mm tool can "
      "cut between them; move them apart, or use a smaller tool, or join them into one cut-out";
  long_row.files = {
      "out/batches/kitchens/countertop_kitchen_island_with_two_sinks_and_a_hob_variant_0042/"
      "countertop_kitchen_island_with_two_sinks_and_a_hob_variant_0042.draco.glb",
      "out/batches/kitchens/countertop_kitchen_island_with_two_sinks_and_a_hob_variant_0042/"
      "countertop_kitchen_island_with_two_sinks_and_a_hob_variant_0042.toolpath.svg"};
  report.rows.push_back(long_row);
  std::string html = render_report_html(report);
  html.replace(
      html.rfind("</body>"), 7,
      "<script>document.body.setAttribute('data-overflow', String(document.documentElement.scrollWidth"
      " - window.innerWidth));</script>\n</body>");
  const std::string page = dir + "/report.html";
  std::ofstream(page, std::ios::binary) << html;
  const test::ChromiumRun run = test::run_chromium(
      "--window-size=1500,700 --virtual-time-budget=10000 --dump-dom", test::file_url(page));
  INFO(run.err);
  REQUIRE(run.code == 0);
  const auto dom = scan_xml(run.out, true);
  const XmlElement& body = *select(dom, "body").at(0);
  REQUIRE_FALSE(body.attr("data-overflow").empty());
  CHECK(std::stoi(body.attr("data-overflow")) <= 0);  // no horizontal scrolling
}

TEST_CASE("html report: in Chromium a missing image is counted as failed",
          "[io][pictures][report][chromium]") {
  REQUIRE(test::chromium_available());  // Debian package chromium (scripts/install-deps.sh --test)
  const test::TempDir dir;
  HtmlReport report;
  report.rows = {row("gone", ReportStatus::Ok, 10)};
  report.rows[0].plot_svg.clear();
  const std::string page_path = dir.write("report.html", render_report_html(report));
  const test::ChromiumRun run = test::run_chromium(
      "--window-size=1200,800 --virtual-time-budget=5000 --dump-dom", test::file_url(page_path));
  REQUIRE(run.code == 0);
  const auto dom = scan_xml(run.out, true);
  const XmlElement& body = *select(dom, "body").at(0);
  CHECK(body.attr("data-images-loaded") == "0");
  CHECK(body.attr("data-images-failed") == "1");
}
