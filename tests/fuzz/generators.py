"""The fuzzer's inputs, shared by the suite (tests/fuzz/test_fuzz_cli.py, a few dozen
examples) and ``benchmarks/fuzz.py`` (thousands, each in its own process).

Each strategy draws a :class:`Case`: the command line, the files it reads (written into
a fresh folder that is the working directory of the run) and the standard input.  Four
families: single entries (and constants) inside an otherwise valid tableau, whole files
(shipped tableaux mutated token by token, random TOML/JSON documents, random bytes),
option sets of every command, and the importers (nodepy text, CSV/TSV).
"""

from __future__ import annotations

import json
from dataclasses import dataclass, field
from pathlib import Path

from hypothesis import strategies as st

ROOT = Path(__file__).resolve().parents[2]


@dataclass
class Case:
    args: list[str]
    files: dict[str, bytes] = field(default_factory=dict)
    stdin: bytes | None = None

    def describe(self) -> str:
        shown = {name: data[:300].decode("utf-8", "backslashreplace") for name, data in self.files.items()}
        return f"rkcheck {' '.join(self.args)}  files={shown}"


# ------------------------------------------------------------------ entries

#: pieces of the entry grammar, and the characters around it that users (and attackers) type
TOKENS = ["1", "2", "0", "3", "1/3", "0.5", "1.2345678", "0.2113248654051871", "1e-3", "1e200", "1e400", "1e-400",
          "9" * 50, "+", "-", "*", "/", "^", "**", "(", ")", "sqrt(", "root(", "x", "x^3-2", ",", " ", "r", "c0",
          "\u2212", "\u00d7", "\u00b7", "\u03c0", "\u00b2", "\u0661", "\x00", "\x1b", "\n", ".", "e", "2^1000",
          "10^999", "2^-1000", "nan", "inf", "None", "import", "Fraction", "sqrt(2)", "sqrt(3)/6", "root(x^2-3,1)",
          "root(x^5-x-1, 1)", "1/7", "12345678901234567890.123456789", "0." + "3" * 60]
ATOMS = ["1", "2", "3", "0", "1/2", "1/3", "1/7", "0.5", "0.2113248654051871", "1e200", "1e-200", "1e155", "9" * 40,
         "2^1000", "2^-1000", "10^300", "r", "s", "c0", "sqrt(2)", "sqrt(3)", "root(x^3-2, 1)", "root(x^5-x-1, 1)",
         "12345678901234567890.123456789", "0." + "3" * 60, "-1", "1e-20", "0.1"]
#: well-formed expressions, so that the layers after the parser are reached
expressions = st.recursive(
    st.sampled_from(ATOMS),
    lambda inner: st.tuples(inner, st.sampled_from(["+", "-", "*", "/", "^"]), inner).map(
        lambda t: f"({t[0]}){t[1]}({t[2]})" if t[1] == "^" and len(t[2]) > 2 else f"{t[0]} {t[1]} {t[2]}")
    | inner.map(lambda x: f"sqrt({x})") | inner.map(lambda x: f"-({x})")
    | st.tuples(inner, st.integers(1, 3)).map(lambda t: f"root(x^{t[1] + 1} - ({t[0]}), 1)"),
    max_leaves=8)
entry_texts = (expressions | expressions | st.lists(st.sampled_from(TOKENS), min_size=0, max_size=25).map("".join)
               | st.text(max_size=40))


def _json_case(doc: dict, *args: str, name: str = "t.json") -> Case:
    return Case(["verify", name, *args], {name: json.dumps(doc).encode("utf-8", "surrogateescape")})


