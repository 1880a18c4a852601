"""`fabmesh params --json`: a JSON Schema (draft 2020-12) of a design's parameters, validated with
Debian's python3-jsonschema against real overrides, and the program agreeing with it."""

import json
from decimal import Decimal

import jsonschema

from conftest import cli, example


def schema_of(design, *defines):
    code, out = cli("params", design, "--json", *defines)
    assert code == 0
    # Decimals, as the schema's description asks: multipleOf 0.1 is then exact (4.6 / 0.1 is not in binary).
    return json.loads(out, parse_float=Decimal)


def errors(schema, instance):
    return [e.message for e in jsonschema.Draft202012Validator(schema).iter_errors(instance)]


def test_the_schema_is_valid_draft_2020_12_and_describes_each_parameter():
    schema = schema_of(example("vessel_golden_solid.yaml"))
    jsonschema.Draft202012Validator.check_schema(schema)
    assert schema["$schema"] == "https://json-schema.org/draft/2020-12/schema"
    assert schema["additionalProperties"] is False
    assert list(schema["properties"]) == ["height", "width", "parameter_set"]
    height = schema["properties"]["height"]
    assert height == {"type": "number", "default": 4, "minimum": 2, "maximum": 10, "multipleOf": Decimal("0.1"),
                      "description": "from the foot (at 2) to the rim"}
    # The defaults are the values read: an override moves it.
    assert schema_of(example("vessel_golden_solid.yaml"), "-D", "height=6")["properties"]["height"]["default"] == 6


def test_overrides_the_schema_accepts_the_program_builds_and_what_it_refuses_the_program_refuses(tmp_path):
    design = example("vessel_golden_solid.yaml")
    schema = schema_of(design)
    good = [{"height": Decimal("5")}, {"height": Decimal("4.6"), "width": Decimal("7.5")}, {}]
    for overrides in good:
        assert errors(schema, overrides) == []
        defines = [a for k, v in overrides.items() for a in ("-D", f"{k}={v}")]
        code, _ = cli("run", design, "-o", str(tmp_path / "out"), "-q", *defines)
        assert code == 0, overrides
    assert any("maximum" in m or "greater than" in m for m in errors(schema, {"height": Decimal("11")}))
    code, _ = cli("run", design, "-o", str(tmp_path / "bad"), "-q", "-D", "height=11")
    assert code == 2
    assert any("minimum" in m or "less than" in m for m in errors(schema, {"width": Decimal("2")}))
    assert any("multiple of" in m for m in errors(schema, {"height": Decimal("4.55")}))
    assert any("Additional properties" in m for m in errors(schema, {"depth": Decimal("3")}))
    code, _ = cli("run", design, "-o", str(tmp_path / "bad2"), "-q", "-D", "depth=3")
    assert code == 2
    assert any("is not of type 'number'" in m for m in errors(schema, {"height": "tall"}))


def test_a_design_without_parameters_has_an_empty_schema_and_a_table_says_so():
    schema = schema_of(example("vessel_golden_shell.yaml"))
    assert schema["properties"] == {} and errors(schema, {}) == []
    code, out = cli("params", example("vessel_golden_shell.yaml"))
    assert code == 0 and "no named parameters" in out
    code, out = cli("params", example("vessel_golden_solid.yaml"))
    assert code == 0
    assert "height = 4 in [2, 10], step 0.1: from the foot (at 2) to the rim" in out
    code, _ = cli("params", example("no_such_design.yaml"))
    assert code == 2


def test_the_sets_are_an_enum_and_examples_that_validate_and_build_as_the_schema_says(tmp_path):
    design = example("vessel_golden_solid.yaml")
    schema = schema_of(design)
    assert schema["properties"]["parameter_set"]["enum"] == ["small", "tall", "wide"]
    assert "default" not in schema["properties"]["parameter_set"]  # the file picks none
    # One example per set, its values resolved (wide's width is "=height * 2.5").
    assert schema["examples"] == [{"parameter_set": "small", "height": 3, "width": 5},
                                  {"parameter_set": "tall", "height": 8},
                                  {"parameter_set": "wide", "width": 10}]
    for instance in schema["examples"]:
        assert errors(schema, instance) == []
    assert any("is not one of" in m for m in errors(schema, {"parameter_set": "huge"}))
    # What the schema accepts, the program builds with those values; what it refuses, it refuses.
    code, out = cli("run", design, "-o", str(tmp_path / "tall"), "--json", "-P", "tall", "-D", "width=7")
    assert code == 0
    item = json.loads(out)
    item = item[0] if isinstance(item, list) else item
    assert item["parameter_set"] == "tall" and item["parameters"] == {"height": 8, "width": 7}
    code, _ = cli("run", design, "-o", str(tmp_path / "huge"), "-q", "-P", "huge")
    assert code == 2 and not (tmp_path / "huge").exists()
    # The set used is the schema's default.
    assert schema_of(design, "-P", "wide")["properties"]["parameter_set"]["default"] == "wide"


CHOSEN_CUP = """name: chosen_cup
kind: vessel
units: cm
tolerance: 0.005
parameters:
  mode: {value: shell, choices: [shell, solid], description: "hollow or full"}
  thick: false
  wall: "=thick ? 0.4 : 0.3"
profile:
  family: quasi_bspline
  points: [[1.5, 6], [1, 5], [2, 4], [3, 3], [1.5, 2]]
body: {mode: "=mode", wall: "=wall"}
"""


def test_a_choice_is_a_string_enum_and_a_switch_a_boolean_as_the_program_takes_them(tmp_path):
    design = tmp_path / "cup.yaml"
    design.write_text(CHOSEN_CUP)
    schema = schema_of(str(design))
    jsonschema.Draft202012Validator.check_schema(schema)
    assert schema["properties"]["mode"] == {"type": "string", "enum": ["shell", "solid"], "default": "shell",
                                            "description": "hollow or full"}
    assert schema["properties"]["thick"] == {"type": "boolean", "default": False}
    assert errors(schema, {"mode": "solid", "thick": True}) == []
    assert any("is not one of" in m for m in errors(schema, {"mode": "glass"}))
    assert any("is not of type 'boolean'" in m for m in errors(schema, {"thick": 1}))
    code, out = cli("run", str(design), "-o", str(tmp_path / "solid"), "--json", "-D", "mode=solid", "-D", "thick=true")
    assert code == 0
    item = json.loads(out)[0]
    assert item["parameters"] == {"mode": "solid", "thick": True, "wall": 0.4}
    for bad in ("mode=glass", "thick=1"):
        code, _ = cli("run", str(design), "-o", str(tmp_path / "bad"), "-q", "-D", bad)
        assert code == 2 and not (tmp_path / "bad").exists(), bad
