// Uses the installed fabmesh library: builds a vessel from a design given as
// YAML text, then validates two meshes given as arrays, a closed tetrahedron
// and the same with a face removed. Exits 0 when the verdicts are the
// expected ones (the vessel and the tetrahedron valid, the open one invalid).
#include <fabmesh/fabmesh.h>

#include <cstdint>
#include <exception>
#include <iostream>
#include <vector>

namespace {

constexpr const char* kCup = R"(name: cup
kind: vessel
units: cm
tolerance: 0.005
profile:
  family: quasi_bspline
  points: [[1.5, 6], [1, 5], [2, 4], [3, 3], [1.5, 2]]
body: {mode: shell, wall: 0.3, base: 0.4}
)";

const char* verdict(bool valid) { return valid ? "valid" : "invalid"; }

}  // namespace

int main() {
  try {
    std::cout << "fabmesh " << fabmesh::version() << " (headers " << FABMESH_VERSION_STRING << ")\n";
    bool ok = true;

    const fabmesh::Design design = fabmesh::parse_design(kCup);
    const fabmesh::Result cup = fabmesh::build(design);
    std::cout << design.kind() << " '" << design.name() << "': " << cup.triangles.size() << " triangles, "
              << verdict(cup.valid) << ", within " << cup.max_deviation << " "
              << fabmesh::to_string(cup.units) << "\n";
    ok = ok && cup.valid && !cup.triangles.empty();

    // A tetrahedron, its faces counter-clockwise seen from outside.
    fabmesh::Mesh tetrahedron;
    tetrahedron.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    tetrahedron.triangles = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
    const fabmesh::ValidationReport closed = fabmesh::validate(tetrahedron);
    std::cout << "closed tetrahedron: " << verdict(closed.valid) << ", volume " << closed.volume << "\n";
    ok = ok && closed.valid;

    // The same arrays through a view, one face left out: three boundary edges.
    const std::vector<double> xyz = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};
    const std::vector<std::int64_t> faces = {0, 2, 1, 0, 1, 3, 0, 3, 2};
    fabmesh::MeshView open;
    open.vertices = xyz.data();
    open.vertex_count = 4;
    open.triangles = faces.data();
    open.triangle_count = 3;
    const fabmesh::ValidationReport opened = fabmesh::validate(open);
    std::cout << "tetrahedron without a face: " << verdict(opened.valid) << ", " << opened.boundary_edges
              << " boundary edges\n";
    ok = ok && !opened.valid && opened.boundary_edges == 3;

    std::cout << (ok ? "as expected" : "NOT as expected") << "\n";
    return ok ? 0 : 1;
  } catch (const fabmesh::Error& e) {
    std::cerr << "fabmesh error: " << e.what() << "\n";
    return 2;
  }
}