@st.composite
def entry_cases(draw) -> Case:
    """A valid 2-stage tableau with constants, one or two of whose entries (or constants,
    which the others refer to) are fuzzed."""
    slots = {"c0": "1/3", "r": "sqrt(3)/6", "s": "1/2 - r", "A11": "1/4", "A12": "1/4 - r", "A21": "1/4 + r",
             "A22": "1/4", "b1": "1/2", "b2": "c0 + 1/6"}
    for slot in draw(st.lists(st.sampled_from(list(slots)), min_size=1, max_size=2, unique=True)):
        slots[slot] = draw(entry_texts)
    doc = {"constants": {k: slots[k] for k in ("c0", "r", "s")},
           "tableau": {"A": [[slots["A11"], slots["A12"]], [slots["A21"], slots["A22"]]], "b": [slots["b1"], slots["b2"]]}}
    command = draw(st.sampled_from(["verify", "verify", "verify", "show", "explain", "scan"]))
    if command == "show":
        fmt = draw(st.sampled_from(["text", "json", "toml", "python", "julia", "latex"]))
        return Case(["show", "t.json", "--format", fmt], _json_case(doc).files)
    if command == "explain":
        return Case(["explain", "1,2,2", "--tableau", "t.json"], _json_case(doc).files)
    extra = draw(st.sampled_from([[], ["--arithmetic", "ball"], ["--decimals", "exact"], ["--decimals", "rounded"],
                                  ["--format", "json"], ["--degree", "2"], ["--format", "junit"], ["--format", "github"]]))
    if command == "verify" and extra[:1] == ["--format"] and extra[1] in ("junit", "github"):
        extra = ["--all"]
    return Case([command, "t.json", "--order", "3", *extra], _json_case(doc).files)


# ------------------------------------------------------------------ whole files

def _shipped() -> list[tuple[str, str]]:
    files = sorted(p for p in (ROOT / "tableaux").rglob("*") if p.suffix in (".toml", ".json"))
    return [(p.name, p.read_text(encoding="utf-8")) for p in files]


SHIPPED = _shipped()
MUTANTS = ["\"1e200\"", "\"1/0\"", "\"\"", "1e400", "[", "]", "{", "}", "=", "\"", ",", "\n", "[[", "99999",
           "-1", "true", "\"sqrt(-1)\"", "\"root(x^60-2, 1)\"", "\"0.2113248654051871\"", "\x00", "\ufeff",
           "\"\x1b[2J\"", "[check]\norder = 30\n", "[check]\ndps = 5000\n", "[expect]\nclassical_order = 20\n",
           "[expect]\nenergy_order = 30\n", "[family]\nname = \"gauss\"\ns = 20\n", "name = \"*x* `y`|z\"\n"]


@st.composite
def mutated_files(draw) -> Case:
    """A shipped tableau file with a few tokens inserted, deleted or replaced."""
    name, text = draw(st.sampled_from(SHIPPED))
    for _ in range(draw(st.integers(1, 4))):
        if not text:
            break
        at = draw(st.integers(0, len(text)))
        how = draw(st.sampled_from(["insert", "delete", "replace", "duplicate"]))
        piece = draw(st.sampled_from(MUTANTS) | st.sampled_from(TOKENS))
        if how == "insert":
            text = text[:at] + piece + text[at:]
        elif how == "delete":
            text = text[:at] + text[at + draw(st.integers(1, 30)):]
        elif how == "replace":
            end = text.find('"', at + 1)
            text = text[:at] + piece + (text[end:] if end > 0 else "")
        else:
            line_start = text.rfind("\n", 0, at) + 1
            line_end = text.find("\n", at)
            line = text[line_start: line_end if line_end >= 0 else len(text)]
            text = text[:line_start] + line + "\n" + text[line_start:]
    suffix = draw(st.sampled_from([".toml", ".toml", ".json", ".csv", ".txt", ""]))
    fname = Path(name).stem + suffix
    command = draw(st.sampled_from(["verify", "verify", "show", "scan", "catalog"]))
    args = [command, fname] + (["--order", "4"] if command in ("verify", "scan", "catalog") else [])
    if command == "catalog":
        args = ["catalog", fname]
    return Case(args, {fname: text.encode("utf-8", "surrogateescape")})


scalars = st.one_of(st.integers(min_value=-10**30, max_value=10**30), st.booleans(), st.text(max_size=12),
                    st.sampled_from(["1/2", "0", "1", "sqrt(2)", "none", "all", "exact", "rounded", "1e200"]),
                    st.floats(allow_nan=False, allow_infinity=False))
