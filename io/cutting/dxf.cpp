#include "io/cutting/dxf.h"

#include <dxflib/dl_dxf.h>
#include <fmt/format.h>
#include <unistd.h>

#include <array>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <memory>
#include <sstream>
#include <vector>

#include "geometry/core/errors.h"
#include "geometry/core/units.h"
#include "io/file.h"

namespace fabmesh {
namespace {

// dxflib writes only to a named file: a private temporary one, removed on every path.
class TempFile {
 public:
  TempFile() {
    std::string pattern = (std::filesystem::temp_directory_path() / "fabmesh-dxf-XXXXXX").string();
    const int fd = mkstemp(pattern.data());
    if (fd < 0)
      throw FileError(pattern, 0, 0, fmt::format("{}: cannot create a temporary DXF file", pattern));
    ::close(fd);
    path_ = pattern;
  }
  ~TempFile() {
    std::error_code ec;
    std::filesystem::remove(path_, ec);
  }
  TempFile(const TempFile&) = delete;
  TempFile& operator=(const TempFile&) = delete;
  const std::string& path() const { return path_; }

 private:
  std::string path_;
};

int insunits(const std::string& units) {
  for (const LengthUnit& u : kLengthUnits) {
    if (u.name == units) return u.dxf_insunits;
  }
  return length_unit("mm").dxf_insunits;
}

// TEXT in the style "Standard"; centred: `at` is the middle of its baseline.
void write_text(DL_Dxf& dxf, DL_WriterA& dw, const Vec2& at, double height, double angle_deg, bool centred,
                const std::string& text, const DL_Attributes& attr) {
  dxf.writeText(dw,
                DL_TextData(at.x(), at.y(), 0.0, at.x(), at.y(), 0.0, height, 1.0, 0, centred ? 1 : 0, 0,
                            text, "Standard", angle_deg * M_PI / 180.0),
                attr);
}

// The name of dimension n's block of geometry (anonymous: *D).
std::string dimension_block(std::size_t n) { return fmt::format("*D{}", n + 1); }

void write_tables(DL_Dxf& dxf, DL_WriterA& dw, const Sheet& sheet) {
  dw.sectionTables();
  dxf.writeVPort(dw);
  dw.tableLinetypes(3);
  dxf.writeLinetype(dw, DL_LinetypeData("BYBLOCK", "BYBLOCK", 0, 0, 0.0));
  dxf.writeLinetype(dw, DL_LinetypeData("BYLAYER", "BYLAYER", 0, 0, 0.0));
  dxf.writeLinetype(dw, DL_LinetypeData("CONTINUOUS", "Continuous", 0, 0, 0.0));
  dw.tableEnd();
  dw.tableLayers(static_cast<int>(sheet.layers.size()) + 1);
  dxf.writeLayer(dw, DL_LayerData("0", 0), DL_Attributes("", DL_Codes::black, 100, "CONTINUOUS", 1.0));
  for (const SheetLayer& layer : sheet.layers)
    dxf.writeLayer(dw, DL_LayerData(layer.name, 0), DL_Attributes("", layer.aci, 100, "CONTINUOUS", 1.0));
  dw.tableEnd();
  dw.tableStyle(1);
  // dxflib records the handle of the style named exactly "Standard" and writes
  // it as the DIMSTYLE's text style (group 340); under another name that
  // handle is never set and 340 carries uninitialised memory.
  dxf.writeStyle(dw, DL_StyleData("Standard", 0, 2.5, 1.0, 0.0, 0, 2.5, "txt", ""));
  dw.tableEnd();
  dxf.writeView(dw);
  dxf.writeUcs(dw);
  dw.tableAppid(1);
  dxf.writeAppid(dw, "ACAD");
  dw.tableEnd();
  // Arrow size, extension line extension, offset and text gap, text height.
  const double h = sheet.text_height;
  if (sheet.dimensions.empty()) {
    dxf.writeDimStyle(dw, 1, 1, 1, 1, 1);
  } else {
    dxf.writeDimStyle(dw, h, 0.5 * h, 0.5 * h, 0.4 * h, h);
  }
  dxf.writeBlockRecord(dw);
  for (std::size_t i = 0; i < sheet.dimensions.size(); ++i) dxf.writeBlockRecord(dw, dimension_block(i));
  dw.tableEnd();
  dw.sectionEnd();
  dw.sectionBlocks();
  for (const char* block : {"*Model_Space", "*Paper_Space", "*Paper_Space0"}) {
    dxf.writeBlock(dw, DL_BlockData(block, 0, 0.0, 0.0, 0.0));
    dxf.writeEndBlock(dw, block);
  }
  // Each dimension's drawing, as a reader shows it: a DIMENSION entity is
  // read (ezdxf) or drawn (most viewers) through this block.
  const DL_Attributes by_block("0", 0, -1, "BYBLOCK", 1.0);
  for (std::size_t i = 0; i < sheet.dimensions.size(); ++i) {
    const DimensionGraphic g = dimension_graphic(sheet.dimensions[i], h);
    const std::string name = dimension_block(i);
    dxf.writeBlock(dw, DL_BlockData(name, 1, 0.0, 0.0, 0.0));
    for (const auto& l : g.lines)
      dxf.writeLine(dw, DL_LineData(l[0].x(), l[0].y(), 0.0, l[1].x(), l[1].y(), 0.0), by_block);
    for (const auto& t : g.arrows) {
      dxf.writeSolid(dw,
                     DL_SolidData(t[0].x(), t[0].y(), 0.0, t[1].x(), t[1].y(), 0.0, t[2].x(), t[2].y(), 0.0,
                                  t[2].x(), t[2].y(), 0.0),
                     by_block);
    }
    write_text(dxf, dw, g.text_at, h, g.text_angle_deg, true, g.text, by_block);
    dxf.writeEndBlock(dw, name);
  }
  dw.sectionEnd();
}

// A linear (rotated) DIMENSION of `d` drawn by block `block`: dxflib's own
// writer leaves out the block (group 2), without which readers drop the
// entity. Its measurement (group 42) is the distance drawn.
void write_dimension(DL_WriterA& dw, const SheetDimension& d, const DimensionGraphic& g,
                     const std::string& block) {
  const DL_Attributes attr(d.layer, 256, -1, "BYLAYER", 1.0);
  const Vec2 u(std::cos(d.angle_deg * M_PI / 180.0), std::sin(d.angle_deg * M_PI / 180.0));
  const Vec2 n(-u.y(), u.x());
  // Group 10: where the dimension line meets the second extension line.
  const Vec2 on_line = d.to + (d.through.dot(n) - d.to.dot(n)) * n;
  dw.entity("DIMENSION");
  dw.dxfString(100, "AcDbEntity");
  dw.entityAttributes(attr);
  dw.dxfString(100, "AcDbDimension");
  dw.dxfString(2, block);
  const auto point = [&](int code, const Vec2& p) {
    dw.dxfReal(code, p.x());
    dw.dxfReal(code + 10, p.y());
    dw.dxfReal(code + 20, 0.0);
  };
  point(10, on_line);
  point(11, g.text_at);
  dw.dxfInt(70, 32);  // rotated (0), its block used by this dimension only (32)
  dw.dxfInt(71, 8);   // text attached at its bottom centre
  dw.dxfReal(42, g.value);
  dw.dxfString(3, "Standard");
  dw.dxfString(100, "AcDbAlignedDimension");
  point(13, d.from);
  point(14, d.to);
  dw.dxfReal(50, d.angle_deg);
  dw.dxfString(100, "AcDbRotatedDimension");
}

void write_arc(DL_Dxf& dxf, DL_WriterA& dw, const EllipseArcParams& a, const DL_Attributes& attr) {
  // DXF arcs run counter-clockwise from the first angle to the second.
  double from = a.from_deg, to = a.to_deg;
  if (to < from) std::swap(from, to);
  const bool whole = to - from >= 360.0;
  if (a.a == a.b) {
    if (whole) {
      dxf.writeCircle(dw, DL_CircleData(a.center.x(), a.center.y(), 0.0, a.a), attr);
    } else {
      dxf.writeArc(
          dw, DL_ArcData(a.center.x(), a.center.y(), 0.0, a.a, from + a.rotation_deg, to + a.rotation_deg),
          attr);
    }
    return;
  }
  // ELLIPSE: major axis vector, minor/major ratio, parameters (radians) measured from the major axis.
  const double rot = a.rotation_deg * M_PI / 180.0;
  Vec2 major(a.a * std::cos(rot), a.a * std::sin(rot));
  double ratio = a.b / a.a, shift = 0.0;
  if (a.b > a.a) {  // the major axis is the rotated y axis; parameters shift by -90 degrees
    major = Vec2(-a.b * std::sin(rot), a.b * std::cos(rot));
    ratio = a.a / a.b;
    shift = -90.0;
  }
  const double p1 = whole ? 0.0 : (from + shift) * M_PI / 180.0;
  const double p2 = whole ? 2.0 * M_PI : (to + shift) * M_PI / 180.0;
  dxf.writeEllipse(
      dw, DL_EllipseData(a.center.x(), a.center.y(), 0.0, major.x(), major.y(), 0.0, ratio, p1, p2), attr);
}

// A rational cubic Bézier span as a SPLINE: degree 3, knots 0 0 0 0 1 1 1 1,
// its 4 control points and, when they differ, their weights (group 41, one
// per control point, after the knots and before the points, in the order of
// the DXF reference). Flags: planar (8), and rational (4) with weights. Equal
// weights are the polynomial cubic, written without weights (they read as 1).
void write_spline(DL_Dxf& dxf, DL_WriterA& dw, const CutEntity& e, const DL_Attributes& attr) {
  const std::array<double, 4>& w = e.weights;
  const bool rational = !(w[1] == w[0] && w[2] == w[0] && w[3] == w[0]);
  dxf.writeSpline(dw, DL_SplineData(3, 8, 4, 0, rational ? 8 | 4 : 8), attr);
  for (const double k : {0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 1.0}) dxf.writeKnot(dw, DL_KnotData(k));
  // dxflib's writeControlPoint leaves the weight out; each is written as the
  // shortest decimal that reads back as the same double (dxfReal's 16
  // decimals would lose a small weight's digits).
  if (rational) {
    for (const double wj : w) dw.dxfString(41, fmt::format("{}", wj));
  }
  for (std::size_t j = 0; j < 4; ++j)
    dxf.writeControlPoint(dw, DL_ControlPointData(e.points[j].x(), e.points[j].y(), 0.0, w[j]));
}

void write_entity(DL_Dxf& dxf, DL_WriterA& dw, const CutEntity& e, bool whole_loop,
                  const DL_Attributes& attr) {
  switch (e.kind) {
    case CutKind::Line:
      dxf.writeLine(dw,
                    DL_LineData(e.points[0].x(), e.points[0].y(), 0.0, e.points[1].x(), e.points[1].y(), 0.0),
                    attr);
      return;
    case CutKind::Arc:
      write_arc(dxf, dw, e.arc, attr);
      return;
    case CutKind::Polyline: {
      // A loop that is one polyline is written closed, without repeating its first point.
      const std::size_t n = whole_loop ? e.points.size() - 1 : e.points.size();
      dxf.writePolyline(dw, DL_PolylineData(static_cast<int>(n), 0, 0, whole_loop ? 1 : 0), attr);
      for (std::size_t i = 0; i < n; ++i)
        dxf.writeVertex(dw, DL_VertexData(e.points[i].x(), e.points[i].y(), 0.0));
      dxf.writePolylineEnd(dw);
      return;
    }
    case CutKind::Spline:
      write_spline(dxf, dw, e, attr);
      return;
  }
}

// dxflib writes the OBJECTS section without owner handles (group 330), so a
// reader that audits the file (ezdxf: "Fixed invalid owner handle in
// DICTIONARY(#D)", 13 such fixes a file) repairs it. Each object is owned by
// the dictionary that lists it (groups 350 and 360 of a DICTIONARY or an
// ACDBDICTIONARYWDFLT); the root dictionary has none. This writes each
// listed object's owner after its handle.
std::string with_object_owners(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  const auto code = [&](std::size_t i) { return std::atoi(lines[i].c_str()); };
  std::size_t first = lines.size();  // the first group of the OBJECTS section
  for (std::size_t i = 0; i + 1 < lines.size(); i += 2) {
    if (code(i) == 2 && lines[i + 1] == "OBJECTS") {
      first = i + 2;
      break;
    }
  }
  std::size_t end = first;
  while (end + 1 < lines.size() && !(code(end) == 0 && lines[end + 1] == "ENDSEC")) end += 2;
  std::map<std::string, std::string> owner;
  std::string type, handle;
  for (std::size_t i = first; i < end; i += 2) {
    const int c = code(i);
    const std::string& value = lines[i + 1];
    if (c == 0) type = value;
    if (c == 5) handle = value;
    if ((c == 350 || c == 360) && (type == "DICTIONARY" || type == "ACDBDICTIONARYWDFLT"))
      owner[value] = handle;
  }
  std::string out;
  for (std::size_t i = 0; i < lines.size(); ++i) {
    out += lines[i];
    out += '\n';
    const bool object_handle = i >= first && i < end && (i - first) % 2 == 1 && code(i - 1) == 5;
    const auto it = object_handle ? owner.find(lines[i]) : owner.end();
    if (it != owner.end() && !(i + 1 < end && code(i + 1) == 330)) out += "330\n" + it->second + "\n";
  }
  return out;
}

}  // namespace

std::string encode_dxf_sheet(const Sheet& sheet, const DxfOptions& options) {
  const TempFile tmp;
  {
    DL_Dxf dxf;
    std::unique_ptr<DL_WriterA> dw(dxf.out(tmp.path().c_str(), DL_Codes::AC1015));
    if (!dw) throw FileError(tmp.path(), 0, 0, fmt::format("{}: dxflib cannot open the file", tmp.path()));
    dxf.writeHeader(*dw);
    dw->dxfString(9, "$INSUNITS");
    dw->dxfInt(70, insunits(options.units));
    dw->sectionEnd();
    write_tables(dxf, *dw, sheet);
    dw->sectionEntities();
    for (const SheetLoop& l : sheet.loops) {
      const DL_Attributes attr(l.layer, 256, -1, "BYLAYER", 1.0);
      const bool whole_loop = l.loop.closed && l.loop.entities.size() == 1;
      for (const CutEntity& e : l.loop.entities) write_entity(dxf, *dw, e, whole_loop, attr);
    }
    for (const SheetLine& l : sheet.lines) {
      dxf.writeLine(*dw, DL_LineData(l.from.x(), l.from.y(), 0.0, l.to.x(), l.to.y(), 0.0),
                    DL_Attributes(l.layer, 256, -1, "BYLAYER", 1.0));
    }
    for (const SheetText& t : sheet.texts) {
      write_text(dxf, *dw, t.at, t.height, 0.0, t.centred, t.text,
                 DL_Attributes(t.layer, 256, -1, "BYLAYER", 1.0));
    }
    for (std::size_t i = 0; i < sheet.dimensions.size(); ++i) {
      const SheetDimension& d = sheet.dimensions[i];
      write_dimension(*dw, d, dimension_graphic(d, sheet.text_height), dimension_block(i));
    }
    dw->sectionEnd();
    dxf.writeObjects(*dw);
    dxf.writeObjectsEnd(*dw);
    dw->dxfEOF();
    dw->close();
  }
  return with_object_owners(read_file(tmp.path()));
}

std::string encode_dxf(const std::vector<CutLoop>& loops, const DxfOptions& options) {
  Sheet sheet;
  sheet.layers = {{"OUTLINE", DL_Codes::red, "red"}, {"HOLES", DL_Codes::blue, "blue"}};
  for (const CutLoop& loop : loops) sheet.loops.push_back({loop.outer ? "OUTLINE" : "HOLES", loop});
  return encode_dxf_sheet(sheet, options);
}

}  // namespace fabmesh
