"""The package's layers stay true: imports go down only, no import cycle (within a package or
across), no module named in a string where this check cannot see it, no module reads another's
private names, and only ``plots/`` draws.

Read from the source (AST), so an import inside a function (or under ``TYPE_CHECKING``) counts
as much as one at the top. A module's size is a guide in docs/layout.md, not a
rule here: a limit on lines made splits by line count, and the cycles between the halves were
hidden in function-level imports (issue 26 item 3).
"""

from __future__ import annotations

import ast
import re
from pathlib import Path

import pytest

SRC = Path(__file__).resolve().parents[1] / "src" / "dryfriction"

# bottom to top; a module may import its own layer and those below
LAYERS: list[set[str]] = [
    {"validation", "program", "results", "simulation", "_compat", "interrupts"},
    {"theory"},
    {"ensemble", "rsf"},
    {"io"},                  # file formats and results folders
    {"records", "sweeps"},   # records: reading, program detection, slicing; sweeps: Dask
    {"fit"},
    {"analysis"},
    {"plots"},
    {"app"},  # the workflows as library functions (issue 26)
    {"cli", "warm"},  # warm: the install step's entry point (python -m dryfriction.warm)
]

# no known cycle: issue 26 item 4 dissolved the simulator's two (the drive classes into
# ensemble/drives.py, the linear stability of the law into rsf/stability.py); nothing may be
# added here
KNOWN_CYCLES: set[frozenset[str]] = set()


def _layer(module: str) -> int | None:
    """Layer of ``dryfriction.X...`` (``None`` for the package root, which re-exports lazily)."""
    parts = module.split(".")
    if parts[0] != "dryfriction" or len(parts) == 1:
        return None
    for i, names in enumerate(LAYERS):
        if parts[1] in names:
            return i
    raise AssertionError(f"{module} is in no layer: add it to LAYERS")


def _modules() -> list[tuple[str, Path]]:
    found = []
    for path in sorted(SRC.rglob("*.py")):
        rel = path.relative_to(SRC.parent).with_suffix("")
        parts = list(rel.parts)
        if parts[-1] == "__init__":
            parts = parts[:-1]
        found.append((".".join(parts), path))
    return found


def _imports(module: str, path: Path) -> list[tuple[str, list[str], int]]:
    """(imported module, names, line) for every import statement in the file."""
    tree = ast.parse(path.read_text())
    package = module if path.name == "__init__.py" else module.rpartition(".")[0]
    out = []
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            out += [(a.name, [], node.lineno) for a in node.names]
        elif isinstance(node, ast.ImportFrom):
            if node.level:
                base = package.split(".")
                base = base[: len(base) - (node.level - 1)]
                target = ".".join(base + ([node.module] if node.module else []))
            else:
                target = node.module or ""
            out.append((target, [a.name for a in node.names], node.lineno))
    return out


MODULES = _modules()


def test_every_module_is_in_a_layer():
    for module, _ in MODULES:
        _layer(module)


@pytest.mark.parametrize("module, path", MODULES, ids=[m for m, _ in MODULES])
def test_imports_go_down_only(module, path):
    here = _layer(module)
    if here is None:
        return
    for target, names, line in _imports(module, path):
        if not target.startswith("dryfriction"):
            continue
        # "from . import x" imports submodules: judge each one
        targets = ([f"{target}.{n}" for n in names
                    if (SRC / f"{n}.py").exists() or (SRC / n).is_dir()]
                   if target == "dryfriction" else [target])
        for t in targets:
            there = _layer(t)
            assert there is None or there <= here, (
                f"{path.relative_to(SRC.parent)}:{line} imports {t} from a higher layer")


@pytest.mark.parametrize("module, path", MODULES, ids=[m for m, _ in MODULES])
def test_no_private_name_read_across_modules(module, path):
    for target, names, line in _imports(module, path):
        if not target.startswith("dryfriction") or target == module:
            continue
        private = [n for n in names if n.startswith("_") and not n.startswith("__")]
        assert not private, f"{path.relative_to(SRC.parent)}:{line} reads {private} of {target}"


# private names that are public API of the standard library or of NumPy
_PUBLIC_UNDERSCORED = {"_replace", "_asdict", "_fields", "_make", "_getframe", "_exit"}
# multiprocessing's fork server has no public way to say whether it runs or to stop it: the
# sweep's cluster (sweeps/cluster.py only) uses the names CPython's own tests use
_FORK_SERVER_NAMES = {"_forkserver", "_forkserver_pid", "_stop"}


