"""The Python module against the command line: the same verdicts, reports and bytes."""

import json
import math
import subprocess
import threading

import meshio
import numpy as np
import pytest

import fabmesh
from conftest import BINARY, cli, corpus, example, without_timings

GOLDEN_VOLUME_CM3 = 46.171424531125  # the golden solid's exact volume (quasi-cubic B-spline profile)


def tetrahedron():
    vertices = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]], dtype=np.float64)
    triangles = np.array([[0, 2, 1], [0, 1, 3], [1, 2, 3], [0, 3, 2]], dtype=np.int64)
    return vertices, triangles


def test_version_is_the_programs():
    code, out = cli("--version")
    assert code == 0
    assert out.strip() == "fabmesh " + fabmesh.__version__


def test_golden_cup_volume_within_what_the_tolerance_implies():
    design = fabmesh.read_design(example("vessel_golden_solid.yaml"))
    assert (design.kind, design.units) == ("vessel", fabmesh.Unit.cm)
    assert design.units == "cm"  # a Unit is its text too
    result = fabmesh.build(design)
    assert result.valid
    assert result.vertices.dtype == np.float64 and result.vertices.shape[1] == 3
    assert result.triangles.shape == (result.to_dict()["triangles"], 3)
    v, t = result.vertices, result.triangles
    volume = np.einsum("ij,ij->i", v[t[:, 0]], np.cross(v[t[:, 1]], v[t[:, 2]])).sum() / 6
    area = result.to_dict()["area"]
    # A surface within d of the exact one encloses a volume within area * d of the exact.
    assert abs(volume - GOLDEN_VOLUME_CM3) <= area * result.max_deviation
    assert result.max_deviation <= design.tolerance


def test_report_is_the_run_json_item(scratch):
    path = example("vessel_golden_solid.yaml")
    result = fabmesh.build(fabmesh.read_design(path))
    # The library's report names outputs under "out/", as `run` does from the current folder.
    done = subprocess.run([BINARY, "run", path, "--json"], capture_output=True, text=True, cwd=scratch,
                          check=True)
    assert without_timings(result.to_dict()) == without_timings(json.loads(done.stdout)[0])


def test_write_gives_the_command_lines_bytes(scratch):
    path = example("vessel_golden_solid.yaml")
    result = fabmesh.build(fabmesh.read_design(path))
    for ext in ("stl", "3mf", "glb"):
        result.write(str(scratch / f"lib.{ext}"))
        code, _ = cli("run", path, "-o", str(scratch / f"cli.{ext}"))
        assert code == 0
        assert (scratch / f"lib.{ext}").read_bytes() == (scratch / f"cli.{ext}").read_bytes()
    files = result.outputs(str(scratch / "all"))
    assert files and all(p.startswith(str(scratch / "all")) for p in files)


def test_build_write_3mf_then_check_file_round_trip(scratch):
    result = fabmesh.build(fabmesh.read_design(example("vessel_golden_solid.yaml")))
    result.write(str(scratch / "cup.3mf"))
    item = fabmesh.check_file(str(scratch / "cup.3mf")).to_dict()
    assert item["valid"] is True
    assert item["format"] == "3MF"
    assert item["triangles"] == len(result.triangles)


def test_meshio_reads_what_write_writes(scratch):
    result = fabmesh.build(fabmesh.read_design(example("vessel_golden_solid.yaml")))
    for ext in ("stl", "obj", "ply", "off"):
        path = scratch / f"cup.{ext}"
        fabmesh.write_mesh(str(path), result.vertices, result.triangles)
        mesh = meshio.read(str(path))
        assert len(mesh.cells_dict["triangle"]) == len(result.triangles)
    result.write(str(scratch / "cup_run.stl"))
    mesh = meshio.read(str(scratch / "cup_run.stl"))
    assert len(mesh.cells_dict["triangle"]) == len(result.triangles)


def test_check_arrays_agrees_with_check_file_and_the_command_line(scratch):
    for name in ("inverted-component.obj", "cavity.obj", "nested-same-orientation.obj"):
        code, out = cli("check", corpus(name), "--json")
        cli_item = json.loads(out)[0]
        file_item = fabmesh.check_file(corpus(name)).to_dict()
        assert without_timings(file_item) == without_timings(cli_item)
        assert file_item["valid"] is (code == 0)


def test_multi_object_file_agrees_with_the_command_line():
    path = corpus("objects/interpenetrating-cubes.3mf")
    code, out = cli("check", path, "--json")
    assert without_timings(fabmesh.check_file(path).to_dict()) == without_timings(json.loads(out)[0])


