"""Named parameters from Python: Design.parameters and overrides by parameter name."""

import json

import pytest

import fabmesh
from conftest import cli, example

CUP = """name: cup
kind: vessel
units: cm
tolerance: 0.02
parameters:
  height: {value: 4, min: 2, max: 10, step: 0.1, description: "foot to rim"}
  wall: 0.3
profile:
  family: quasi_bspline
  points: [[1.5, "=2 + height"], [1, 5], [2, 4], [3, 3], [1.5, 2]]
  lambdas: [0, 0, 0]
body: {mode: shell, wall: "=wall", base: 0.4}
"""


def test_parameters_are_read_only_with_their_ranges():
    design = fabmesh.parse_design(CUP)
    height, wall = design.parameters
    assert (height.name, height.value, height.min, height.max, height.step) == ("height", 4.0, 2.0, 10.0, 0.1)
    assert height.description == "foot to rim"
    assert (wall.name, wall.value, wall.min, wall.max, wall.step, wall.description) == (
        "wall", 0.3, None, None, None, "")
    with pytest.raises(AttributeError):
        height.value = 5
    assert "height" in repr(height)
    assert fabmesh.read_design(example("vessel_golden_shell.yaml")).parameters == []


def test_overrides_by_parameter_name():
    design = fabmesh.parse_design(CUP, overrides={"height": 6, "wall": 0.25})
    assert [p.value for p in design.parameters] == [6.0, 0.25]
    result = fabmesh.build(design)
    assert result.valid
    assert result.to_dict()["parameters"] == {"height": 6.0, "wall": 0.25}
    assert result.to_dict()["bounding_box"]["size"][2] > 6.0  # the profile's 6, and the rim cut square above it


def test_the_example_builds_as_the_command_line_reports_it(tmp_path):
    design = fabmesh.read_design(example("vessel_golden_solid.yaml"), overrides={"width": 7})
    assert [(p.name, p.value) for p in design.parameters] == [("height", 4.0), ("width", 7.0)]
    code, out = cli("run", example("vessel_golden_solid.yaml"), "-D", "width=7", "-o", str(tmp_path) + "/",
                    "--json", "-q")
    assert code == 0
    assert json.loads(out)[0]["parameters"] == {"height": 4.0, "width": 7.0}
    assert fabmesh.build(design).to_dict()["parameters"] == {"height": 4.0, "width": 7.0}


def test_a_value_out_of_range_is_an_input_error_naming_the_override():
    with pytest.raises(fabmesh.InputError) as caught:
        fabmesh.parse_design(CUP, overrides={"height": 15})
    assert caught.value.exit_code == 2
    assert caught.value.key == "parameters.height"
    assert caught.value.override == "height=15"
    assert "parameters.height: 15 is outside [2, 10]" in str(caught.value)


def test_an_expression_error_names_its_line_and_column():
    with pytest.raises(fabmesh.InputError) as caught:
        fabmesh.parse_design(CUP.replace('"=2 + height"', '"=2 + heigth"'))
    assert (caught.value.key, caught.value.line, caught.value.column) == ("profile.points[0][1]", 10, 18)
    assert "unknown name 'heigth'" in str(caught.value)