@pytest.mark.parametrize("module, path", MODULES, ids=[m for m, _ in MODULES])
def test_no_private_attribute_of_another_object(module, path):
    # ``ens._norm`` read by the driver couples it to the population's insides; an object's
    # own methods (self, cls) are the only readers of its private attributes
    tree = ast.parse(path.read_text())
    bad = [f"{path.relative_to(SRC.parent)}:{node.lineno} reads {ast.unparse(node)}"
           for node in ast.walk(tree)
           if isinstance(node, ast.Attribute) and node.attr.startswith("_")
           and not node.attr.startswith("__") and node.attr not in _PUBLIC_UNDERSCORED
           and not (module == "dryfriction.sweeps.cluster" and node.attr in _FORK_SERVER_NAMES)
           and not (isinstance(node.value, ast.Name) and node.value.id in ("self", "cls"))]
    assert not bad, "; ".join(bad)


@pytest.mark.parametrize("module, path", MODULES, ids=[m for m, _ in MODULES])
def test_only_plots_draw(module, path):
    if module.startswith("dryfriction.plots"):
        return
    for target, _, line in _imports(module, path):
        assert not target.startswith("matplotlib"), (
            f"{path.relative_to(SRC.parent)}:{line} imports matplotlib outside plots/")


def _targets(module: str, path: Path, root: Path = SRC.parent) -> list[tuple[str, int]]:
    """(module of the package, line) for every import of one: ``from . import x`` of a
    submodule names the submodule (``root``: the folder that holds ``dryfriction/``)."""
    out = []
    for target, names, line in _imports(module, path):
        if not target.startswith("dryfriction"):
            continue
        base = root.joinpath(*target.split("."))
        subs = [f"{target}.{n}" for n in names
                if base.joinpath(f"{n}.py").exists() or base.joinpath(n).is_dir()]
        out += [(t, line) for t in subs or [target]]
    return out


def _cycles(modules: list[tuple[str, Path]], root: Path = SRC.parent) -> list[list[str]]:
    """The import cycles among ``modules``: each strongly connected component of more than one
    module, or a module importing itself (Tarjan's algorithm)."""
    known = {m for m, _ in modules}
    graph = {m: sorted({t for t, _ in _targets(m, p, root) if t in known}) for m, p in modules}
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    stack: list[str] = []
    on_stack: set[str] = set()
    found: list[list[str]] = []

    def visit(v: str) -> None:
        index[v] = low[v] = len(index)
        stack.append(v)
        on_stack.add(v)
        for w in graph[v]:
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on_stack:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            component = []
            while True:
                w = stack.pop()
                on_stack.discard(w)
                component.append(w)
                if w == v:
                    break
            if len(component) > 1 or v in graph[v]:
                found.append(sorted(component))

    for v in graph:
        if v not in index:
            visit(v)
    return found


def test_no_import_cycle():
    # a cycle is two modules that cannot be read (or split) one without the other; one kept
    # alive by an import placed in a function is a cycle all the same
    cycles = [c for c in _cycles(MODULES) if frozenset(c) not in KNOWN_CYCLES]
    assert not cycles, "import cycles: " + "; ".join(" <-> ".join(c) for c in cycles)


# a module (with or without a function after ':') named by a string, in full
# ("dryfriction.plots.runs") or from the package ("plots.runs", as importlib's relative names)
_MODULE_STRING = re.compile(r"(?:dryfriction((?:\.\w+)+)|\.?(\w+(?:\.\w+)+))(?::\w+)?")
# the package's lazy public names (tests/test_compat.py checks that each is on a current path
# and loads; the package's root is in no layer) and the old paths of release 0.1, which are the
# subject of dryfriction._compat
_NAMES_MODULES_ON_PURPOSE = {"dryfriction", "dryfriction._compat"}


def _docstrings(tree: ast.AST) -> set[int]:
    ids = set()
    for node in ast.walk(tree):
        if isinstance(node, (ast.Module, ast.ClassDef, ast.FunctionDef, ast.AsyncFunctionDef)):
            body = node.body
            if body and isinstance(body[0], ast.Expr) and isinstance(body[0].value, ast.Constant):
                ids.add(id(body[0].value))
    # a string right after an assignment documents it (Sphinx's attribute docstrings)
    for node in ast.walk(tree):
        for field in ("body", "orelse"):
            stmts = getattr(node, field, None)
            if not isinstance(stmts, list):
                continue
            for before, stmt in zip(stmts, stmts[1:], strict=False):
                if (isinstance(before, (ast.Assign, ast.AnnAssign))
                        and isinstance(stmt, ast.Expr) and isinstance(stmt.value, ast.Constant)):
                    ids.add(id(stmt.value))
    return ids