values = st.recursive(scalars, lambda children: st.lists(children, max_size=4)
                      | st.dictionaries(st.sampled_from(["A", "b", "c", "x", "name", "order", "value", "degree"]),
                                        children, max_size=3), max_leaves=12)
TABLES = ["method", "constants", "tableau", "check", "expect", "family", "other"]
KEYS = {"method": ["name", "description", "references"], "constants": ["r3", "q", "x", "None", "import"],
        "tableau": ["A", "b", "c"], "check": ["degree", "order", "dps", "decimals", "require", "ordr"],
        "expect": ["energy_order", "avf", "classical_order", "quadrature_order", "symplectic", "other"],
        "family": ["name", "s", "k", "rule", "zeta", "beta"], "other": ["x"]}


@st.composite
def documents(draw) -> dict:
    doc: dict = {}
    for table in draw(st.lists(st.sampled_from(TABLES), max_size=4, unique=True)):
        doc[table] = {key: draw(values) for key in draw(st.lists(st.sampled_from(KEYS[table]), max_size=3,
                                                                 unique=True))}
    if draw(st.booleans()):  # often a nearly valid tableau, so that the deeper layers are reached
        s = draw(st.integers(min_value=1, max_value=3))
        cell = st.sampled_from(["0", "1/2", "1/3", "sqrt(3)/6", "0.2113248654", "1e-3", "-1", "1e200"]) | values
        doc["tableau"] = {"A": [[draw(cell) for _ in range(s)] for _ in range(s)], "b": [draw(cell) for _ in range(s)]}
    return doc


def toml_text(doc: dict) -> str:
    """A small TOML writer for the generated documents."""
    def value(v):
        if isinstance(v, bool):
            return "true" if v else "false"
        if isinstance(v, (int, float)):
            return repr(v)
        if isinstance(v, str):
            return json.dumps(v)  # a JSON string is a TOML basic string
        if isinstance(v, list):
            return "[" + ", ".join(value(x) for x in v) + "]"
        return "{" + ", ".join(f"{json.dumps(k)} = {value(x)}" for k, x in v.items()) + "}"

    lines = []
    for table, body in doc.items():
        lines.append(f"[{table}]")
        lines.extend(f"{json.dumps(k)} = {value(v)}" for k, v in body.items())
    return "\n".join(lines) + "\n"


@st.composite
def document_files(draw) -> Case:
    doc = draw(documents())
    if draw(st.booleans()):
        name, data = "t.toml", toml_text(doc).encode("utf-8", "surrogateescape")
    else:
        name, data = "t.json", json.dumps(doc).encode("utf-8")
    command = draw(st.sampled_from(["verify", "show", "scan"]))
    return Case([command, name] + (["--order", "3"] if command != "show" else []), {name: data})


@st.composite
def byte_files(draw) -> Case:
    data = draw(st.binary(max_size=300))
    name = draw(st.sampled_from(["t.toml", "t.json", "t.csv", "t.txt", "-"]))
    if name == "-":
        return Case(["verify", "-", "--order", "3"], stdin=data)
    return Case(["verify", name, "--order", "3"], {name: data})


file_cases = mutated_files() | mutated_files() | document_files() | byte_files()


# ------------------------------------------------------------------ options

#: hostile values, tried on any flag
VALUES = ["0", "-1", "31", "5001", "x", "", "1e9", "99999999999999999999", "1e300", "nan", "inf", "1e-1000",
          "/dev/stdout", "\x1b[2J"]
