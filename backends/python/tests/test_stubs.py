"""The type stubs cover the package: hush/_hush.pyi (written from the built module at build
time) names every class, method, property and keyword parameter; hush/__init__.pyi and
hush/dask.pyi name the functions of __init__.py and dask.py with their parameters. The
docstrings quote the C++ contract comments (tools/python_docstrings.py)."""
import ast
import importlib
import inspect
import pathlib
import re

import pytest

import hush
from hush import _hush

PACKAGE = pathlib.Path(hush.__file__).parent


def stub(name):
    return ast.parse((PACKAGE / name).read_text())


def defs(body):
    """{name: [argument names]} of the function definitions in an ast body (last overload)."""
    out = {}
    for node in body:
        if isinstance(node, ast.FunctionDef):
            a = node.args
            out[node.name] = [x.arg for x in a.posonlyargs + a.args + a.kwonlyargs] + \
                ([a.vararg.arg] if a.vararg else []) + ([a.kwarg.arg] if a.kwarg else [])
    return out


def test_module_stub_names_every_class_method_and_keyword():
    tree = stub("_hush.pyi")
    classes = {n.name: n for n in tree.body if isinstance(n, ast.ClassDef)}
    functions = defs(tree.body)
    for name in dir(_hush):
        if name.startswith("__"):
            continue
        value = getattr(_hush, name)
        if isinstance(value, type):
            assert name in classes, name
            methods = defs(classes[name].body)
            assert methods["__init__"][1:] == list(value.keywords), name
            for attr, member in vars(value).items():
                if attr.startswith("_") and attr not in ("__call__",) or attr == "keywords":
                    continue
                assert attr in methods or attr == "dimension", f"{name}.{attr}"
        elif callable(value):
            assert name in functions, name
        else:
            assert re.search(rf"^{name}: ", (PACKAGE / "_hush.pyi").read_text(), re.M), name


@pytest.mark.parametrize("module_name, stub_file", [("hush", "__init__.pyi"),
                                                    ("hush.dask", "dask.pyi")])
def test_package_stubs_match_the_python_functions(module_name, stub_file):
    module = importlib.import_module(module_name)
    stubbed = defs(stub(stub_file).body)
    public = {n: f for n, f in vars(module).items()
              if inspect.isfunction(f) and not n.startswith("_") and f.__module__ == module.__name__}
    assert set(stubbed) == set(public)
    for name, f in public.items():
        assert stubbed[name] == list(inspect.signature(f).parameters), name


def test_keywords_are_the_ones_the_constructor_accepts():
    for name in ("Perlin2", "Fractal3", "Wavelet2", "Gabor3", "Anisotropic", "CoherentStream",
                 "NprGabor"):
        cls = getattr(hush, name)
        with pytest.raises(TypeError) as e:
            cls(not_a_parameter=1)
        valid = re.search(r"valid: (.*)$", str(e.value)).group(1).split(", ")
        assert sorted(valid) == sorted(cls.keywords), name


def test_docstrings_quote_the_cpp_contract():
    root = pathlib.Path(__file__).resolve().parents[3]
    header = (root / "include/hush/gabor.hpp").read_text()
    # A params field's comment, and the header's opening comment.
    assert "N': the mean number of kernels overlapping a point" in header
    assert "N': the mean number of kernels overlapping a point" in hush.Gabor2.__doc__
    assert hush.Gabor2.keywords["impulses"][0] == "float"
    assert header.splitlines()[2][3:] in hush.Gabor2.__doc__
    assert "glsl: within the GLSL tolerance" in hush.Perlin2.__call__.__doc__
    assert "|output| <= bound()" in hush.Wavelet2.bound.__doc__