def _module_strings(module: str, source: str) -> list[tuple[int, str]]:
    """(line, string) for each string constant, docstrings aside, that is a module of the
    package or ``module:function``."""
    tree = ast.parse(source)
    skip = _docstrings(tree)
    out = []
    for node in ast.walk(tree):
        if (isinstance(node, ast.Constant) and isinstance(node.value, str)
                and id(node) not in skip):
            match = _MODULE_STRING.fullmatch(node.value.strip())
            if match is None:
                continue
            where = SRC.joinpath(*(match.group(1) or "." + match.group(2)).split(".")[1:])
            if where.is_dir() or where.with_suffix(".py").exists():
                out.append((node.lineno, node.value))
    return out


@pytest.mark.parametrize("module, path", MODULES, ids=[m for m, _ in MODULES])
def test_no_module_named_in_a_string(module, path):
    # "dryfriction.plots.runs:rsf_figure" handed to importlib is an import that neither the
    # layer check nor the cycle check sees, and that breaks unseen when the module moves
    if module in _NAMES_MODULES_ON_PURPOSE:
        return
    bad = [f"{path.relative_to(SRC.parent)}:{n} names {v!r}"
           for n, v in _module_strings(module, path.read_text())]
    assert not bad, "; ".join(bad)


def test_the_cycle_and_string_checks_can_fail(tmp_path):
    # the mistakes these checks are for: two modules importing each other, one of them inside
    # a function (as io/lab and io/labsteps did), and a figure named by a string
    pkg = tmp_path / "dryfriction" / "records"
    pkg.mkdir(parents=True)
    (pkg / "a.py").write_text("from .b import f\n")
    (pkg / "b.py").write_text("def f():\n    from .a import g\n")
    (pkg / "c.py").write_text("from . import a\n")
    mods = [(f"dryfriction.records.{m}", pkg / f"{m}.py") for m in "abc"]
    assert _cycles(mods, tmp_path) == [["dryfriction.records.a", "dryfriction.records.b"]]
    (pkg / "b.py").write_text("def f():\n    from . import c\n")  # b -> c -> a -> b
    assert _cycles(mods, tmp_path) == [["dryfriction.records.a", "dryfriction.records.b",
                                        "dryfriction.records.c"]]
    assert _cycles(mods[::2], tmp_path) == []
    assert _module_strings("x", 'draw("dryfriction.plots.runs:rsf_figure")\n') == [
        (1, "dryfriction.plots.runs:rsf_figure")]
    assert _module_strings("x", '"""See dryfriction.plots.runs."""\nX = 1\n') == []
    assert _module_strings("x", 'importlib.import_module(".plots.runs", "dryfriction")\n') == [
        (1, ".plots.runs")]
    assert _module_strings("x", 'open("fit.json")\n') == []


def test_the_layer_check_can_fail(tmp_path):
    # a theory module importing the ensemble must be caught
    fake = tmp_path / "dryfriction" / "theory" / "x.py"
    fake.parent.mkdir(parents=True)
    fake.write_text("from ..ensemble.driving import simulate\n")
    (target, _, _), = _imports("dryfriction.theory.x", fake)
    assert target == "dryfriction.ensemble.driving"
    assert _layer(target) > _layer("dryfriction.theory.x")


# project-level checks (the layout, packaging, the docs, start-up) and root-level modules'
# tests (results.py's tables) stay at the top of tests/; everything else mirrors a package
ROOT_TESTS = {"test_layers", "test_packaging", "test_docs", "test_doc_paths", "test_readme",
              "test_startup", "test_benchmarks", "test_mutants_list", "test_tables", "test_compat",
              "test_simulator_shape",  # simulation.py, and no old simulator form anywhere
              "test_program", "test_validation", "test_warm"}  # program.py, validation.py, warm.py


def test_the_tests_mirror_the_packages() -> None:
    """Every test file lives in ``tests/<package>/`` for a package of ``src/dryfriction``
    (the generators the tests share stay in ``tests/``), and every package with code has its
    folder of tests."""
    tests = Path(__file__).resolve().parent
    packages = {p.parent.name for p in SRC.glob("*/__init__.py")
                if any(q.name != "__init__.py" for q in p.parent.glob("*.py"))}
    folders = {p.name for p in tests.iterdir() if p.is_dir() and p.name != "__pycache__"
               and any(p.glob("test_*.py"))}
    assert folders <= packages, f"test folders that name no package: {folders - packages}"
    assert packages <= folders, f"packages without a folder of tests: {packages - folders}"
    top = {p.stem for p in tests.glob("test_*.py")}
    assert top == ROOT_TESTS, f"test files at the top of tests/: {sorted(top ^ ROOT_TESTS)}"
