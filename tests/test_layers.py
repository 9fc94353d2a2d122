"""The layering of docs/architecture.md, enforced: `lint-imports` keeps the contracts
of pyproject.toml ([tool.importlinter])."""

from __future__ import annotations

import ast
import shutil
import subprocess
import sys
import tomllib
from pathlib import Path
from typing import Any

import pytest

ROOT = Path(__file__).parent.parent


def _lint_imports() -> list[str]:
    found = shutil.which("lint-imports", path=str(Path(sys.executable).parent))
    if found is None:
        found = shutil.which("lint-imports")
    if found is None:
        pytest.skip("import-linter is not installed (pip install -e '.[test]' brings it)")
    return [found]


def test_import_contracts_are_kept() -> None:
    result = subprocess.run([*_lint_imports(), "--no-cache"], cwd=ROOT, capture_output=True,
                            text=True, timeout=120)
    assert result.returncode == 0, result.stdout + result.stderr
    # every contract of pyproject.toml was checked, and kept
    config = tomllib.loads((ROOT / "pyproject.toml").read_text(encoding="utf-8"))
    contracts = config["tool"]["importlinter"]["contracts"]
    assert len(contracts) >= 4
    assert f"{len(contracts)} kept, 0 broken" in result.stdout, result.stdout


def test_core_messages_name_no_command_line_option() -> None:
    # core speaks of the model; the library and the command line word refusals for users
    for path in sorted((ROOT / "src" / "gyrovib" / "core").glob("*.py")):
        text = path.read_text(encoding="utf-8")
        for flag in ("--method", "--profile", "--sensor", "--rate", "--samples", "--unit"):
            assert flag not in text, f"{path.name} mentions {flag}"


# ----------------------------------------------------------------- the package's own imports

SRC = ROOT / "src"
#: The package faces, whose module ``__getattr__`` imports their names on first use.
FACES = ("gyrovib", "gyrovib.api")


def _modules() -> dict[str, Path]:
    out = {}
    for path in sorted((SRC / "gyrovib").rglob("*.py")):
        parts = list(path.relative_to(SRC).with_suffix("").parts)
        if parts[-1] == "__init__":
            parts.pop()
        out[".".join(parts)] = path
    return out


def _type_checking(node: ast.AST) -> bool:
    return isinstance(node, ast.If) and "TYPE_CHECKING" in ast.unparse(node.test)


def _imports(name: str, path: Path, known: dict[str, Path],
             annotations: bool = False) -> set[str]:
    """The package's modules ``name`` imports, anywhere in it (functions too), except
    under ``if TYPE_CHECKING:`` (annotations only) unless ``annotations``."""
    package = name if path.name == "__init__.py" else name.rpartition(".")[0]
    found: set[str] = set()

    def visit(node: ast.AST) -> None:
        if _type_checking(node) and not annotations:
            return
        if isinstance(node, ast.Import):
            found.update(a.name for a in node.names)
        elif isinstance(node, ast.ImportFrom):
            base = node.module or ""
            if node.level:
                parent = package.split(".")[: len(package.split(".")) - node.level + 1]
                base = ".".join([*parent, *([base] if base else [])])
            names = {f"{base}.{a.name}" for a in node.names}
            found.update(names)
            if not names <= set(known):  # a name of the package itself, not a submodule
                found.add(base)
        for child in ast.iter_child_nodes(node):
            visit(child)

    visit(ast.parse(path.read_text(encoding="utf-8")))
    return {m for m in found if m in known and m != name}


def _graph(annotations: bool = False) -> dict[str, set[str]]:
    known = _modules()
    return {name: _imports(name, path, known, annotations) for name, path in known.items()}


