// Budgets are checked before the work: designs whose tolerance needs far
// more triangles than their budget are refused at once with a BudgetError
// naming the tolerance, the estimate and the budget. Each case runs the real
// binary under a memory and a time limit enforced by the harness (before the
// estimates these cases took minutes to tens of minutes, or gigabytes).

#include <unistd.h>

#include <catch2/catch.hpp>
#include <filesystem>
#include <string>

#include "io/file.h"
#include "tests/pipeline/cli_harness.h"
#include "tests/pipeline/limited_run.h"

using namespace fabmesh;
using namespace fabmesh::testing;
namespace fs = std::filesystem;

namespace {

constexpr std::size_t kMemory = std::size_t{1} << 30;  // 1 GiB (address space; resident under ASan)

// Runs `design` under the time and memory limits; its exit code (2 when the
// budget refused it early, as the checks inside require).
int refused_code(const std::string& design, const fs::path& dir, double seconds) {
  const LimitedRun r = run_limited({"run", design, "-o", (dir / "out").string()}, seconds, kMemory);
  INFO(design << ": " << r.describe() << "\n" << r.out << r.err);
  REQUIRE_FALSE(r.timed_out);
  REQUIRE(r.signal == 0);
  CHECK_THAT(r.out + r.err,
             Catch::Contains("budget of") && Catch::Contains("at least") && Catch::Contains("tolerance"));
  CHECK(names_place(r.err, design, "tolerance"));  // at the key that asked for it
  CHECK((!fs::exists(dir / "out") || fs::is_empty(dir / "out")));
  return r.code;
}

}  // namespace

TEST_CASE("budget: a surface at tolerance 1e-12 is refused before refining", "[pipeline][budget]") {
  const fs::path dir = fresh_dir("budget_surface_tiny");
  CHECK(refused_code(edited_example(dir, "surface_basin_shell.yaml", "tolerance: 0.5", "tolerance: 1e-12",
                                    "tiny.yaml"),
                     dir, 20.0) == 2);
}

TEST_CASE("budget: a surface with max_triangles 2e9 at tolerance 1e-9 is refused before refining",
          "[pipeline][budget]") {
  const fs::path dir = fresh_dir("budget_surface_huge");
  CHECK(refused_code(edited_example(dir, "surface_basin_open.yaml", "tolerance: 0.5",
                                    "tolerance: 1e-9\nmax_triangles: 2e9", "huge.yaml"),
                     dir, 20.0) == 2);
}

TEST_CASE("budget: a vessel at tolerance 1e-12 is refused before sampling", "[pipeline][budget]") {
  const fs::path dir = fresh_dir("budget_vessel_tiny");
  CHECK(refused_code(edited_example(dir, "vessel_golden_shell.yaml", "tolerance: 0.005", "tolerance: 1e-12",
                                    "tiny.yaml"),
                     dir, 20.0) == 2);
}

TEST_CASE("budget: a vessel with max_triangles 2e9 at tolerance 1e-9 is refused before sampling",
          "[pipeline][budget]") {
  const fs::path dir = fresh_dir("budget_vessel_huge");
  CHECK(refused_code(edited_example(dir, "vessel_golden_shell.yaml", "tolerance: 0.005",
                                    "tolerance: 1e-9\nmax_triangles: 2e9", "huge.yaml"),
                     dir, 20.0) == 2);
}

TEST_CASE("budget: a vessel larger than the process's memory is refused before allocating it",
          "[pipeline][budget]") {
  // 1.77e9 triangles: within max_triangles 2e9, but its arrays need 42.5 GB.
  // The process may use the smaller of the machine's memory and its address
  // space limit (1 GiB here; under ASan, which cannot run with one, the
  // machine's memory, which must then be smaller than 42.5 GB).
#ifdef FABMESH_TEST_ASAN
  const double machine =
      static_cast<double>(::sysconf(_SC_PHYS_PAGES)) * static_cast<double>(::sysconf(_SC_PAGESIZE));
  INFO("this case needs a machine with less than 42.5 GB of memory under ASan; this one has "
       << machine * 1e-9);
  REQUIRE(machine < 42e9);
#endif
  const fs::path dir = fresh_dir("budget_vessel_memory");
  const std::string design = edited_example(dir, "vessel_golden_shell.yaml", "tolerance: 0.005",
                                            "tolerance: 4e-8\nmax_triangles: 2e9", "dense.yaml");
  const LimitedRun r = run_limited({"run", design, "-o", (dir / "out").string()}, 20.0, kMemory);
  INFO(r.describe() << "\n" << r.out << r.err);
  REQUIRE_FALSE(r.timed_out);
  REQUIRE(r.signal == 0);
  CHECK(r.code == 2);
  CHECK_THAT(r.err, Catch::Contains("1771791528 triangles and 42.5 GB of memory, more than the") &&
                        Catch::Contains("GB this process can use"));
  CHECK(names_place(r.err, design, "tolerance"));
  CHECK((!fs::exists(dir / "out") || fs::is_empty(dir / "out")));
}

TEST_CASE("budget: a countertop at tolerance 1e-12 is refused before sampling", "[pipeline][budget]") {
  const fs::path dir = fresh_dir("budget_countertop_tiny");
  CHECK(refused_code(
            edited_example(dir, "countertop_g2.yaml", "tolerance: 0.05", "tolerance: 1e-12", "tiny.yaml"),
            dir, 20.0) == 2);
}

TEST_CASE("budget: the surface shell at 0.001 mm ends within its limits with a budget error",
          "[pipeline][budget]") {
  // Under the estimate (the shell's offset sheets need more than the surface
  // alone), so refinement runs, but in memory linear in the grid lines; it
  // had not finished after 580 s before.
  const fs::path dir = fresh_dir("budget_surface_fine");
  const std::string design =
      edited_example(dir, "surface_basin_shell.yaml", "tolerance: 0.5", "tolerance: 0.001", "fine.yaml");
  const LimitedRun r = run_limited({"run", design, "-o", (dir / "out").string()}, 120.0, kMemory);
  INFO(r.describe() << "\n" << r.out << r.err);
  REQUIRE_FALSE(r.timed_out);
  REQUIRE(r.signal == 0);
  CHECK(r.code == 2);
  CHECK_THAT(r.out + r.err, Catch::Contains("budget of"));
  CHECK((!fs::exists(dir / "out") || fs::is_empty(dir / "out")));
}