#: values each flag accepts (most runs use one, so that the run gets past validation)
VALID = {
    "--order": ["1", "2", "3", "4", "5"], "-N": ["1", "2", "3", "4", "5"], "--dps": ["10", "15", "30", "50", "700"],
    "--degree": ["2", "3", "4", "none"], "-m": ["2", "3", "4", "6", "none"],
    "--decimals": ["auto", "rounded", "float64", "exact"], "--max-stages": ["1", "2", "64", "1000"],
    "--arithmetic": ["auto", "exact", "ball"], "--max-conditions": ["1", "10", "100000"],
    "--require": ["any", "proof", "digits:10", "digits:100"], "--jobs": ["1", "2"],
    "--fail-on": ["auto", "conditions", "claims", "never"], "-o": ["out.txt", "/dev/stdout", "missing/out.txt", "-"],
    "--sort": ["path", "energy"], "--emit": ["python", "sympy", "julia", "matlab", "latex"],
    "-s": ["1", "2", "3", "4"], "--stages": ["1", "2", "3"], "--rule": ["gauss", "radau-i", "radau-ii", "lobatto",
                                                                      "zeta:1/3", "zeta:-1", "zeta:1e7", "zeta:1e400", "x"],
    "--tableau": ["t.toml", "@rk4", "missing.toml"], "--problem": ["harmonic", "quartic", "henon-heiles",
                                                                  "random:degree=4", "random:degree=99,dim=99"],
    "--h": ["1/10", "0.1", "1/16", "1e300", "1e-1000", "0", "-1"], "--steps": ["1", "10", "50", "20000000"],
    "--points": ["1", "2", "101"], "--eps": ["1/1000", "1e-3,1e-6", "0", "2", "1e-300"],
    "--digits": ["1", "10", "60", "5000"], "--zeta": ["1/3", "-1", "0", "1e7"],
    "--format": ["text", "json", "csv", "junit", "github", "toml", "tableau-json", "latex", "julia", "python"],
    "--direction": ["random", "kernel", "entry:1,1", "entry:9,9", "x"], "--seed": ["1", "-5"],
}
COMMAND_OPTIONS = {
    "verify": ["--order", "--dps", "--degree", "--decimals", "--max-stages", "--arithmetic", "--format",
               "--max-conditions", "--require", "--all", "--fail-on", "--fail-fast"],
    "show": ["--format", "--max-stages", "--decimals"],
    "scan": ["--order", "--dps", "--degree", "--format", "--jobs", "--fail-on", "-o", "--sort", "--max-conditions",
             "--decimals", "--require"],
    "conditions": ["-N", "-m", "--emit", "--max-conditions", "--count", "-s", "--format", "--classical"],
    "explain": ["--tableau", "--dps", "--decimals"],
    "kernel": ["-s", "-m", "--dps", "--rule", "--tableau"],
    "simulate": ["--problem", "--h", "--steps", "--dps", "--points", "--energy-order"],
    "perturb": ["--eps", "--order", "--degree", "--dps", "--seed"],
    "new": ["--digits", "-s", "--zeta", "-o", "--exact"],
    "catalog": ["--order", "-o"],
}
FLAGS = {"--all", "--count", "--fail-fast", "--classical", "--energy-order", "--exact"}
OPTION_FILE = b'[tableau]\nA = [["1/4", "1/4 - sqrt(3)/6"], ["1/4 + sqrt(3)/6", "1/4"]]\nb = ["1/2", "1/2"]\n'


@st.composite
def option_cases(draw) -> Case:
    command = draw(st.sampled_from(list(COMMAND_OPTIONS)))
    args = [command]
    if command in ("verify", "show", "scan", "simulate", "perturb", "catalog"):
        args.append(draw(st.sampled_from(["t.toml", "t.toml", "@rk4", "@gauss-2", "missing.toml", "."])))
    if command == "explain":
        args.append(draw(st.sampled_from(["1,2,2", "1,2,3,3", "1,2,3,3,2,2", "3", "0", "x"])))
    if command == "new":
        args.append(draw(st.sampled_from(["gauss", "avf", "lobatto-iiia", "radau-iia", "x"])))
    if command == "perturb":
        args += ["--direction", draw(st.sampled_from(VALID["--direction"]))]
    for flag in draw(st.lists(st.sampled_from(COMMAND_OPTIONS[command]), max_size=4)):
        if flag in FLAGS:
            args.append(flag)
            continue
        hostile = draw(st.integers(0, 4)) == 0
        args += [flag, draw(st.sampled_from(VALUES if hostile else VALID.get(flag, VALUES)))]
    # keep each run small: options that pass validation must still finish in seconds
    if command in ("verify", "scan", "perturb", "catalog") and "--order" not in args:
        args += ["--order", "4"]
    if command == "conditions" and "-N" not in args:
        args += ["-N", "4"]
    if command == "simulate":
        if "--problem" not in args:
            args += ["--problem", "harmonic"]
        if "--steps" not in args:
            args += ["--steps", "50"]
    if command == "kernel":
        if "-m" not in args:
            args += ["-m", "6"]
        if "-s" not in args and "--tableau" not in args:
            args += ["-s", "2"]
    if command == "scan" and "--jobs" not in args:
        args += ["--jobs", "1"]
    return Case(args, {"t.toml": OPTION_FILE})


