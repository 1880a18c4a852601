"""fabmesh.repair over numpy arrays and fabmesh.repair_file, and Open3D's
judgement of every repaired 3MF of tests/data/repair-corpus (docs/repair.md)."""

import json
import pathlib

import numpy as np
import open3d as o3d
import pytest

import fabmesh
from conftest import SOURCE, cli

CORPUS = SOURCE / "tests" / "data" / "repair-corpus"
CUBE_V = np.array([[x, y, z] for z in (0, 1) for y in (0, 1) for x in (0, 1)], dtype=float)
CUBE_T = np.array([[0, 2, 3], [0, 3, 1], [4, 5, 7], [4, 7, 6], [0, 1, 5], [0, 5, 4],
                   [2, 6, 7], [2, 7, 3], [0, 4, 6], [0, 6, 2], [1, 3, 7], [1, 7, 5]])


def corpus_files():
    return [case["file"] for case in json.loads((CORPUS / "manifest.json").read_text())["cases"]]


def test_a_valid_cube_comes_back_unchanged():
    r = fabmesh.repair(CUBE_V, CUBE_T)
    assert r.valid and not r.changed
    assert r.to_dict()["repairs"] == []
    np.testing.assert_array_equal(r.vertices, CUBE_V)
    np.testing.assert_array_equal(r.triangles, CUBE_T)


def test_a_hole_is_filled_and_said_where():
    r = fabmesh.repair(CUBE_V, CUBE_T[1:])
    assert r.valid and r.changed
    steps = {s["step"]: s for s in r.to_dict()["repairs"]}
    assert steps["hole_fill"]["count"] == 1
    assert len(steps["hole_fill"]["places"][0]["point"]) == 3
    assert fabmesh.check(r.vertices, r.triangles).valid
    assert r.after.valid
    assert r.volume_after == pytest.approx(1.0) == r.to_dict()["volume"]["after"]
    assert r.distance >= 0.0 and r.to_dict()["distance"]["bound"] == r.distance


def test_overlapping_cubes_become_one_solid():
    v = np.vstack([CUBE_V * 2, CUBE_V * 2 + 1])
    t = np.vstack([CUBE_T, CUBE_T + 8])
    r = fabmesh.repair(v, t)
    assert r.valid
    assert [s["step"] for s in r.to_dict()["repairs"]] == ["union"]
    assert r.volume_after == pytest.approx(15.0)
    assert r.components_after == 1


def test_what_cannot_be_mended_is_a_report_not_an_exception():
    r = fabmesh.repair(CUBE_V, CUBE_T[1:], fill_holes=False)
    assert not r.valid
    assert r.unresolved


def test_bad_arrays_raise_input_error():
    with pytest.raises(fabmesh.InputError):
        fabmesh.repair(CUBE_V, CUBE_T[:, :2])
    with pytest.raises(fabmesh.InputError):
        fabmesh.repair(np.zeros((0, 3)), np.zeros((0, 3), dtype=np.int64))
    with pytest.raises(fabmesh.InputError):
        fabmesh.repair(CUBE_V, CUBE_T + 100)


def test_repair_file_matches_the_command_line(tmp_path):
    out = tmp_path / "holes.3mf"
    item = fabmesh.repair_file(CORPUS / "holes.obj", out)
    assert item["exit_code"] == 0 and out.exists()
    code, text = cli("repair", str(CORPUS / "holes.obj"), "-o", str(tmp_path / "cli.3mf"), "--json")
    assert code == 0
    assert (tmp_path / "cli.3mf").read_bytes() == out.read_bytes()


@pytest.mark.parametrize("name", corpus_files())
def test_open3d_reads_every_repaired_3mf_watertight(name, tmp_path):
    out = tmp_path / (pathlib.Path(name).stem + ".3mf")
    item = fabmesh.repair_file(CORPUS / name, out)
    assert item["exit_code"] == 0, item["message"]
    # Open3D reads no 3MF: the same repair written as PLY, which it reads as is.
    ply = tmp_path / (pathlib.Path(name).stem + ".ply")
    assert fabmesh.repair_file(out, ply)["exit_code"] == 0
    mesh = o3d.io.read_triangle_mesh(str(ply))
    assert len(mesh.triangles) > 0
    assert mesh.is_watertight()
    assert mesh.is_edge_manifold() and mesh.is_vertex_manifold()
    assert mesh.is_orientable()
    assert not mesh.is_self_intersecting()