def _cycles(graph: dict[str, set[str]]) -> list[list[str]]:
    """The strongly connected components of more than one module (Tarjan)."""
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    stack: list[str] = []
    on: set[str] = set()
    out: list[list[str]] = []

    def strong(v: str) -> None:
        index[v] = low[v] = len(index)
        stack.append(v)
        on.add(v)
        for w in sorted(graph[v]):
            if w not in index:
                strong(w)
                low[v] = min(low[v], low[w])
            elif w in on:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            part = []
            while True:
                w = stack.pop()
                on.discard(w)
                part.append(w)
                if w == v:
                    break
            if len(part) > 1:
                out.append(sorted(part))

    for v in sorted(graph):
        if v not in index:
            strong(v)
    return out


def test_no_import_circle_in_the_package() -> None:
    graph = _graph()
    assert graph["gyrovib.api.commands.select"] >= {"gyrovib.api.study.study"}  # the probe works
    assert _cycles(graph) == []


def test_no_import_circle_counting_annotations() -> None:
    # the imports under `if TYPE_CHECKING:` too: a type a module only names in its
    # annotations is taken from the package face, so even the picture of who needs
    # whom has no circle
    assert _cycles(_graph(annotations=True)) == []


def test_the_cycle_finder_finds_a_circle() -> None:
    # the finder itself, on a made-up graph: a → b → c → a, d alone
    graph = {"a": {"b"}, "b": {"c"}, "c": {"a"}, "d": {"a"}}
    assert _cycles(graph) == [["a", "b", "c"]]


def test_only_package_faces_have_a_module_getattr() -> None:
    found = []
    for name, path in _modules().items():
        tree = ast.parse(path.read_text(encoding="utf-8"))
        if any(isinstance(n, ast.FunctionDef) and n.name == "__getattr__" for n in tree.body):
            found.append(name)
    assert sorted(found) == sorted(FACES)


def _complexity(function: ast.FunctionDef) -> int:
    """McCabe's cyclomatic complexity: 1 + decisions (branches, loops, handlers, and/or)."""
    count = 1
    for node in ast.walk(function):
        if isinstance(node, ast.If | ast.For | ast.While | ast.IfExp | ast.ExceptHandler
                      | ast.AsyncFor | ast.match_case):
            count += 1
        elif isinstance(node, ast.BoolOp):
            count += len(node.values) - 1
        elif isinstance(node, ast.comprehension):
            count += 1 + len(node.ifs)
    return count


#: The preparation and evaluation every command shares, and the views on it.
PIPELINE = ("api/study/study.py", "api/study/prepare.py", "api/evaluation/evaluate.py",
            "api/evaluation/checks.py", "api/commands/sweep.py",
            "api/commands/bounds.py:bounds_of", "api/commands/analyze.py:analysis_of",
            "api/commands/select.py:selection_of", "api/report/views.py:trade_study")


def test_the_preparation_is_made_of_small_functions() -> None:
    over = {}
    for where in PIPELINE:
        rel, _, only = where.partition(":")
        tree = ast.parse((SRC / "gyrovib" / rel).read_text(encoding="utf-8"))
        for node in ast.walk(tree):
            if (isinstance(node, ast.FunctionDef) and node.name == (only or node.name)
                    and _complexity(node) >= 15):
                over[f"{rel}:{node.name}"] = _complexity(node)
    assert over == {}


def test_the_error_loop_and_the_saturation_rule_are_written_once() -> None:
    # eq. (13)-(16) over the sensor groups, and reach > range, are called from one
    # module of the library (the brute force of analyze --method numeric turns its
    # sample moments into terms with vibration_error too: it is the one other caller)
    calls: dict[str, list[str]] = {"vibration_error": [], "saturated_at": []}
    for path in sorted((SRC / "gyrovib" / "api").rglob("*.py")):
        tree = ast.parse(path.read_text(encoding="utf-8"))
        for node in ast.walk(tree):
            if isinstance(node, ast.FunctionDef):
                for call in ast.walk(node):
                    if (isinstance(call, ast.Call) and isinstance(call.func, ast.Name)
                            and call.func.id in calls):
                        calls[call.func.id].append(
                            f"{path.relative_to(SRC / 'gyrovib')}:{node.name}")
    assert sorted(set(calls["vibration_error"])) == ["api/commands/analyze.py:_simulate",
                                                      "api/evaluation/evaluate.py:error"]
    assert calls["saturated_at"] == ["api/evaluation/evaluate.py:saturation"]


