#include "io/pictures/html_report.h"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <cmath>

#include "geometry/core/error_checks.h"
#include "io/pictures/markup.h"

namespace fabmesh {
namespace {

constexpr const char* kStyle = R"(
body{font:14px/1.4 system-ui,sans-serif;margin:16px;color:#222;background:#fafafa}
h1{font-size:20px;margin:0 0 4px}
.meta{color:#666;margin-bottom:8px}
.counts span{display:inline-block;margin-right:12px}
#filter{margin:8px 0;padding:4px 6px;width:280px}
table{border-collapse:collapse;background:#fff;max-width:100%}
th,td{border:1px solid #ddd;padding:4px 6px;vertical-align:top;text-align:left;overflow-wrap:anywhere}
th{background:#eee;position:sticky;top:0;z-index:1}
th[data-type]{cursor:pointer;user-select:none}
th[aria-sort=ascending]::after{content:" \25b2"}
th[aria-sort=descending]::after{content:" \25bc"}
td.num{text-align:right;white-space:nowrap}
td.thumb{padding:2px}
td.thumb img{display:block;object-fit:contain;background:#f0f0f0}
.status{font-weight:bold;white-space:nowrap;border-radius:3px;padding:0 4px}
.status-ok{color:#176f2c;background:#dff3e4}
.status-invalid{color:#8a5a00;background:#fff0cc}
.status-bad-input{color:#8a1f11;background:#fde2dd}
.status-error{color:#fff;background:#a01818}
.files a{display:block}
footer{color:#666;margin-top:12px}
)";

// Every image reports its own load or error (inline handlers, so no event is
// missed whatever the timing); the count is shown once the page script runs.
constexpr const char* kImageScript =
    "function settle(img, ok) {"
    " img.setAttribute('data-state', ok && img.naturalWidth > 0 ? 'loaded' : 'failed');"
    " if (window.showImages) window.showImages(); }";

// Sorting (numbers or text, missing values last, stable), filtering, and a
// count of the images that loaded or failed (on <body> and in the footer).
constexpr const char* kScript = R"(
(function () {
  'use strict';
  var table = document.getElementById('summary');
  var body = table.tBodies[0];
  var heads = table.tHead.rows[0].cells;
  function key(row, i, numeric) {
    var cell = row.cells[i];
    var v = cell.hasAttribute('data-sort') ? cell.getAttribute('data-sort') : cell.textContent;
    if (!numeric) return v.toLowerCase();
    var n = v === '' ? NaN : Number(v);
    return isNaN(n) ? null : n;
  }
  function sortBy(i) {
    var th = heads[i];
    var numeric = th.getAttribute('data-type') === 'number';
    var dir = th.getAttribute('aria-sort') === 'ascending' ? -1 : 1;
    var keyed = Array.prototype.map.call(body.rows, function (r, n) {
      return {row: r, key: key(r, i, numeric), n: n};
    });
    keyed.sort(function (a, b) {
      if (a.key === b.key) return a.n - b.n;
      if (a.key === null) return 1;
      if (b.key === null) return -1;
      return (a.key < b.key ? -1 : 1) * dir;
    });
    for (var j = 0; j < heads.length; j++) heads[j].removeAttribute('aria-sort');
    th.setAttribute('aria-sort', dir === 1 ? 'ascending' : 'descending');
    var fragment = document.createDocumentFragment();
    keyed.forEach(function (e) { fragment.appendChild(e.row); });
    body.appendChild(fragment);
  }
  Array.prototype.forEach.call(heads, function (th, i) {
    if (th.hasAttribute('data-type')) th.addEventListener('click', function () { sortBy(i); });
  });
  var filter = document.getElementById('filter');
  filter.addEventListener('input', function () {
    var q = filter.value.toLowerCase();
    Array.prototype.forEach.call(body.rows, function (r) {
      r.hidden = q !== '' && r.textContent.toLowerCase().indexOf(q) < 0;
    });
  });
  var status = document.getElementById('images-status');
  window.showImages = function () {
    var all = document.images.length;
    var loaded = document.querySelectorAll('img[data-state=loaded]').length;
    var failed = document.querySelectorAll('img[data-state=failed]').length;
    document.body.setAttribute('data-images-loaded', String(loaded));
    document.body.setAttribute('data-images-failed', String(failed));
    status.textContent = all + ' images: ' + loaded + ' loaded, ' + failed + ' failed' +
        (loaded + failed < all ? ' (the others load when scrolled to)' : '');
  };
  window.showImages();
})();
)";

// A relative path as a URL reference: unreserved characters and '/' kept,
// every other byte percent-encoded.
std::string url_path(const std::string& path, const std::string& row) {
  if (!path.empty() && (path[0] == '/' || path[0] == '\\')) {
    throw InputError(fmt::format("html report: '{}' of '{}' must be relative to the page", path, row));
  }
  std::string out;
  for (const char c : path) {
    const auto u = static_cast<unsigned char>(c);
    if (std::isalnum(u) || c == '/' || c == '.' || c == '_' || c == '-' || c == '~') {
      out += c;
    } else {
      out += fmt::format("%{:02X}", static_cast<unsigned>(u));
    }
  }
  return out;
}

std::string basename(const std::string& path) {
  const std::size_t slash = path.find_last_of('/');
  return slash == std::string::npos ? path : path.substr(slash + 1);
}

std::string status_class(ReportStatus s) {
  std::string c = to_string(s);
  std::replace(c.begin(), c.end(), ' ', '-');
  return "status-" + c;
}

// A numeric cell: the value with its unit, sorted by the raw value; "-" when absent.
std::string number_cell(const std::optional<double>& value, const std::string& unit) {
  if (!value) return "<td class=\"num\" data-sort=\"\">-</td>";
  return fmt::format("<td class=\"num\" data-sort=\"{}\">{}{}</td>", short_number(*value, 17),
                     short_number(*value, 6), unit.empty() ? "" : " " + escape_markup(unit));
}

std::string thumbnail_cell(const std::string& path, const std::string& what, const std::string& row,
                           const HtmlReportOptions& o) {
  if (path.empty()) return "<td class=\"thumb\"></td>";
  const std::string url = url_path(path, row);
  return fmt::format(
      "<td class=\"thumb\"><a href=\"{}\"><img src=\"{}\" loading=\"lazy\" decoding=\"async\" width=\"{}\" "
      "height=\"{}\" alt=\"{} of {}\" onload=\"settle(this, 1)\" onerror=\"settle(this, 0)\"/></a></td>",
      url, url, o.thumbnail_width, o.thumbnail_height, what, escape_markup(row));
}

std::string bbox_cell(const ReportRow& r) {
  if (!r.bbox) return "<td class=\"num\" data-sort=\"\">-</td>";
  const Vec3 size = (*r.bbox)[1] - (*r.bbox)[0];
  const Vec3& lo = (*r.bbox)[0];
  const Vec3& hi = (*r.bbox)[1];
  const std::string title = fmt::format(
      "min ({}, {}, {}) max ({}, {}, {})", short_number(lo.x(), 6), short_number(lo.y(), 6),
      short_number(lo.z(), 6), short_number(hi.x(), 6), short_number(hi.y(), 6), short_number(hi.z(), 6));
  return fmt::format("<td class=\"num\" data-sort=\"{}\" title=\"{}\">{} \u00d7 {} \u00d7 {}{}</td>",
                     short_number(size.maxCoeff(), 17), title, short_number(size.x(), 5),
                     short_number(size.y(), 5), short_number(size.z(), 5),
                     r.units.empty() ? "" : " " + escape_markup(r.units));
}

std::string timing_cell(const ReportRow& r) {
  if (r.timings.empty()) return "<td class=\"num\" data-sort=\"\">-</td>";
  double total = 0.0;
  std::string title;
  for (const StageTiming& t : r.timings) {
    require_in_range("html report timing (seconds)", t.seconds, 0.0, 1e12);
    total += t.seconds;
    title += fmt::format("{}{}: {} s", title.empty() ? "" : "; ", escape_markup(t.stage),
                         short_number(t.seconds, 3));
  }
  return fmt::format("<td class=\"num\" data-sort=\"{}\" title=\"{}\">{} s</td>", short_number(total, 17),
                     title, short_number(total, 3));
}

std::string row_html(const ReportRow& r, const HtmlReportOptions& o) {
  const std::string units = r.units.empty() ? "" : r.units;
  std::string files;
  for (const std::string& f : r.files) {
    if (f.empty()) continue;
    files += fmt::format("<a href=\"{}\">{}</a>", url_path(f, r.name), escape_markup(basename(f)));
  }
  std::string message = escape_markup(r.message);
  if (!r.remarks.empty()) {
    message += "<ul class=\"remarks\">";
    for (const std::string& line : r.remarks) message += "<li>" + escape_markup(line) + "</li>";
    message += "</ul>";
  }
  return fmt::format(
      "<tr>{}{}<td>{}</td><td>{}</td><td data-sort=\"{}\"><span class=\"status "
      "{}\">{}</span></td><td>{}</td>{}{}{}{}"
      "<td class=\"num\" data-sort=\"{}\">{}</td>{}<td class=\"files\">{}</td></tr>\n",
      thumbnail_cell(r.preview_png, "preview", r.name, o), thumbnail_cell(r.plot_svg, "plot", r.name, o),
      escape_markup(r.name), escape_markup(r.kind), static_cast<int>(r.status), status_class(r.status),
      to_string(r.status), message, number_cell(r.max_deviation, units),
      number_cell(r.volume, units.empty() ? "" : units + "\u00b3"),
      number_cell(r.area, units.empty() ? "" : units + "\u00b2"), bbox_cell(r),
      r.triangles ? std::to_string(*r.triangles) : "", r.triangles ? std::to_string(*r.triangles) : "-",
      timing_cell(r), files);
}

std::string counts_html(const HtmlReport& report) {
  std::array<std::size_t, 4> counts{};
  for (const ReportRow& r : report.rows) ++counts[static_cast<std::size_t>(r.status)];
  std::string out = fmt::format("<div class=\"counts\"><span>{} designs</span>", report.rows.size());
  for (const ReportStatus s :
       {ReportStatus::Ok, ReportStatus::Invalid, ReportStatus::BadInput, ReportStatus::Error}) {
    out += fmt::format("<span class=\"status {}\">{} {}</span>", status_class(s),
                       counts[static_cast<std::size_t>(s)], to_string(s));
  }
  return out + "</div>\n";
}

}  // namespace

const char* to_string(ReportStatus status) {
  switch (status) {
    case ReportStatus::Ok:
      return "ok";
    case ReportStatus::Invalid:
      return "invalid";
    case ReportStatus::BadInput:
      return "bad input";
    case ReportStatus::Error:
      return "error";
  }
  return "error";
}

std::string render_report_html(const HtmlReport& report, const HtmlReportOptions& options) {
  require_in_range("html report thumbnail_width", options.thumbnail_width, 16, 1024);
  require_in_range("html report thumbnail_height", options.thumbnail_height, 16, 1024);
  const std::string title = escape_markup(report.title);
  std::string out = fmt::format(
      "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\"/>\n"
      "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\"/>\n<title>{}</title>\n"
      "<style>{}</style>\n<script>{}</script>\n</head>\n<body>\n<h1>{}</h1>\n<div class=\"meta\">{}</div>\n{}"
      "<input id=\"filter\" type=\"search\" placeholder=\"Filter rows (name, kind, status, verdict)\"/>\n"
      "<table id=\"summary\">\n<thead><tr><th>Preview</th><th>Plot</th><th data-type=\"text\">Name</th>"
      "<th data-type=\"text\">Kind</th><th data-type=\"number\">Status</th><th "
      "data-type=\"text\">Verdict</th>"
      "<th data-type=\"number\">Max deviation</th><th data-type=\"number\">Volume</th>"
      "<th data-type=\"number\">Area</th><th data-type=\"number\" title=\"sorted by the largest "
      "side\">Size</th>"
      "<th data-type=\"number\">Triangles</th><th "
      "data-type=\"number\">Time</th><th>Files</th></tr></thead>\n<tbody>\n",
      title, kStyle, kImageScript, title,
      report.generated_by.empty() ? "" : "Generated by " + escape_markup(report.generated_by),
      counts_html(report));
  out.reserve(out.size() + report.rows.size() * 1200);
  for (const ReportRow& r : report.rows) out += row_html(r, options);
  out += fmt::format(
      "</tbody>\n</table>\n<footer><span "
      "id=\"images-status\"></span></footer>\n<script>{}</script>\n</body>\n"
      "</html>\n",
      kScript);
  return out;
}

}  // namespace fabmesh
