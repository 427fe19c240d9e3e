"""The package's layers stay true: imports go down only, no module reads another's private
names, only ``plots/`` draws, and no module grows past the size a reader can hold.

Read from the source (AST), so an import inside a function counts as much as one at the top.
"""

from __future__ import annotations

import ast
from pathlib import Path

import pytest

SRC = Path(__file__).resolve().parents[1] / "src" / "dryfriction"

# bottom to top; a module may import its own layer and those below
LAYERS: list[set[str]] = [
    {"validation", "program", "results", "simulation", "_compat", "interrupts"},
    {"theory"},
    {"ensemble", "rsf"},
    {"io"},
    {"fit"},
    {"analysis"},
    {"plots"},
    {"cli", "warm"},  # warm: the install step's entry point (python -m dryfriction.warm)
]
MAX_LINES = 650  # "no module over ~600 lines"


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
# sweep's cluster (io/cluster.py only) uses the names CPython's own tests use
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
           and not (module == "dryfriction.io.cluster" and node.attr in _FORK_SERVER_NAMES)
           and not (isinstance(node.value, ast.Name) and node.value.id in ("self", "cls"))]
    assert not bad, "; ".join(bad)


@pytest.mark.parametrize("module, path", MODULES, ids=[m for m, _ in MODULES])
def test_only_plots_draw(module, path):
    if module.startswith("dryfriction.plots"):
        return
    for target, _, line in _imports(module, path):
        assert not target.startswith("matplotlib"), (
            f"{path.relative_to(SRC.parent)}:{line} imports matplotlib outside plots/")


@pytest.mark.parametrize("module, path", MODULES, ids=[m for m, _ in MODULES])
def test_modules_stay_readable(module, path):
    n = len(path.read_text().splitlines())
    assert n <= MAX_LINES, f"{path.relative_to(SRC.parent)} has {n} lines (> {MAX_LINES})"


def test_the_layer_check_can_fail(tmp_path):
    # a theory module importing the ensemble must be caught
    fake = tmp_path / "dryfriction" / "theory" / "x.py"
    fake.parent.mkdir(parents=True)
    fake.write_text("from ..ensemble.driving import simulate\n")
    (target, _, _), = _imports("dryfriction.theory.x", fake)
    assert target == "dryfriction.ensemble.driving"
    assert _layer(target) > _layer("dryfriction.theory.x")