def test_an_invalid_mesh_is_a_verdict_not_an_exception():
    v, t = tetrahedron()
    assert fabmesh.check(v, t).valid is True
    item = fabmesh.check(v, t[:3]).to_dict()
    assert item["valid"] is False
    assert item["boundary_edges"] == 3
    inverted = fabmesh.check(v, t[:, ::-1]).to_dict()
    assert inverted["valid"] is False


@pytest.mark.parametrize("vertices, triangles, argument", [
    (np.zeros((4, 2)), np.zeros((1, 3), dtype=np.int64), "vertices"),
    (np.zeros((4, 3)), np.zeros((1, 4), dtype=np.int64), "triangles"),
    (np.zeros((4, 3)), np.array([[0, 1, 4]]), "triangles"),
    (np.zeros((4, 3)), np.array([[0, 1, -1]]), "triangles"),
    (np.zeros((4, 3)), np.array([[0.0, 1.5, 2.0]]), "triangles"),
    (np.zeros((4, 3)), "not an array", "triangles"),
    (np.array([["a", "b", "c"]]), np.zeros((0, 3), dtype=np.int64), "vertices"),
])
def test_bad_arrays_raise_input_error_naming_the_argument(vertices, triangles, argument):
    with pytest.raises(fabmesh.InputError) as caught:
        fabmesh.check(vertices, triangles)
    assert caught.value.key == argument
    assert isinstance(caught.value, ValueError)
    assert caught.value.exit_code == 2


def test_odd_but_valid_arrays_are_accepted():
    v, t = tetrahedron()
    assert fabmesh.check(v.astype(np.float32), t.astype(np.int32)).valid is True
    wide = np.zeros((4, 6))
    wide[:, ::2] = v
    assert fabmesh.check(wide[:, ::2], t).valid is True  # not contiguous
    assert fabmesh.check(v.tolist(), t.tolist()).valid is True


def test_a_non_finite_vertex_is_bad_input_as_in_a_file(scratch):
    # `fabmesh check` refuses a file with a NaN coordinate (exit 2); arrays get the same InputError.
    v, t = tetrahedron()
    nan = v.astype(np.float32)
    nan[1, 1] = np.nan
    with pytest.raises(fabmesh.InputError) as caught:
        fabmesh.check(nan, t)
    assert caught.value.key == "vertices"
    assert caught.value.exit_code == 2
    assert "vertex 1" in str(caught.value)
    path = scratch / "nan.obj"  # the same mesh as a file: the item of `check --json`, exit code 2
    path.write_text("v 0 0 0\nv 1 nan 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 2 3 4\nf 3 1 4\n")
    item = fabmesh.check_file(str(path)).to_dict()
    assert item["valid"] is False and item["exit_code"] == 2 and "error" in item
    code, _ = cli("check", str(path))
    assert code == 2


def test_design_errors_carry_their_place(scratch):
    with pytest.raises(fabmesh.InputError) as caught:
        fabmesh.read_design(example("vessel_golden_solid.yaml"), overrides={"body.wal": 0.25})
    assert caught.value.key == "body.wal"
    text = (open(example("vessel_golden_solid.yaml")).read()).replace("lambdas: [0, 0, 0]", "lambdas: [0, 0, 7]")
    with pytest.raises(fabmesh.InputError) as caught:
        fabmesh.parse_design(text)
    error = caught.value
    line = text[:text.index("lambdas: [0, 0, 7]")].count("\n") + 1  # where the example has its lambdas
    assert (error.file, error.line) == ("design.yaml", line)
    assert error.column > 0
    assert str(error).startswith(f"design.yaml:{line}:")
    with pytest.raises(fabmesh.InputError), pytest.deprecated_call():
        fabmesh.load_design(example("vessel_golden_solid.yaml"), text="name: x")
    with pytest.raises(fabmesh.InputError):
        fabmesh.read_design(str(scratch / "caf\udce9.yaml"))


def test_overrides_have_the_command_line_meaning():
    design = fabmesh.read_design(example("vessel_golden_solid.yaml"),
                                 overrides={"name": "tall", "profile.points[0]": [1.5, 7]})
    assert design.name == "tall"
    assert fabmesh.build(design).valid


