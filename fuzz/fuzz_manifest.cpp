// libFuzzer entry for batch manifests (io/design/manifest.h): the input is a
// manifest's text, parsed as DIR/m.yaml by parse_manifest. DIR, made once per
// process (fuzz/temp_folder.h) and removed at exit, holds the files
// manifests name: a copy of configs/examples (the bundled manifests' designs
// and table), cup.yaml (the tests' cup) and t.csv (a table of cup variants),
// so the seeds (tests/data/fuzz-seeds/manifest/) read real bases and tables.
//
// parse_manifest may only return or throw FileError (bad input, located);
// anything else (a crash, another exception, a sanitizer report, a hang
// caught by -timeout, memory beyond -rss_limit_mb) is a finding. What it
// returns must hold what manifest.h documents: a base per label, at least
// one and at most kMaxBatchVariants variants, each (of the first 64, the
// middle and the last) with a base, a plain, unreserved name unique among
// those checked, override paths that parse, and range values finite within
// kMaxDesignNumber. A manifest of at most 16 variants is also planned
// (plan_batch, which reads nothing beyond what the bases read), and the plan
// must name the manifest's variants with well-formed keys.

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <set>
#include <stdexcept>
#include <string>
#include <string_view>
#include <system_error>
#include <vector>

#include "fuzz/temp_folder.h"
#include "geometry/core/errors.h"
#include "io/design/manifest.h"
#include "io/design/number_limits.h"
#include "io/design/overrides.h"
#include "io/design/read_design.h"
#include "pipeline/batch/plan.h"
#include "tests/io/design/cup_design.h"

namespace {

namespace fs = std::filesystem;

// Manifests this small are planned too (a plan resolves every variant).
constexpr std::size_t kMaxPlanned = 16;
// The variants checked one by one: the first ones, the middle and the last.
constexpr std::size_t kCheckedFirst = 64;

// The table of the manifest tests: a name column, a quoted list, a blank
// line and an empty cell (the base's value), CRLF and LF line ends.
constexpr const char* kTable =
    "name,body.wall,profile.points[1]\r\n"
    "thin,0.2,\"[1.2, 5]\"\r\n"
    "\r\n"
    "plain,,\n";

void require(bool holds) {
  if (!holds) __builtin_trap();
}

void write_text(const fs::path& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
}

std::string make_fixture() {
  const std::string dir = fabmesh::fuzz::make_temp_folder("fuzz-manifest");
  // Without the examples the bundled seeds only reach "missing file": say so.
  std::error_code ec;
  fs::copy(FABMESH_FUZZ_EXAMPLES, dir, fs::copy_options::overwrite_existing, ec);
  if (ec) {
    std::fprintf(stderr, "fuzz_manifest: cannot copy %s: %s\n", FABMESH_FUZZ_EXAMPLES, ec.message().c_str());
    std::abort();
  }
  write_text(fs::path(dir) / "cup.yaml", fabmesh::test::kCup);
  write_text(fs::path(dir) / "t.csv", kTable);
  return dir;
}

// This process's fixture folder, made on first use, removed at exit.
const std::string& fixture() { return fabmesh::fuzz::process_folder<make_fixture>(); }

bool ends_with(const std::string& text, std::string_view end) {
  return text.size() >= end.size() && text.compare(text.size() - end.size(), end.size(), end) == 0;
}

// A value a range {from, to, steps} made: its text says "(..., value I of N)".
bool from_range(const fabmesh::Override& o) {
  const std::size_t of = o.text.rfind(" of ");
  return ends_with(o.text, ")") && of != std::string::npos &&
         o.text.find(", value ", 0) != std::string::npos &&
         std::all_of(o.text.begin() + static_cast<std::ptrdiff_t>(of + 4), o.text.end() - 1,
                     [](char c) { return c >= '0' && c <= '9'; });
}

void require_bounded_number(const std::string& text) {
  char* end = nullptr;
  const double v = std::strtod(text.c_str(), &end);
  require(!text.empty() && *end == '\0');
  require(std::isfinite(v) && std::abs(v) <= fabmesh::kMaxDesignNumber);
}

// An override path as the manifest checked it: one parse_override accepts.
void require_path(const std::string& path) {
  try {
    require(fabmesh::parse_override(path + "=0").path == path);
  } catch (const fabmesh::InputError&) {
    __builtin_trap();
  }
}

void check_variant(const fabmesh::BatchManifest& m, std::size_t i, std::set<std::string>& names) {
  const fabmesh::Variant v = m.variant(i);
  require(v.base < m.bases.size());
  require(fabmesh::plain_name_problem(v.name).empty());
  const auto& reserved = fabmesh::reserved_variant_names();
  require(std::find(reserved.begin(), reserved.end(), v.name) == reserved.end());
  require(names.insert(v.name).second);
  for (const fabmesh::Override& o : v.overrides) {
    require_path(o.path);
    require(o.path != "kind");
    if (o.path != "name")
      require(std::find(m.parameters.begin(), m.parameters.end(), o.path) != m.parameters.end());
    if (from_range(o)) require_bounded_number(o.value);
  }
  const std::vector<fabmesh::Override> all = fabmesh::variant_overrides(m, v);
  require(!all.empty() && all.back().path == "name");
}

void check_plan(const fabmesh::BatchManifest& m) {
  const auto is_key = [](const std::string& k) {
    return k.size() == 64 && k.find_first_not_of("0123456789abcdef") == std::string::npos;
  };
  const fabmesh::BatchPlan plan = fabmesh::plan_batch(m);
  require(plan.size() == m.variant_count());
  require(is_key(plan.digest));
  for (std::size_t i = 0; i < plan.size(); ++i) {
    const std::string name = m.variant(i).name;
    require(plan.name(i) == name && plan.find(name) == i);
    require(is_key(plan.key(i)));
  }
}

void check_manifest(const fabmesh::BatchManifest& m, const std::string& path) {
  require(m.path == path);
  require(!m.bases.empty() && m.bases.size() == m.base_labels.size());
  const std::size_t n = m.variant_count();
  require(n >= 1 && n <= fabmesh::kMaxBatchVariants && n % m.bases.size() == 0);
  require(std::set<std::string>(m.parameters.begin(), m.parameters.end()).size() == m.parameters.size());
  require(std::find(m.parameters.begin(), m.parameters.end(), "name") == m.parameters.end());
  for (const fabmesh::Override& o : m.common) require_path(o.path);
  std::set<std::string> names;
  for (std::size_t i = 0; i < std::min(n, kCheckedFirst); ++i) check_variant(m, i, names);
  for (const std::size_t i : {n / 2, n - 1}) {
    if (i >= kCheckedFirst) check_variant(m, i, names);
  }
  try {
    m.variant(n);
    __builtin_trap();  // there is no variant n
  } catch (const std::out_of_range&) {
  }
  if (n <= kMaxPlanned) check_plan(m);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  const std::string path = (fs::path(fixture()) / "m.yaml").string();
  fabmesh::BatchManifest manifest;
  try {
    manifest = fabmesh::parse_manifest(text, path);
  } catch (const fabmesh::FileError&) {
    return 0;  // rejected cleanly
  }
  check_manifest(manifest, path);
  return 0;
}
