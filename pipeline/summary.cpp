#include "pipeline/summary.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

namespace fabmesh {
namespace {

// A casting master cut for the bed: its sections with their heights as
// printed, what each is cut into, and the order to glue them.
void print_master_pieces(const Facts& m, const std::string& u, std::ostream& out) {
  const Facts::Value* listed = m.find("sections");
  if (listed == nullptr) return;
  const auto& sections = std::get<std::vector<Facts>>(*listed);
  const int sectors = static_cast<int>(m.number("sectors"));
  const char* piece = sectors == 2 ? "halves" : "quarters";
  std::string levels;
  std::size_t count = 0;
  for (const Facts& s : sections) {
    if (s.find("from_deg") != nullptr && s.number("from_deg") != 0.0) continue;
    std::string name = s.text("name");
    const std::size_t cut = name.find(sectors == 2 ? "-half-" : "-quarter-");
    name = sectors == 1 ? name : cut == std::string::npos ? std::string("the master") : name.substr(0, cut);
    levels += fmt::format("{}{} {:.4g} {}", count++ == 0 ? "" : ", ", name, s.number("height"), u);
  }
  const Facts& pin = m.group("pin");
  const auto pins = [&](const char* where) {
    return fmt::format("a {:g} {} pin {} into a {:g} {} hole", pin.number("diameter"), u, where,
                       pin.number("hole_diameter"), u);
  };
  if (sectors == 1) {
    out << fmt::format("  master: cut for the bed into {} sections ({} tall as printed), {}\n", count, levels,
                       pins("on the axis at each joint"));
    return;
  }
  out << fmt::format(
      "  master: cut for the bed into {} pieces, {} in {} ({} tall as printed), {}{}\n", sections.size(),
      count == 1 ? "the whole height" : fmt::format("{} sections each", count), piece, levels,
      pins("across every joint"),
      count == 1 ? "" : "; glue each section's pieces together first, then stack the sections");
}

// The headline facts of the builder: shrinkage, the mould, the router path.
void print_build_facts(const Facts& facts, const std::string& u, std::ostream& out) {
  if (facts.contains("shrinkage")) {
    const Facts& s = facts.group("shrinkage");
    const auto& fired = std::get<std::vector<double>>(*s.find("fired_size"));
    out << fmt::format(
        "  shrinkage {}: written {:.6g} times the fired size ({:.6g} x {:.6g} x {:.6g} {} when fired)\n",
        s.number("shrinkage"), s.number("factor"), fired[0], fired[1], fired[2], u);
  }
  if (facts.contains("mould")) {
    const Facts& m = facts.group("mould");
    out << fmt::format(
        "  mould: {} parts, each closed and embedded by construction; slip {:.6g} {}^3, plaster "
        "{:.6g} {}^3\n",
        std::get<std::vector<Facts>>(*m.find("parts")).size(), m.number("slip_volume"), u,
        m.number("plaster_volume"), u);
    out << fmt::format(
        "  casting: {:.0f} g of plaster into {:.0f} g of water ({:.3g} : 1 by weight), {:.0f} ml of slip "
        "({:.0f} g at {:.3g} g/ml) to fill it to the spare\n",
        m.number("plaster_grams"), m.number("water_grams"), m.number("plaster_ratio"),
        m.number("slip_millilitres"), m.number("slip_grams"), m.number("slip_density"));
    if (const Facts::Value* cases = m.find("cases")) {
      // Which way each part leaves its case (the refused ones are warnings).
      const auto& all = std::get<std::vector<Facts>>(*cases);
      std::string made;
      std::size_t count = 0;
      for (const Facts& c : all) {
        if (c.find("refused") != nullptr) continue;
        const auto along = [](const Facts& piece) {
          const auto& pull = std::get<std::vector<double>>(*piece.find("pull"));
          int k = 0;
          while (k < 2 && pull[k] == 0.0) ++k;
          return fmt::format("{}{}", pull[k] > 0.0 ? "+" : "-", "xyz"[k]);
        };
        made += fmt::format("{}{} lifts out along {}", count++ == 0 ? "" : ", ", c.text("part"), along(c));
        if (c.contains("plate"))
          made += fmt::format(" once its plate is off along {}", along(c.group("plate")));
        if (const Facts::Value* pieces = c.find("pieces")) {
          const auto& list = std::get<std::vector<Facts>>(*pieces);
          const bool lid = std::any_of(list.begin(), list.end(),
                                       [](const Facts& p) { return p.text("beyond") == "its curved back"; });
          const std::size_t n = list.size() - (lid ? 1 : 0);
          if (lid && n == 0) made += " once its lid is off";
          if (lid && n > 0)
            made += fmt::format(" once its {} other piece{} and its lid are off", n, n == 1 ? "" : "s");
          if (!lid && n > 0)
            made += fmt::format(" once its {} other piece{} off", n, n == 1 ? " is" : "s are");
        }
      }
      out << fmt::format("  casting cases: {} of {} parts ({})\n", count, all.size(),
                         count == 0 ? "none" : made);
      // The faces the draft leans, part by part.
      std::string leaned;
      std::size_t faces = 0, stay = 0;
      double taken = 0.0, deg = 0.0;
      for (const Facts& c : all) {
        if (!c.contains("draft")) continue;
        const Facts& d = c.group("draft");
        deg = d.number("deg");
        const auto& named = std::get<std::vector<std::string>>(*d.find("faces"));
        stay += std::get<std::vector<std::string>>(*d.find("not_leaned")).size();
        taken += d.number("volume");
        if (named.empty()) continue;
        leaned += fmt::format("{}{}", faces == 0 ? "" : ", ", c.text("part"));
        for (const std::string& f : named)
          leaned += " " + f.substr(f.rfind(' ') + 1);  // "its face across +x"
        faces += named.size();
      }
      if (faces + stay > 0) {
        out << fmt::format(
            "  casting cases' draft: {:g} degree{} on {} face{}{}{}{}\n", deg, deg == 1.0 ? "" : "s", faces,
            faces == 1 ? "" : "s", faces == 0 ? "" : fmt::format(" ({})", leaned),
            faces == 0 ? "" : fmt::format(", taking {:.4g} {}^3 from the parts as cast", taken, u),
            stay == 0 ? ""
                      : fmt::format("; {} more do{} not lean (the report's draft.not_leaned says why)", stay,
                                    stay == 1 ? "es" : ""));
      }
      // The pieces too big for the bed, written in sections.
      std::string cut;
      std::size_t pieces = 0, sections = 0;
      const Facts* pin = nullptr;
      for (const Facts& c : all) {
        std::vector<const Facts*> each{&c};
        if (const Facts::Value* listed = c.find("pieces")) {
          for (const Facts& p : std::get<std::vector<Facts>>(*listed)) each.push_back(&p);
        }
        for (const Facts* p : each) {
          const Facts::Value* listed = p->find("sections");
          if (listed == nullptr) continue;
          const std::size_t n = std::get<std::vector<Facts>>(*listed).size();
          cut += fmt::format("{}{} in {}", pieces++ == 0 ? "" : ", ", p->text("name"), n);
          sections += n;
          pin = &p->group("section_pin");
        }
      }
      if (pin != nullptr) {
        out << fmt::format(
            "  casting cases cut for the bed: {} piece{} in {} sections ({}), two {:g} {} pins "
            "into {:g} {} holes across every joint\n",
            pieces, pieces == 1 ? "" : "s", sections, cut, pin->number("diameter"), u,
            pin->number("hole_diameter"), u);
      }
    }
  }
  if (facts.contains("master")) print_master_pieces(facts.group("master"), u, out);
  if (facts.contains("print")) {
    // A design that prints upright (`print:`) hears what the checks found; the others see it in the report.
    const Facts& p = facts.group("print");
    if (std::get<bool>(*p.find("checked"))) out << "  " << p.text("summary") << "\n";
  }
  if (facts.contains("kitchen")) {
    const Facts& k = facts.group("kitchen");
    std::string used;
    for (const double u_slab : std::get<std::vector<double>>(*k.find("utilisation")))
      used += fmt::format("{}{:.1f}%", used.empty() ? "" : ", ", 100.0 * u_slab);
    int drills = 0;
    if (const Facts::Value* programs = k.find("programs")) {
      for (const Facts& p : std::get<std::vector<Facts>>(*programs))
        drills += p.contains("drills") ? static_cast<int>(p.number("drills")) : 0;
    }
    const std::size_t pieces = std::get<std::vector<Facts>>(*k.find("pieces")).size();
    const std::size_t seams = std::get<std::vector<Facts>>(*k.find("seams")).size();
    const int slabs = static_cast<int>(k.number("slabs"));
    out << fmt::format(
        "  kitchen: {} piece{} at {} seam{} on {} slab{} (no fewer than {} can hold them); usable area "
        "used {}{}\n",
        pieces, pieces == 1 ? "" : "s", seams, seams == 1 ? "" : "s", slabs, slabs == 1 ? "" : "s",
        static_cast<int>(k.number("lower_bound")), used,
        drills == 0 ? std::string()
                    : fmt::format("; {} tap hole{} drilled first", drills, drills == 1 ? "" : "s"));
  }
  if (facts.contains("cnc")) {
    const Facts& c = facts.group("cnc");
    const int drills = c.contains("drills") ? static_cast<int>(c.number("drills")) : 0;
    out << fmt::format("  router path: {} passes, within {:.3g} {} of the exact offset{}\n",
                       static_cast<int>(c.number("passes")), c.number("deviation"), u,
                       drills == 0
                           ? std::string()
                           : fmt::format("; {} tap hole{} drilled first", drills, drills == 1 ? "" : "s"));
  }
}

void print_files(const Result& r, std::ostream& out) {
  for (const OutputFile& f : r.files) out << fmt::format("  wrote {} (in {})\n", f.path, f.units);
}

void print_notes(const Result& r, std::ostream& out) {
  for (const std::string& note : r.notes) out << fmt::format("  note: {}\n", note);
}

double total_ms(const Result& r) {
  double total = 0.0;
  for (const auto& t : r.timings_ms) total += t.second;
  return total;
}

}  // namespace

double summary_number(double x, double extent) { return std::abs(x) < 1e-12 * extent ? 0.0 : x; }

void print_warnings(const Result& r, const std::string& subject, std::ostream& err) {
  for (const SkippedOutput& s : r.skipped)
    err << fmt::format("fabmesh: warning: {}: skipped {}: {}\n", subject, s.format, s.reason);
  for (const std::string& warning : r.warnings) err << fmt::format("fabmesh: warning: {}\n", warning);
}

void print_summary(const Result& r, std::ostream& out) {
  const std::string& u = r.units;
  if (r.purpose == MeshPurpose::Drawing) {
    out << fmt::format("{}: {} drawn at true size, within {:.3g} {} of the exact curve (tolerance {} {})\n",
                       r.name, r.kind, r.max_deviation, u, r.tolerance, u);
    print_files(r, out);
    print_notes(r, out);
    out << fmt::format("  {:.1f} ms\n", total_ms(r));
    return;
  }
  const Part* part = product(r);
  const ValidationReport v = part != nullptr ? part->validation : ValidationReport{};
  // An enclosed volume only exists for a closed mesh.
  const std::string volume =
      v.boundary_edges == 0 ? fmt::format("{:.6g} {}^3", v.volume, u) : std::string("- (open)");
  out << fmt::format("{}: {} with {} vertices, {} triangles, volume {}, area {:.6g} {}^2, genus {}\n", r.name,
                     r.kind, v.vertices, v.triangles, volume, v.area, u,
                     v.genus ? std::to_string(*v.genus) : "-");
  if (!r.parameters.empty()) {
    std::string values;
    for (const DesignParameter& p : r.parameters)
      values += fmt::format("{}{} = {}", values.empty() ? "" : ", ", p.name,
                            p.kind == ParameterKind::Number ? fmt::format("{:.6g}", p.value) : p.text);
    out << "  parameters: " << values
        << (r.parameter_set.empty() ? std::string() : " (set " + r.parameter_set + ")") << "\n";
  }
  const Vec3 size = r.bbox_max - r.bbox_min;
  const double extent =
      std::max({size.maxCoeff(), r.bbox_min.cwiseAbs().maxCoeff(), r.bbox_max.cwiseAbs().maxCoeff()});
  const auto n = [extent](double x) { return summary_number(x, extent); };
  out << fmt::format(
      "  size {:.6g} x {:.6g} x {:.6g} {} (x {:.6g}..{:.6g}, y {:.6g}..{:.6g}, z {:.6g}..{:.6g})\n",
      n(size.x()), n(size.y()), n(size.z()), u, n(r.bbox_min.x()), n(r.bbox_max.x()), n(r.bbox_min.y()),
      n(r.bbox_max.y()), n(r.bbox_min.z()), n(r.bbox_max.z()));
  if (v.valid()) {
    out << fmt::format(
        "  valid: closed, manifold ({}), outward, no self-intersections ({}); within {:.3g} {} of the exact "
        "surface (tolerance {} {})\n",
        v.topology_proof.empty() ? "checked" : "by construction",
        v.self_intersection == IntersectionCheck::ProvenByConstruction ? "by construction" : "checked",
        r.max_deviation, u, r.tolerance, u);
  } else {
    const std::vector<std::string> defects = describe_defects(v);
    out << fmt::format("  for viewing only, not valid for fabrication ({}; {})\n",
                       r.facts.contains("fabrication") ? r.facts.text("fabrication") : "invalid",
                       defects.empty() ? "" : defects.front());
  }
  if (r.parts.size() > 1) {
    for (const Part& p : r.parts) {
      if (p.role == PartRole::Product) continue;
      out << fmt::format("  part {} ({}): {} triangles, volume {:.6g} {}^3, {}\n", p.name, to_string(p.role),
                         p.validation.triangles, p.validation.volume, u,
                         p.validation.valid() ? "valid" : "INVALID");
    }
  }
  print_build_facts(r.facts, u, out);
  print_files(r, out);
  print_notes(r, out);
  out << fmt::format("  {:.1f} ms\n", total_ms(r));
}

}  // namespace fabmesh