def test_curves():
    c = fabmesh.tbezier([[0, 0], [1, 2], [3, 2], [4, 0]], lam=0.5, mu=-0.5)
    assert np.allclose(c.evaluate(0.0), [0, 0]) and np.allclose(c.evaluate(1.0), [4, 0])
    ts = np.linspace(0, 1, 11)
    assert c.evaluate(ts).shape == (11, 2)
    h = 1e-6
    fd = (c.evaluate(0.3 + h) - c.evaluate(0.3 - h)) / (2 * h)
    assert np.allclose(c.derivative(0.3), fd, rtol=1e-6)
    points, bound = c.sample(1e-4)
    assert points.shape[1] == 2 and bound <= 1e-4
    assert math.isfinite(c.curvature(0.5))
    with pytest.raises(fabmesh.InputError) as caught:
        fabmesh.tbezier([[0, 0], [1, 2], [3, 2], [4, 0]], lam=3)
    assert caught.value.exit_code == 2
    b = fabmesh.quasi_bspline([[1.5, 6], [1, 5], [2, 4], [3, 3], [1.5, 2]])
    assert b.sample(1e-3)[1] <= 1e-3
    assert fabmesh.hbezier([[0, 0], [1, 2], [3, 2], [4, 0]], alpha=2).segments == 1
    assert b.through is None


def test_quasi_bspline_through_points():
    golden = fabmesh.quasi_bspline([[1.5, 6], [1, 5], [2, 4], [3, 3], [1.5, 2]], [0, 0.5, 0])
    joints = golden.evaluate(np.arange(golden.segments + 1, dtype=float))
    c = fabmesh.quasi_bspline_through(joints, [0, 0.5, 0])
    t = c.through
    assert np.array_equal(t["points"], joints)
    assert np.abs(t["control_points"] - [[1.5, 6], [1, 5], [2, 4], [3, 3], [1.5, 2]]).max() < 1e-12
    assert 0 <= t["deviation"] < 1e-13
    met = np.hypot(*(c.evaluate(np.arange(5, dtype=float)) - joints).T)
    assert met.max() <= t["deviation"] + 1e-14
    # A design's through: curve is the same curve.
    built = fabmesh.build(fabmesh.parse_design(
        "name: p\nkind: curve\nunits: cm\ntolerance: 0.005\ncurve:\n  family: quasi_bspline\n"
        "  through: " + str(joints.tolist()) + "\n  lambdas: [0, 0.5, 0]\n"))
    assert np.array_equal(built.curves[0].curve.through["control_points"], t["control_points"])
    with pytest.raises(fabmesh.InputError) as singular:
        fabmesh.quasi_bspline_through([[0, 0], [1, 1], [2, 0]], [-8])
    assert singular.value.key == "through" and singular.value.exit_code == 2
    with pytest.raises(fabmesh.InputError) as count:
        fabmesh.quasi_bspline_through([[0, 0], [1, 1], [2, 0]], [0, 0])
    assert count.value.key == "lambdas"
    with pytest.raises(fabmesh.InputError) as faired:
        fabmesh.fair(c, "strain")
    assert faired.value.key == "curve"


MIXED_DESIGN = """
name: mixed
kind: curve
tolerance: 0.01
curve:
  family: tbezier
  segments:
    - points: [[0, 0], [1, 2], [3, 3], [4, 1]]
      lambda: 0.5
    - family: hbezier
      join: {continuity: G2, k: 1.5, m: 0.25}
      points: [[8, 0]]
      alpha: 2
      mu: -1
    - line: {to: [10, -3]}
"""


def test_composite_is_the_design_files_curve():
    c = fabmesh.composite([
        {"points": [[0, 0], [1, 2], [3, 3], [4, 1]], "lambda": 0.5},
        {"family": "hbezier", "join": {"continuity": "G2", "k": 1.5, "m": np.float64(0.25)},
         "points": [[8, 0]], "alpha": 2, "mu": -1},
        {"family": "line", "points": [[10, -3]]},
    ])
    from_design = fabmesh.build(fabmesh.parse_design(MIXED_DESIGN)).curves[0].curve
    ts = np.linspace(0, 3, 61)
    assert c.segments == 3
    assert np.allclose(c.evaluate(ts), from_design.evaluate(ts), rtol=0, atol=1e-12)
    joints = c.joints
    assert [(j["declared"], j["achieved"]) for j in joints] == [("G2", "G2"), ("G0", "G0")]
    assert joints[0]["curvature_before"] == pytest.approx(joints[0]["curvature_after"], rel=1e-9)
    assert c.fairing is None


