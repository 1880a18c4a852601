"""The type stub (python/fabmesh.pyi, installed beside the module) is held to the module itself:
the same public names, the same members of each class, the same parameters of each function."""

import ast
import enum
import inspect
import re

import pytest

import fabmesh
from conftest import SOURCE

STUB = ast.parse((SOURCE / "python" / "fabmesh.pyi").read_text())
ALIASES = {"StrPath", "ArrayLike"}  # the stub's own type aliases, not names of the module


def stub_top():
    names = {}
    for node in STUB.body:
        if isinstance(node, (ast.ClassDef, ast.FunctionDef)):
            names[node.name] = node
        elif isinstance(node, ast.AnnAssign) and isinstance(node.target, ast.Name):
            names[node.target.id] = node
        elif isinstance(node, ast.Assign):
            for target in node.targets:
                if isinstance(target, ast.Name) and target.id not in ALIASES:
                    names[target.id] = node
    return names


def stub_members(cls):
    members = set()
    for node in cls.body:
        if isinstance(node, ast.FunctionDef):
            members.add(node.name)
        elif isinstance(node, ast.AnnAssign) and isinstance(node.target, ast.Name):
            members.add(node.target.id)
        elif isinstance(node, ast.Assign):
            members.update(t.id for t in node.targets if isinstance(t, ast.Name))
    return members


def stub_parameters(function):
    args = function.args
    names = [a.arg for a in args.posonlyargs + args.args + args.kwonlyargs]
    return [n for n in names if n != "self"]


def runtime_parameters(function):
    """The parameter names pybind11 writes in the first line of a docstring: name(a: T, b: T = x) -> R."""
    first = (function.__doc__ or "").splitlines()[0] if function.__doc__ else ""
    match = re.match(r"\w+\((.*)\)\s*->", first)
    assert match, f"no signature in the docstring of {function!r}: {first!r}"
    names, depth, current = [], 0, ""
    for char in match.group(1) + ",":
        depth += char in "([{"
        depth -= char in ")]}"
        if char == "," and depth == 0:
            name = current.split(":")[0].split("=")[0].strip()
            if name and name not in ("self", "*"):
                names.append(name)
            current = ""
        else:
            current += char
    return names


PUBLIC = sorted(n for n in dir(fabmesh) if not n.startswith("_")) + ["__version__", "__getattr__"]
TOP = stub_top()


def test_the_stub_names_every_public_name_of_the_module_and_no_other():
    assert sorted(TOP) == sorted(PUBLIC)


@pytest.mark.parametrize("name", [n for n, node in TOP.items() if isinstance(node, ast.ClassDef)])
def test_each_class_has_the_stubs_members(name):
    cls = getattr(fabmesh, name)
    declared = stub_members(TOP[name])
    if issubclass(cls, BaseException):
        # Attributes of an exception are set where it is raised: its class only has to exist with the stub's bases.
        bases = {b.id if isinstance(b, ast.Name) else b.attr for b in TOP[name].bases}
        assert bases == {b.__name__ for b in cls.__bases__}
        return
    if issubclass(cls, enum.Enum):
        assert declared == {m.name for m in cls}
        for node in TOP[name].body:
            if isinstance(node, ast.Assign):
                assert cls[node.targets[0].id].value == node.value.value
        return
    runtime = {n for n in vars(cls) if not n.startswith("_") or n in ("__getitem__", "__len__", "__iter__")}
    assert declared == runtime
    for node in TOP[name].body:
        if isinstance(node, ast.FunctionDef) and not any(
                isinstance(d, ast.Name) and d.id == "property" for d in node.decorator_list):
            method = getattr(cls, node.name)
            if not node.name.startswith("__"):
                assert stub_parameters(node) == runtime_parameters(method), f"{name}.{node.name}"


@pytest.mark.parametrize("name", [n for n, node in TOP.items() if isinstance(node, ast.FunctionDef)])
def test_each_function_has_the_stubs_parameters(name):
    function = getattr(fabmesh, name)
    if name == "__getattr__":
        assert inspect.isbuiltin(function) or callable(function)
        return
    assert stub_parameters(TOP[name]) == runtime_parameters(function)
