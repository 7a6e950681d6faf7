"""The package layout is the one-way flow docs/development.md draws: each stage imports only the
stages before it.  Read from the source (every import statement, also inside
functions), never by importing the package."""

from __future__ import annotations

import ast
from pathlib import Path

from support.paths import REPO

PACKAGE = REPO / "rkcheck"

BASE = {"errors", "version"}
#: unit -> the units it may import (a unit is a subpackage or a top-level module)
ALLOWED: dict[str, set[str]] = {
    "version": set(),
    "errors": set(),
    "options": BASE | {"numbers"},
    "verdicts": BASE | {"numbers"},
    "numbers": BASE,
    "trees": BASE,
    "methods": BASE | {"options", "numbers"},
    "io": BASE | {"options", "numbers", "methods"},
    "evaluation": BASE | {"numbers", "trees", "methods"},
    "properties": BASE | {"verdicts", "numbers", "trees", "methods", "evaluation"},
    "energy": BASE | {"options", "verdicts", "numbers", "trees", "methods", "evaluation", "properties"},
    "dynamics": BASE | {"options", "verdicts", "numbers", "methods", "evaluation", "properties", "energy"},
    "studies": BASE | {"options", "verdicts", "numbers", "trees", "methods", "evaluation", "properties", "energy"},
    "batch": BASE | {"options", "verdicts", "numbers", "trees", "methods", "io", "evaluation", "properties", "energy"},
    "reports": BASE | {"options", "verdicts", "numbers", "trees", "methods", "io", "evaluation", "properties",
                       "energy", "dynamics", "studies", "batch"},
    "api": BASE | {"options", "verdicts", "numbers", "trees", "methods", "io", "evaluation", "properties", "energy",
                   "dynamics", "studies", "batch", "reports"},
    "cli": BASE | {"options", "io", "reports", "api"},  # io: only io.printable (test_cli_uses_only_the_api)
    "__init__": BASE | {"api"},
    "program": BASE | {"cli"},
    "__main__": {"program"},
}
#: the core computes; it never prints, parses command lines or renders
CORE = ("verdicts", "numbers", "trees", "methods", "evaluation", "properties", "energy")


def unit_of(path: Path) -> str:
    rel = path.relative_to(PACKAGE)
    return rel.parts[0].removesuffix(".py") if len(rel.parts) > 1 else rel.stem


def imports(path: Path) -> list[tuple[int, str, list[str]]]:
    """(line, module, names) of every import of rkcheck in the file."""
    tree = ast.parse(path.read_text(encoding="utf-8"))
    out = []
    for node in ast.walk(tree):
        if isinstance(node, ast.ImportFrom):
            assert node.level == 0, f"{path}:{node.lineno}: relative import"
            if node.module and node.module.split(".")[0] == "rkcheck":
                out.append((node.lineno, node.module, [a.name for a in node.names]))
        elif isinstance(node, ast.Import):
            for alias in node.names:
                if alias.name.split(".")[0] == "rkcheck":
                    out.append((node.lineno, alias.name, []))
    return out


def imported_units(module: str, names: list[str]) -> set[str]:
    parts = module.split(".")
    if len(parts) > 1:
        return {parts[1]}
    # `from rkcheck import X`: the version string, or a public name (loaded from rkcheck.api)
    public = root_public_names()
    return {"__version__" if n == "__version__" else ("api" if n in public else n) for n in names}


def test_every_unit_has_a_rule():
    units = {unit_of(p) for p in PACKAGE.rglob("*.py")}
    assert units <= set(ALLOWED), f"add a rule for {sorted(units - set(ALLOWED))}"


def test_imports_follow_the_flow():
    bad = []
    for path in sorted(PACKAGE.rglob("*.py")):
        unit = unit_of(path)
        for line, module, names in imports(path):
            for target in imported_units(module, names) - {unit, "__version__"}:
                if target not in ALLOWED[unit]:
                    bad.append(f"{path.relative_to(REPO)}:{line}: {unit} imports {target} ({module})")
    assert not bad, "imports against the flow:\n" + "\n".join(bad)


#: What rkcheck/cli may import of rkcheck ("the CLI uses this API, nothing
#: else"): the package root (its version, its public names), the API, the renderers,
#: itself, the errors, the shared option vocabulary, and making file text printable.
CLI_MAY_IMPORT = ("rkcheck.api", "rkcheck.reports", "rkcheck.cli")
CLI_MAY_IMPORT_EXACTLY = ("rkcheck", "rkcheck.errors", "rkcheck.version", "rkcheck.options", "rkcheck.io.printable")