# ------------------------------------------------------------------ importers

nodepy_values = (st.sampled_from(["0.5", "1", "0", "-0.25", "0.2113248654051871", "0.788675134594813"])
                 | st.sampled_from(["1e200", "x", "1/3", "sqrt(3)/6", "1,5"]) | entry_texts)


@st.composite
def nodepy_cases(draw) -> Case:
    lines = []
    huge = st.sampled_from([99999, 10**30, 64, 65])
    sections = ["A[k,j]", "b[k]"] + draw(st.lists(st.sampled_from(["A[k,j]", "b[k]", "c[k]", "bhat[k]", "junk"]),
                                                  max_size=3))
    for section in sections:
        lines.append(draw(st.sampled_from(["", "Feagin ", "#"])) + section)
        for _ in range(draw(st.integers(0, 5))):
            width = (3 if section == "A[k,j]" else 2) if draw(st.integers(0, 9)) else draw(st.integers(1, 4))
            index = huge if draw(st.integers(0, 29)) == 0 else st.integers(0, 2)
            words = [str(draw(index)) for _ in range(width - 1)] + [draw(nodepy_values).replace(" ", "")]
            if draw(st.integers(0, 19)) == 0:
                words[0] = draw(st.sampled_from(["-1", "x", "1.5", "\u0661", "+2", "\u00b2"]))
            lines.append(" ".join(words))
    name = draw(st.sampled_from(["m.txt", "m.nodepy"]))
    return Case(["verify", name, "--order", "3"], {name: "\n".join(lines).encode("utf-8", "surrogateescape")})


csv_cells = (st.sampled_from(["0", "1/2", "1", "0.5", "1/3", "2/3", "1/4", "\"1/2\"", "\"0.5\"", " 1 ", "sqrt(3)/6"])
             | st.sampled_from(["", "\"1,5\"", "\"\"", "\"a\"\"b\"", "\"", "1e200"]) | entry_texts)


@st.composite
def csv_cases(draw) -> Case:
    n = draw(st.integers(2, 5))  # rows: s + 1 of a Butcher array, s of the GeometricIntegrators layout
    width = draw(st.sampled_from([n, n, n + 2, n + 1]))
    sep = draw(st.sampled_from([",", ";", "\t", " "]))
    def cell():  # a separator inside a cell is quoted, as a spreadsheet does it
        text = draw(csv_cells).replace("\n", "")
        return f'"{text}"' if sep in text and not text.startswith('"') and draw(st.integers(0, 3)) else text

    rows = [sep.join(cell() for _ in range(width)) for _ in range(n)]
    if draw(st.booleans()):
        rows.insert(0, "# order stages type")
    text = "\n".join(rows) + draw(st.sampled_from(["", "\n", "\r\n"]))
    data = text.encode("utf-8", "surrogateescape")
    if draw(st.booleans()):
        data = b"\xef\xbb\xbf" + data
    name = draw(st.sampled_from(["m.csv", "m.tsv"]))
    return Case(["verify", name, "--order", "3"], {name: data})


importer_cases = nodepy_cases() | csv_cases()

#: every family, by the name benchmarks/fuzz.py reports
FAMILIES = {"entries": entry_cases(), "files": file_cases, "options": option_cases(), "importers": importer_cases}