def test_one_immutability_mechanism_in_the_library() -> None:
    # every dataclass of gyrovib.api is declared frozen=True, eq=False, repr=False on
    # the Frozen base (directly or through Result): one mechanism, not three
    found = []
    for path in sorted((SRC / "gyrovib" / "api").rglob("*.py")):
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
            if not isinstance(node, ast.ClassDef):
                continue
            for deco in node.decorator_list:
                if "dataclass" in ast.unparse(deco):
                    found.append((node.name, ast.unparse(deco),
                                  [ast.unparse(b) for b in node.bases]))
    assert len(found) > 20  # the probe works
    odd = [f for f in found
           if f[1] != "dataclass(frozen=True, eq=False, repr=False)"
           or not set(f[2]) & {"Frozen", "Result", "SensorsByProfiles"}]
    assert odd == []


def test_the_api_face_lists_its_names_once_for_run_time_and_types() -> None:
    # __init__.pyi is the one listing: type checkers read its imports, and __init__.py
    # reads the same lines to import each name on first use
    import gyrovib.api as face

    stub = ast.parse((SRC / "gyrovib" / "api" / "__init__.pyi").read_text(encoding="utf-8"))
    typed = {a.asname or a.name for n in stub.body if isinstance(n, ast.ImportFrom)
             for a in n.names}
    assert len(typed) > 40  # the probe works
    assert typed == set(face._WHERE) == set(face.__all__)
    for name in sorted(typed):  # and each resolves at run time
        assert getattr(face, name) is not None


def test_each_room_of_the_api_has_one_face() -> None:
    # every package under gyrovib.api says what it holds, and the names of its face
    # resolve (a module of the room renamed or a name dropped breaks this)
    import importlib

    rooms = sorted(p.parent for p in (SRC / "gyrovib" / "api").glob("*/__init__.py"))
    assert {r.name for r in rooms} >= {"study", "datasheet", "evaluation", "commands",
                                       "report", "placement"}
    for room in rooms:
        module = importlib.import_module(f"gyrovib.api.{room.name}")
        assert (module.__doc__ or "").strip(), room.name
        for name in getattr(module, "__all__", ()):
            assert getattr(module, name) is not None, (room.name, name)


#: The house rules for every module of the package: no function over this
#: cyclomatic complexity (radon counts the same decisions), no module over so many lines.
MAX_COMPLEXITY = 15
MAX_LINES = 600


def test_no_function_in_the_package_is_over_complexity_15() -> None:
    # radon's own count (the measure the house rule names), methods and closures included
    from radon.complexity import cc_visit
    from radon.visitors import Class

    def blocks(items: list[Any]) -> Any:
        for block in items:
            yield block
            yield from blocks(list(getattr(block, "methods", [])) if isinstance(block, Class)
                              else list(getattr(block, "closures", [])))

    over = {}
    for path in sorted((SRC / "gyrovib").rglob("*.py")):
        for block in blocks(cc_visit(path.read_text(encoding="utf-8"))):
            if not isinstance(block, Class) and block.complexity > MAX_COMPLEXITY:
                over[f"{path.relative_to(SRC / 'gyrovib')}:{block.name}"] = block.complexity
    assert over == {}


def test_no_module_in_the_package_is_over_600_lines() -> None:
    long = {str(path.relative_to(SRC / "gyrovib")): n
            for path in sorted((SRC / "gyrovib").rglob("*.py"))
            if (n := len(path.read_text(encoding="utf-8").splitlines())) > MAX_LINES}
    assert long == {}


def test_the_complexity_probe_counts_decisions() -> None:
    # the probe itself: 1 + an if, a for with a condition, a boolean and
    code = "def f(x):\n    if x and x > 1:\n        return [y for y in x if y]\n    return 0\n"
    function = ast.parse(code).body[0]
    assert isinstance(function, ast.FunctionDef)
    assert _complexity(function) == 1 + 1 + 1 + 2