def cli_import_allowed(module: str) -> bool:
    return module in CLI_MAY_IMPORT_EXACTLY or any(module == p or module.startswith(p + ".") for p in CLI_MAY_IMPORT)


def _assigned(path: Path, name: str):
    """The literal value assigned to ``name`` at the top of a module (read from the source)."""
    for node in ast.parse(path.read_text(encoding="utf-8")).body:
        if isinstance(node, (ast.Assign, ast.AnnAssign)):
            targets = node.targets if isinstance(node, ast.Assign) else [node.target]
            if any(isinstance(t, ast.Name) and t.id == name for t in targets) and node.value is not None:
                return ast.literal_eval(node.value)
    raise AssertionError(f"{path}: no literal {name}")


def root_public_names() -> set[str]:
    """The names ``rkcheck`` exports: ``__version__`` and the ``__all__`` of each module
    listed in ``rkcheck/api/__init__.py``'s ``MODULES`` (read from the sources)."""
    names = {"__version__"}
    for module in _assigned(PACKAGE / "api" / "__init__.py", "MODULES"):
        names |= set(_assigned(PACKAGE / "api" / f"{module}.py", "__all__"))
    return names


def test_cli_uses_only_the_api():
    public = root_public_names()
    bad = []
    for path in sorted((PACKAGE / "cli").rglob("*.py")):
        for line, module, names in imports(path):
            # `from rkcheck import verify` takes a public name (loaded from rkcheck.api);
            # `from rkcheck import energy` would take a subpackage
            targets = [f"rkcheck.{n}" for n in names if n not in public] if module == "rkcheck" else [module]
            bad += [f"{path.relative_to(REPO)}:{line}: imports {t}" for t in targets if not cli_import_allowed(t)]
    assert not bad, "the CLI must go through rkcheck.api:\n" + "\n".join(bad)


def test_the_cli_rule_catches_core_imports(tmp_path):
    """The rule above is not vacuous: core modules, also inside functions, are caught."""
    assert not cli_import_allowed("rkcheck.energy.check") and not cli_import_allowed("rkcheck.io.loader")
    assert not cli_import_allowed("rkcheck.apis") and not cli_import_allowed("rkcheck.options_extra")
    assert cli_import_allowed("rkcheck.api.batch") and cli_import_allowed("rkcheck.io.printable")
    sample = tmp_path / "cmd.py"
    sample.write_text("def f():\n    from rkcheck.trees.listing import condition_listing\n    import rkcheck.numbers\n")
    assert [m for _, m, _ in imports(sample)] == ["rkcheck.trees.listing", "rkcheck.numbers"]
    assert {"scan", "verify", "OptionError", "__version__"} <= root_public_names() and "energy" not in root_public_names()


def test_core_does_no_io_and_knows_no_cli():
    forbidden = {"click", "rich", "sys.stdout", "builtins.print"}
    bad = []
    for unit in CORE:
        module = PACKAGE / f"{unit}.py"  # a unit is a subpackage or a top-level module
        for path in [module] if module.exists() else sorted((PACKAGE / unit).rglob("*.py")):
            tree = ast.parse(path.read_text(encoding="utf-8"))
            for node in ast.walk(tree):
                if isinstance(node, (ast.Import, ast.ImportFrom)):
                    names = [node.module] if isinstance(node, ast.ImportFrom) else [a.name for a in node.names]
                    if any(n and n.split(".")[0] in forbidden for n in names):
                        bad.append(f"{path.relative_to(REPO)}:{node.lineno}: imports {names}")
                if isinstance(node, ast.Call) and isinstance(node.func, ast.Name) and node.func.id in ("print", "open"):
                    bad.append(f"{path.relative_to(REPO)}:{node.lineno}: calls {node.func.id}()")
    assert not bad, "\n".join(bad)


def test_every_subpackage_says_what_it_takes_gives_and_may_import():
    for init in sorted(PACKAGE.glob("*/__init__.py")):
        doc = ast.get_docstring(ast.parse(init.read_text(encoding="utf-8"))) or ""
        assert "May import" in doc or init.parent.name == "cli", f"{init}: docstring lacks the import rule"
        assert len(doc.split()) >= 20, f"{init}: docstring too short to say what the stage takes and gives"


