"""Loading and running an input deck: Python 2 decks are translated (print statements, `<>`,
integer division), the deck runs with the commands in its namespace, and an error names the
deck's file and line."""
import ast
import importlib.machinery
import importlib.util
import numbers
import os
import sys
import sysconfig
import traceback
import warnings


def classic_division(a, b):
    """Python 2's `/`: floor division of two integers, true division otherwise."""
    if isinstance(a, numbers.Integral) and isinstance(b, numbers.Integral) \
            and not isinstance(a, bool) and not isinstance(b, bool):
        return a // b
    return a / b


class _ClassicDivision(ast.NodeTransformer):
    """Rewrites `a / b` as classic_division(a, b) (and `x /= b` for a name x)."""

    def visit_BinOp(self, node):
        self.generic_visit(node)
        if isinstance(node.op, ast.Div):
            return ast.copy_location(
                ast.Call(func=ast.Name(id="__classic_division__", ctx=ast.Load()),
                         args=[node.left, node.right], keywords=[]), node)
        return node

    def visit_AugAssign(self, node):
        self.generic_visit(node)
        if isinstance(node.op, ast.Div) and isinstance(node.target, ast.Name):
            call = ast.Call(func=ast.Name(id="__classic_division__", ctx=ast.Load()),
                            args=[ast.Name(id=node.target.id, ctx=ast.Load()), node.value],
                            keywords=[])
            return ast.copy_location(
                ast.Assign(targets=[ast.Name(id=node.target.id, ctx=ast.Store())], value=call),
                node)
        return node


def _import_classic_division(module):
    """Puts `from grain._deck import classic_division as __classic_division__` after the
    docstring and the __future__ imports of a translated module."""
    k = 0
    body = module.body
    if body and isinstance(body[0], ast.Expr) and isinstance(body[0].value, ast.Constant) and \
            isinstance(body[0].value.value, str):
        k = 1
    while k < len(body) and isinstance(body[k], ast.ImportFrom) and body[k].module == "__future__":
        k += 1
    body.insert(k, ast.ImportFrom(module="grain._deck",
                                  names=[ast.alias(name="classic_division",
                                                   asname="__classic_division__")], level=0))
    return module


def translate(source, path, module=False):
    """The code object of a deck (or, with `module`, of a module it imports) and whether it was
    read as Python 2. Code that is not valid Python 3 is translated as 2to3 does (lib2to3's
    fixers; tabs count to the next multiple of 8 columns, as in Python 2) and runs with Python
    2's integer division; the line numbers stay those of the file."""
    try:
        return compile(source, path, "exec"), False
    except SyntaxError as python3_error:
        source = source.expandtabs(8)
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            try:
                from lib2to3 import refactor
            except ImportError:  # pragma: no cover - Debian package python3-lib2to3
                raise SystemExit(
                    "grain-parmec: %s is not valid Python 3 (%s, line %s) and lib2to3 "
                    "(Debian python3-lib2to3) is missing to read it as Python 2"
                    % (path, python3_error.msg, python3_error.lineno))
            fixers = refactor.get_fixers_from_package("lib2to3.fixes")
            tool = refactor.RefactoringTool(fixers)
            text = source if source.endswith("\n") else source + "\n"
            try:
                tree = tool.refactor_string(text, path)
            except Exception:
                raise python3_error
        tree = _ClassicDivision().visit(ast.parse(str(tree), path))
        if module:
            tree = _import_classic_division(tree)
        return compile(ast.fix_missing_locations(tree), path, "exec"), True


class _Python2Loader(importlib.machinery.SourceFileLoader):
    """Loads a module a deck imports, reading it as Python 2 if it is not valid Python 3."""

    def source_to_code(self, data, path, *, _optimize=-1):
        return translate(importlib.util.decode_source(data), path, module=True)[0]

    def get_code(self, fullname):  # no bytecode cache: a translation is not Python 3's own
        path = self.get_filename(fullname)
        return self.source_to_code(self.get_data(path), path)


class _Python2Finder:
    """Finds the modules of a deck's own folders (not those of the Python installation or of
    grain) and gives them to _Python2Loader."""
    _system = None

    @classmethod
    def find_spec(cls, name, path=None, target=None):
        spec = importlib.machinery.PathFinder.find_spec(name, path)
        if spec is None or not spec.origin or not spec.origin.endswith(".py"):
            return None
        if cls._system is None:
            paths = {sys.prefix, sys.base_prefix, os.path.dirname(os.path.dirname(__file__))}
            paths.update(v for k, v in sysconfig.get_paths().items() if v)
            cls._system = tuple(os.path.realpath(p) + os.sep for p in paths)
        if os.path.realpath(spec.origin).startswith(cls._system):
            return None
        spec.loader = _Python2Loader(name, spec.origin)
        return spec


def _install_finder():
    if not any(f is _Python2Finder for f in sys.meta_path):
        sys.meta_path.insert(0, _Python2Finder)


class DeckError(Exception):
    """An error raised by a deck's command, with the deck's file and line."""


def deck_line(tb, path):
    """The line of the deck where the traceback `tb` passed last."""
    line = None
    for frame, lineno in traceback.walk_tb(tb):
        if os.path.abspath(frame.f_code.co_filename) == os.path.abspath(path):
            line = lineno
    return line


def run(path, args, namespace):
    """Runs the deck at `path` with sys.argv = [path] + args in `namespace` (the commands)."""
    with open(path, encoding="utf-8", errors="replace") as f:
        source = f.read()
    code, python2 = translate(source, path)
    namespace.update({"__name__": "__main__", "__file__": path,
                      "__classic_division__": classic_division})
    sys.argv = [path] + list(args)
    _install_finder()
    exec(code, namespace)
    return python2
