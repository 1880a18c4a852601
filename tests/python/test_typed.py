"""The module's typed edges: the library's names, enums that are also texts, results with parts,
designs from dicts, numpy values as overrides, the one error tree, and the names of 0.3 kept with a
DeprecationWarning."""

import json
import subprocess

import numpy as np
import pytest

import fabmesh
from conftest import BINARY, example, without_timings


def test_enums_are_typed_and_their_texts():
    assert fabmesh.Unit.mm == "mm" and fabmesh.Unit("in") is fabmesh.Unit.inch
    design = fabmesh.read_design(example("vessel_golden_solid.yaml"))
    assert design.units is fabmesh.Unit.cm
    open_tet = fabmesh.check([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]], [[0, 2, 1], [0, 1, 3], [1, 2, 3]])
    assert not open_tet.valid
    assert open_tet.defects[0].kind is fabmesh.DefectKind.boundary_edge
    assert open_tet.defects[0].count == 3
    assert open_tet.to_dict()["defect_kinds"] == [k.value for k in (d.kind for d in open_tet.defects)]


def test_a_mould_design_is_one_result_of_many_parts(tmp_path):
    path = example("mould_golden.yaml")
    result = fabmesh.build(fabmesh.read_design(path))
    assert result.valid
    roles = [p.role for p in result.parts]
    assert roles[0] is fabmesh.PartRole.product and result.parts[0].name == result.name
    assert fabmesh.PartRole.mould_side in roles
    for part in result.parts:
        assert part.valid and part.validation.valid
        assert part.triangles.shape == (part.validation.triangles, 3)
    assert np.array_equal(result.parts[0].vertices, result.vertices)
    # Every file run writes is named with the parts it holds; the report is run --json's item.
    assert {f.format for f in result.files} >= {"mould_stl"}
    assert all(f.parts for f in result.files if f.format.startswith("mould_"))
    done = subprocess.run([BINARY, "run", path, "--json"], capture_output=True, text=True, cwd=tmp_path,
                          check=True)
    item = json.loads(done.stdout)[0]
    assert without_timings(result.to_dict()) == without_timings(item)
    assert [p["role"] for p in item["parts"]] == [r.value for r in roles]


def test_designs_from_a_dict_build_as_from_their_yaml():
    text = open(example("vessel_golden_solid.yaml")).read()
    import yaml  # Debian's python3-yaml, which meshio depends on
    as_dict = yaml.safe_load(text)
    from_dict = fabmesh.build(fabmesh.parse_design(as_dict, source="vessel_golden_solid.yaml"))
    from_text = fabmesh.build(fabmesh.parse_design(text, source="vessel_golden_solid.yaml"))
    assert np.array_equal(from_dict.vertices, from_text.vertices)
    with pytest.raises(fabmesh.InputError) as caught:
        fabmesh.parse_design(42)
    assert caught.value.key == "design"


def test_numpy_values_are_overrides():
    path = example("vessel_golden_solid.yaml")
    plain = fabmesh.read_design(path, overrides={"body.mode": "solid", "profile.points[1]": [1.0, 5.0]})
    numpy = fabmesh.read_design(path, overrides={"profile.points[1]": np.array([1.0, 5.0])})
    assert np.array_equal(fabmesh.build(plain).vertices, fabmesh.build(numpy).vertices)
    assert fabmesh.read_design(path, overrides={"tolerance": np.float32(0.02)}).tolerance == pytest.approx(0.02)
    assert fabmesh.read_design(path, overrides={"max_triangles": np.int64(400000)}).name
    with pytest.raises(fabmesh.InputError) as caught:
        fabmesh.read_design(path, overrides={"tolerance": object()})
    assert caught.value.key == "overrides.tolerance"
    assert caught.value.exit_code == 2


def test_one_error_tree_with_the_command_lines_codes(tmp_path):
    with pytest.raises(fabmesh.MissingFileError) as caught:
        fabmesh.read_design(str(tmp_path / "nothing.yaml"))
    assert isinstance(caught.value, FileNotFoundError) and isinstance(caught.value, fabmesh.InputError)
    assert caught.value.exit_code == 2 and caught.value.file.endswith("nothing.yaml")
    assert issubclass(fabmesh.MachineError, OSError) and issubclass(fabmesh.MachineError, fabmesh.Error)
    with pytest.raises(fabmesh.InputError) as bad:
        fabmesh.read_design(example("vessel_golden_solid.yaml"), overrides={"body.wall": -1})
    assert (bad.value.key, bad.value.line, bad.value.column) == ("body.wall", None, None)
    assert bad.value.override == "body.wall=-1"


def test_write_mesh_refuses_coordinates_that_are_not_finite(tmp_path):
    vertices = np.array([[0, 0, 0], [1, 0, 0], [0, np.nan, 0], [0, 0, 1]], dtype=np.float64)
    triangles = np.array([[0, 2, 1], [0, 1, 3], [1, 2, 3], [0, 3, 2]])
    with pytest.raises(fabmesh.InputError) as caught:
        fabmesh.write_mesh(str(tmp_path / "nan.stl"), vertices, triangles)
    assert caught.value.key == "vertices"
    assert not (tmp_path / "nan.stl").exists()


def test_read_mesh_is_a_mesh_that_unpacks(tmp_path):
    vertices = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]], dtype=np.float64)
    triangles = np.array([[0, 2, 1], [0, 1, 3], [1, 2, 3], [0, 3, 2]])
    fabmesh.write_mesh(str(tmp_path / "t.3mf"), vertices, triangles, units="cm")
    mesh = fabmesh.read_mesh(str(tmp_path / "t.3mf"))
    assert mesh.units is fabmesh.Unit.cm
    v, t, units = mesh
    assert np.allclose(v, vertices) and t.shape == (4, 3) and units == "cm"
    fabmesh.write_mesh(str(tmp_path / "t.stl"), vertices, triangles)
    assert fabmesh.read_mesh(str(tmp_path / "t.stl")).units is None


def test_the_names_of_0_3_still_work_and_warn():
    path = example("vessel_golden_solid.yaml")
    with pytest.deprecated_call():
        design = fabmesh.load_design(path)
    result = fabmesh.build(design)
    with pytest.deprecated_call():
        assert result.report == result.to_dict()
    with pytest.deprecated_call():
        assert result.validation["valid"] is True
    with pytest.deprecated_call():
        assert fabmesh.EnvironmentError is fabmesh.MachineError
    with pytest.raises(AttributeError):
        fabmesh.no_such_name  # noqa: B018


def test_the_casting_master_is_a_part_of_its_own(tmp_path):
    # Asked for, the master (vessel and spare) is one more part, role master, the cavity's volume.
    design = fabmesh.read_design(example("mould_golden.yaml"), overrides={"outputs": ["mould_stl", "master_stl"]})
    result = fabmesh.build(design)
    masters = [p for p in result.parts if p.role is fabmesh.PartRole.master]
    assert len(masters) == 1 and masters[0].name == "master" and masters[0].valid
    report = result.to_dict()
    assert report["build"]["master"]["spare"] is True
    assert report["build"]["master"]["volume"] == pytest.approx(report["build"]["mould"]["slip_volume"], rel=1e-12)
    assert [f.parts for f in result.files if f.format == "master_stl"] == [["master"]]