@pytest.mark.parametrize("segments, key", [
    ([{"points": [[0, 0], [1, 1], [2, 1], [3, 0]]}, {"points": [[4, 1], [5, 0]]}], "segments[1]"),
    ([{"points": [[0, 0], [1, 1], [2, 1], [3, 0]], "shape": 1}], "segments[0].shape"),
    ([{"points": [[0, 0], [1, 1], [2, 1], [3, 0]], "family": "nurbs"}], "segments[0].family"),
    ([{"points": [[0, 0], [1, 1], [2, 1]]}], "segments[0]"),
    ([{"points": [[0, 0, 0], [1, 1, 1]]}], "segments[0].points"),
    ([{"points": [[0, 0], [1, 1], [2, 1], [3, 0]]}, {"points": [[5, 0]], "join": {"continuity": "C2"}}],
     "segments[1].join.continuity"),
    ([{"points": [[0, 0], [1, 1], [2, 1], [3, 0]]}, {"points": [[5, 0]], "join": {"continuity": "G2", "k": "x"}}],
     "segments[1].join.k"),
    ([{"points": [[0, 0], [1, 1], [2, 1], [3, 0]], "lambda": 4}], "segments[0]"),
    (["not a dict"], "segments[0]"),
])
def test_composite_errors_name_the_segment(segments, key):
    with pytest.raises(fabmesh.InputError) as caught:
        fabmesh.composite(segments)
    assert caught.value.key.startswith(key), (caught.value.key, str(caught.value))
    assert caught.value.exit_code == 2


def test_fair_matches_the_designs_fairing():
    points = [[1.5, 6], [1, 5], [2, 4], [3, 3], [1.5, 2]]
    b = fabmesh.quasi_bspline(points, lambdas=[0.5, 0.5, 0.5])
    f = fabmesh.fair(b, "strain")
    assert f.fairing["energy"] == "strain" and f.fairing["after"] < f.fairing["before"]
    design = fabmesh.parse_design(f"""
name: faired
kind: curve
tolerance: 0.005
curve:
  family: quasi_bspline
  points: {points}
  lambdas: [0.5, 0.5, 0.5]
  fair: strain
""")
    built = fabmesh.build(design).curves[0].curve
    ts = np.linspace(0, f.segments, 41)
    assert np.allclose(f.evaluate(ts), built.evaluate(ts), rtol=0, atol=1e-12)
    assert built.fairing["after"] == pytest.approx(f.fairing["after"], rel=1e-12)
    # The lambdas optimize reports are the ones fair chose: fairing again changes nothing.
    assert fabmesh.fair(built, "strain").fairing["after"] == pytest.approx(f.fairing["after"], rel=1e-9)
    with pytest.raises(fabmesh.InputError) as caught:
        fabmesh.fair(b, "smoothness")
    assert caught.value.key == "energy"
    with pytest.raises(fabmesh.InputError) as caught:
        fabmesh.fair(fabmesh.hbezier([[0, 0], [1, 2], [3, 2], [4, 0]]))
    assert caught.value.key == "energy"
    g2 = fabmesh.composite([
        {"points": [[1, 0.2], [0.2, 0.4], [1.6, 1.4], [1, 0.2]], "lambda": 1, "mu": 1},
        {"points": [[4, 0]], "lambda": -1, "join": {"continuity": "G2"}},
    ])
    with pytest.raises(fabmesh.InputError) as caught:
        fabmesh.fair(g2)
    assert caught.value.key == "keeps"
    assert fabmesh.fair(g2, keeps="G1").joints[0]["achieved"] == "G1"


def test_optimize_is_the_command_lines():
    path = example("example4_profile.yaml")
    code, out = cli("optimize", path, "--json")
    assert code == 0
    assert fabmesh.optimize(fabmesh.read_design(path)) == json.loads(out)


def test_builds_run_in_parallel_threads():
    designs = [fabmesh.read_design(example("vessel_golden_solid.yaml"), overrides={"name": f"v{i}"})
               for i in range(4)]
    serial = [fabmesh.build(d).vertices for d in designs]
    results = [None] * len(designs)

    def work(i):
        results[i] = fabmesh.build(designs[i]).vertices

    threads = [threading.Thread(target=work, args=(i,)) for i in range(len(designs))]
    for thread in threads:
        thread.start()
    for thread in threads:
        thread.join()
    for a, b in zip(serial, results):
        assert np.array_equal(a, b)


def test_help_explains_arguments_and_errors():
    assert "InputError" in fabmesh.build.__doc__
    assert "units" in fabmesh.Result.vertices.__doc__
    assert fabmesh.check.__doc__ and fabmesh.check_file.__doc__ and fabmesh.read_design.__doc__
