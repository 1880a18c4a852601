// Times the stages of writing a validated mesh as Draco, on a binary STL
// (welded exactly), against writing it as STL: where the Draco output's time
// goes. Build with -DFABMESH_BUILD_BENCH=ON in Release (target draco_stages):
//
//   build-bench/bench/draco_stages MESH.stl TOLERANCE [RUNS]
//
// TOLERANCE is the distance (the STL's units) the Draco output may move a
// vertex. Prints the median of RUNS (default 7) runs of each stage, in ms.

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <functional>
#include <string>
#include <vector>

#include "geometry/mesh/weld.h"
#include "geometry/validation/detail/self_intersect.h"
#include "geometry/validation/detail/topology.h"
#include "geometry/validation/detail/triangle_bvh.h"
#include "geometry/validation/validate.h"
#include "io/file.h"
#include "io/mesh/draco.h"
#include "io/mesh/stl.h"

namespace {

double median_ms(int runs, const std::function<void()>& f) {
  std::vector<double> ms;
  for (int i = 0; i < runs; ++i) {
    const auto start = std::chrono::steady_clock::now();
    f();
    ms.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
  }
  std::sort(ms.begin(), ms.end());
  return ms[ms.size() / 2];
}

}  // namespace

int main(int argc, char** argv) {
  using namespace fabmesh;
  if (argc < 3) {
    fmt::print(stderr, "usage: draco_stages MESH.stl TOLERANCE [RUNS]\n");
    return 2;
  }
  const TriangleSoup soup = weld(parse_stl(read_file(argv[1]), argv[1])).soup;
  const double tolerance = std::atof(argv[2]);
  const int runs = argc > 3 ? std::atoi(argv[3]) : 7;
  const ValidationReport report = validate(soup);
  ValidationOptions moved;  // the decoded meshes are moved copies of `soup`
  moved.moved_from = MovedFrom{&soup, &report};
  int tries = 0;
  const auto fit = [&](const TriangleSoup& decoded) {
    ++tries;
    return validate(decoded, moved).valid();
  };
  const DracoFit found = fit_draco(soup, tolerance, fit, "drc");
  const std::string bytes = encode_draco_bits(soup, found.bits);
  fmt::print("{} triangles, {} bits after {} tries, {} bytes of Draco, moved by up to {:.3g}\n",
             soup.triangles.size(), found.bits, tries, bytes.size(), found.max_displacement);
  const auto row = [&](const char* what, const std::function<void()>& f) {
    fmt::print("{:<44} {:8.2f} ms\n", what, median_ms(runs, f));
  };
  row("encode_stl", [&] { (void)encode_stl(soup); });
  row("encode_draco_bits (no ids)", [&] { (void)encode_draco_bits(soup, found.bits); });
  row("parse_draco (decode to a soup)", [&] { (void)parse_draco(bytes, "drc"); });
  row("analyse_topology (decoded)", [&] { (void)analyse_topology(found.decoded); });
  row("find_self_intersections (decoded, parallel)", [&] { (void)find_self_intersections(found.decoded); });
  SelfIntersectOptions serial;
  serial.parallel = false;
  row("find_self_intersections (decoded, 1 thread)",
      [&] { (void)find_self_intersections(found.decoded, {}, serial); });
  std::size_t pairs = 0, adjacent = 0;
  row("TriangleBvh build + traversal, count pairs", [&] {
    const TriangleBvh bvh(found.decoded, {}, false);
    TriangleBvh::TaskCursor cursor(bvh, 1024);
    std::vector<TriangleBvh::Task> tasks;
    pairs = adjacent = 0;
    while (cursor.next(64, tasks)) {
      for (const auto& task : tasks) {
        bvh.run(task, [&](std::size_t i, std::size_t j) {
          ++pairs;
          const auto& a = found.decoded.triangles[bvh.face(i)];
          const auto& b = found.decoded.triangles[bvh.face(j)];
          for (int x = 0; x < 3; ++x)
            for (int y = 0; y < 3; ++y)
              if (a[x] == b[y]) {
                ++adjacent;
                x = y = 3;
              }
        });
      }
    }
  });
  fmt::print("  {} candidate pairs, {} of them adjacent\n", pairs, adjacent);
  row("validate (decoded, full)", [&] { (void)validate(found.decoded); });
  row("validate, moved_from (decoded)", [&] { (void)validate(found.decoded, moved); });
  row("fit_draco (validate moved_from as accept)", [&] { (void)fit_draco(soup, tolerance, fit, "drc"); });
  row("require_draco_matches", [&] { require_draco_matches(bytes, found); });
  return 0;
}