# ------------------------------------------------------------------ no cycles


def module_of(path: Path) -> str:
    rel = path.relative_to(REPO).with_suffix("")
    parts = rel.parts[:-1] if rel.name == "__init__" else rel.parts
    return ".".join(parts)


def import_graph() -> dict[str, set[str]]:
    """module -> the rkcheck modules it imports, at the top or inside a function alike
    (``from rkcheck.x import y`` counts as importing ``rkcheck.x.y`` when that is a
    module, else ``rkcheck.x``)."""
    modules = {module_of(p): p for p in PACKAGE.rglob("*.py")}
    graph: dict[str, set[str]] = {}
    for name, path in modules.items():
        targets = set()
        for _, module, names in imports(path):
            subs = [f"{module}.{n}" for n in names if f"{module}.{n}" in modules]
            targets |= set(subs) if subs and len(subs) == len(names) else {module}
        graph[name] = {t for t in targets if t in modules and t != name}
    return graph


def cycles(graph: dict[str, set[str]]) -> list[list[str]]:
    """The strongly connected components with more than one module (Tarjan's algorithm,
    iterative)."""
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    stack: list[str] = []
    on_stack: set[str] = set()
    out: list[list[str]] = []
    counter = 0
    for root in sorted(graph):
        if root in index:
            continue
        work = [(root, iter(sorted(graph[root])))]
        index[root] = low[root] = counter
        counter += 1
        stack.append(root)
        on_stack.add(root)
        while work:
            v, it = work[-1]
            w = next(it, None)
            if w is not None:
                if w not in index:
                    index[w] = low[w] = counter
                    counter += 1
                    stack.append(w)
                    on_stack.add(w)
                    work.append((w, iter(sorted(graph.get(w, ())))))
                elif w in on_stack:
                    low[v] = min(low[v], index[w])
                continue
            work.pop()
            if work:
                low[work[-1][0]] = min(low[work[-1][0]], low[v])
            if low[v] == index[v]:
                component = []
                while True:
                    w = stack.pop()
                    on_stack.discard(w)
                    component.append(w)
                    if w == v:
                        break
                if len(component) > 1:
                    out.append(sorted(component))
    return out


#: Package ``__init__`` modules that load their public names lazily from their own
#: submodules (PEP 562): the submodule importing its package is Python's import
#: machinery, not a dependency.
LAZY_PACKAGES = {"rkcheck", "rkcheck.api"}


def test_no_module_imports_in_a_cycle():
    """No two modules need each other, not even through an import inside a function:
    such an import hides a cycle rather than removing it."""
    graph = {m: {t for t in targets if t not in LAZY_PACKAGES} for m, targets in import_graph().items()}
    found = cycles(graph)
    assert not found, "import cycles:\n" + "\n".join(" <-> ".join(c) for c in found)


def test_the_cycle_finder_finds_cycles():
    assert cycles({"a": {"b"}, "b": {"c"}, "c": {"a"}, "d": {"a"}}) == [["a", "b", "c"]]
    assert cycles({"a": {"b"}, "b": set()}) == []


#: the modules that import mpmath; .ci/run tests them (through the tests of these
#: modules: dynamics, studies, the double-bush rank, arrays) with mpmath's newest release
#: as well, so a module that starts to use mpmath belongs here and its tests there
MPMATH_USERS = {"energy/double_bush.py", "energy/double_bush_rank.py", "dynamics/hamiltonians.py",
                "dynamics/integrator.py", "dynamics/simulate.py", "studies/accuracy.py", "methods/arrays.py",
                "reports/studies.py", "reports/simulation.py"}


def test_the_modules_that_use_mpmath_are_the_ones_ci_tests_with_both_releases():
    users = set()
    for path in PACKAGE.rglob("*.py"):
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
            names = ([a.name for a in node.names] if isinstance(node, ast.Import)
                     else [node.module or ""] if isinstance(node, ast.ImportFrom) else [])
            if any(n.split(".")[0] == "mpmath" for n in names):
                users.add(path.relative_to(PACKAGE).as_posix())
    assert users == MPMATH_USERS
    ci = (REPO / ".ci" / "run").read_text(encoding="utf-8")
    for tests in ("tests/dynamics", "tests/studies", "tests/energy/test_double_bush_exact.py",
                  "tests/api/test_api_misuse.py"):
        assert tests in ci
