# The type stubs (supermodal.pyi, next to the module) name what the module has, and only that; the
# keyword lists in the stubs are the ones the functions accept.
import ast
import inspect
import pathlib

import pytest

import supermodal as sm

STUBS = pathlib.Path(sm.__file__).with_name("supermodal.pyi")
ALIASES = {"Vec3", "Quat", "Path", "Motion", "Solver", "Anchor", "ExportInfo", "FitResult"}


def stub_tree():
    assert STUBS.exists(), f"no stubs next to {sm.__file__}"
    return ast.parse(STUBS.read_text())


def public(names):
    return {n for n in names if not n.startswith("_") or n == "__version__"}


def test_stubs_name_every_module_attribute():
    tree = stub_tree()
    stubbed = set()
    for node in tree.body:
        if isinstance(node, (ast.ClassDef, ast.FunctionDef)):
            stubbed.add(node.name)
        elif isinstance(node, ast.AnnAssign):
            stubbed.add(node.target.id)
        elif isinstance(node, ast.Assign):
            stubbed.update(t.id for t in node.targets)
    assert public(dir(sm)) - {"annotations"} <= stubbed | {"__doc__", "__file__", "__name__", "__loader__",
                                                             "__package__", "__spec__"}
    assert stubbed - ALIASES <= set(dir(sm))


@pytest.mark.parametrize("cls", ["World", "Body", "DeformedPoints", "Constraint", "Material", "ContactEvent", "Contact", "FaultEvent"])
def test_stub_classes_match(cls):
    node = next(n for n in stub_tree().body if isinstance(n, ast.ClassDef) and n.name == cls)
    members = {m.name for m in node.body if isinstance(m, ast.FunctionDef)}
    members |= {m.target.id for m in node.body if isinstance(m, ast.AnnAssign)}
    actual = {n for n in dir(getattr(sm, cls)) if not n.startswith("_")}
    assert members - {"__init__", "__eq__", "__hash__", "__len__"} == actual


def keywords(cls, method):
    node = next(n for n in stub_tree().body if isinstance(n, ast.ClassDef) and n.name == cls)
    fn = next(m for m in node.body if isinstance(m, ast.FunctionDef) and m.name == method)
    return [a.arg for a in fn.args.kwonlyargs], [ast.literal_eval(d) for d in fn.args.kw_defaults]


@pytest.mark.parametrize("cls,method", [("World", "__init__"), ("World", "create_body"), ("Material", "__init__")])
def test_stub_keywords_are_accepted_with_their_defaults(cls, method):
    names, defaults = keywords(cls, method)
    w = sm.World()
    for name, default in zip(names, defaults):
        if default is ...:  # +inf in the module; the stubs cannot spell it
            continue
        # Each keyword with its documented default is accepted, one at a time.
        if cls == "World" and method == "__init__":
            assert sm.World(**{name: default}).settings()[name] == pytest.approx(default)
        elif cls == "World":
            w.create_body(**{name: default})
        else:
            assert getattr(sm.Material(**{name: default}), name) == default
