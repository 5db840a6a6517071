"""The hand-written type stubs (__init__.pyi) name what the module has, with its parameters."""
import ast
import inspect
import pathlib
import re

import fcl_superellipsoid as fse

STUB = pathlib.Path(fse.__file__).with_name("__init__.pyi")


def stub_tree():
    return ast.parse(STUB.read_text())


def parameters_of_docstring(function):
    """Parameter names from pybind11's signature line, 'name(self: T, a: T, *, b: T = 1) -> R'."""
    line = function.__doc__.strip().splitlines()[0]
    inside = line[line.index("(") + 1:line.rindex(")")]
    inside = re.sub(r"\[[^\]]*\]", "", inside)  # drop typing brackets with commas
    names = [part.split(":")[0].split("=")[0].strip() for part in inside.split(",")]
    return [n for n in names if n and n != "*"]


def is_result_type(node):
    """A stub class of a result (a NamedTuple), whose fields are checked rather than methods."""
    return any(isinstance(b, ast.Name) and b.id == "NamedTuple" for b in node.bases)


def stub_parameters(node):
    args = node.args
    return [a.arg for a in args.posonlyargs + args.args + args.kwonlyargs]


def test_every_public_name_has_a_stub_and_every_stub_a_name():
    tree = stub_tree()
    stubbed = {n.name for n in tree.body if isinstance(n, (ast.ClassDef, ast.FunctionDef))}
    stubbed |= {n.target.id for n in tree.body if isinstance(n, ast.AnnAssign)}
    public = set(fse.__all__)
    assert stubbed - {"ArrayLike", "FloatArray", "Pose", "Method"} == public


def test_functions_and_methods_have_the_stubs_parameters():
    for node in stub_tree().body:
        if isinstance(node, ast.FunctionDef):
            assert stub_parameters(node) == parameters_of_docstring(getattr(fse, node.name))
        if isinstance(node, ast.ClassDef) and not is_result_type(node):
            cls = getattr(fse, node.name)
            for item in node.body:
                if isinstance(item, ast.FunctionDef) and not any(
                        isinstance(d, ast.Name) and d.id in ("property", "overload")
                        for d in item.decorator_list):
                    member = getattr(cls, item.name)
                    assert stub_parameters(item) == parameters_of_docstring(member), (
                        node.name, item.name)
                if isinstance(item, ast.FunctionDef) and any(
                        isinstance(d, ast.Name) and d.id == "property" for d in item.decorator_list):
                    assert isinstance(inspect.getattr_static(cls, item.name), property)


def test_result_types_have_the_stubs_fields():
    for node in stub_tree().body:
        if isinstance(node, ast.ClassDef) and is_result_type(node):
            fields = [item.target.id for item in node.body if isinstance(item, ast.AnnAssign)]
            assert list(getattr(fse, node.name)._fields) == fields
