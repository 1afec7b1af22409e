"""The import graphs of vjax and fitting: their layers (rooms), the rules between them, and the
drawings in docs/architecture.md.

    python tools/architecture.py          # check the rules, print the graph (Mermaid)
    python tools/architecture.py --write  # also rewrite the graph's section of docs/architecture.md

Rules (tests/test_architecture.py runs :func:`violations`):

- no import circle between vjax's modules (explicit imports; a package's ``__init__`` counts
  as a module of its own);
- a name beginning with one underscore is used only inside the folder that defines it;
- a folder imports only the folders below it in :data:`LAYERS`;
- every file has at most :data:`MAX_LINES` lines (fitting: but those in :data:`TOO_LONG`);
- fitting uses vjax's public names only: ``vjax`` and its layer packages, no underscore name.
"""
from __future__ import annotations

import ast
import pathlib
import re
import sys

ROOT = pathlib.Path(__file__).resolve().parents[1]
PACKAGE = ROOT / "vjax"
FITTING = ROOT / "fitting"
DOC = ROOT / "docs" / "architecture.md"
MAX_LINES = 500

# Each layer and the layers it may import (the public package vjax/__init__.py may import all).
LAYERS = {
    "_core": set(),
    "materials": {"_core"},
    "bodies": {"_core", "materials"},
    "contact": {"_core", "bodies"},
    "films": {"_core", "materials"},
    "reference": {"_core"},
    "scenes": {"_core", "materials", "bodies", "contact", "films", "reference"},
    "sweep": set(),
}


# fitting's rooms, bottom up, and the rooms each may import (its package __init__ may import all)
FITTING_LAYERS = {
    "shared": set(),
    "measurements": {"shared"},
    "calibration": {"shared", "measurements"},
    "fem": {"shared", "measurements", "calibration"},
    "torque": {"shared", "measurements", "calibration"},
    "bearing": {"shared", "calibration"},
    "cli": {"shared", "measurements", "calibration", "fem", "torque", "bearing"},
}
# files over MAX_LINES that are known and named, each with what is to be done
TOO_LONG = {
    "fitting/fem/export.py": "one file per FEM code, its writer beside its reader (issue 51)",
    "fitting/measurements/dma.py": "the instruments' readers apart from the table (issue 51)",
}


def modules(package: pathlib.Path | None = None) -> dict[str, pathlib.Path]:
    """Dotted module name -> file, for every module of ``package`` (default vjax; a package as
    its ``__init__``)."""
    out = {}
    for path in sorted((package or PACKAGE).rglob("*.py")):
        parts = path.relative_to(ROOT).with_suffix("").parts
        name = ".".join(parts[:-1] if parts[-1] == "__init__" else parts)
        out[name] = path
    return out


def layer(module: str) -> str:
    """The layer of a module: its first folder (or file) under vjax; '' for vjax itself."""
    parts = module.split(".")
    return parts[1] if len(parts) > 1 else ""


def folder(module: str, mods) -> str:
    """The folder a module's file lies in (a package's ``__init__`` in its own)."""
    return str(mods[module].parent.relative_to(ROOT))


def _resolve(module: str, node: ast.ImportFrom, mods) -> str:
    """The absolute name of the package or module ``from ... import`` refers to in ``module``."""
    if node.level == 0:
        return node.module or ""
    is_package = mods[module].name == "__init__.py"
    base = module.split(".")
    base = base if is_package else base[:-1]
    base = base[: len(base) - (node.level - 1)]
    return ".".join(base + ([node.module] if node.module else []))


def imports(module: str, mods):
    """(edges, private uses) of a module: the modules of its own package it imports, and each
    (line, target module, name) where it uses a target's underscore name. A fitting module's
    import of a vjax name that is not public counts as a private use (target "vjax")."""
    tree = ast.parse(mods[module].read_text())
    edges, private, aliases = set(), [], {}
    own = module.split(".")[0]
    for node in ast.walk(tree):
        if isinstance(node, ast.ImportFrom):
            target = _resolve(module, node, mods)
            if own != "vjax" and (target + ".").startswith("vjax."):
                names = target.split(".")[1:] + [a.name for a in node.names]
                if any(n.startswith("_") for n in names) or len(target.split(".")) > 2:
                    private.append((node.lineno, "vjax", target + " import " + ", ".join(a.name for a in node.names)))
            if not (target + ".").startswith(own + "."):
                continue
            for alias in node.names:
                sub = f"{target}.{alias.name}"
                if sub in mods:                       # a module imported from its package
                    edges.add(sub)
                    aliases[alias.asname or alias.name] = sub
                else:
                    edges.add(target)
                    if alias.name.startswith("_") and not alias.name.startswith("__"):
                        private.append((node.lineno, target, alias.name))
        elif isinstance(node, ast.Import):
            for alias in node.names:
                if alias.name.startswith(own) and alias.name in mods:
                    edges.add(alias.name)
    for node in ast.walk(tree):
        if (isinstance(node, ast.Attribute) and isinstance(node.value, ast.Name) and node.value.id in aliases
                and node.attr.startswith("_") and not node.attr.startswith("__")):
            private.append((node.lineno, aliases[node.value.id], node.attr))
    edges.discard(module)
    return edges, private


def graph(package: pathlib.Path | None = None):
    mods = modules(package)
    return mods, {m: imports(m, mods) for m in mods}


def cycles(edges: dict[str, set[str]]) -> list[list[str]]:
    """The strongly connected components of more than one module (Tarjan), or a self-import."""
    index, low, stack, on, out, counter = {}, {}, [], set(), [], [0]

    def visit(v):
        index[v] = low[v] = counter[0]
        counter[0] += 1
        stack.append(v)
        on.add(v)
        for w in edges.get(v, ()):
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            component = []
            while True:
                w = stack.pop()
                on.discard(w)
                component.append(w)
                if w == v:
                    break
            if len(component) > 1:
                out.append(sorted(component))

    sys.setrecursionlimit(10000)
    for v in edges:
        if v not in index:
            visit(v)
    return out


def violations(package: pathlib.Path | None = None) -> list[str]:
    """Every broken rule of ``package`` (default vjax), as a sentence naming the file."""
    mods, found = graph(package)
    layers = FITTING_LAYERS if package == FITTING else LAYERS
    edges = {m: e for m, (e, _) in found.items()}
    out = [f"import circle: {' -> '.join(c)}" for c in cycles(edges)]
    for m, (targets, private) in found.items():
        here = folder(m, mods)
        for line, target, name in private:
            if target == "vjax":
                out.append(f"{mods[m].relative_to(ROOT)}:{line}: imports vjax beyond its public names ({name})")
            elif folder(target, mods) != here:
                out.append(f"{mods[m].relative_to(ROOT)}:{line}: private name {name} of {target} used outside "
                           f"its folder")
        lm = layer(m)
        if lm:
            for t in targets:
                lt = layer(t)
                if lt and lt != lm and lt not in layers.get(lm, set()):
                    out.append(f"{mods[m].relative_to(ROOT)}: layer {lm} imports {t} (layer {lt}), which it may not")
                if not lt:
                    out.append(f"{mods[m].relative_to(ROOT)}: imports the package {t} itself (its __init__)")
        lines = mods[m].read_text().count("\n")
        if lines > MAX_LINES and str(mods[m].relative_to(ROOT)) not in TOO_LONG:
            out.append(f"{mods[m].relative_to(ROOT)}: {lines} lines (at most {MAX_LINES})")
    return out


def mermaid(package: pathlib.Path | None = None) -> str:
    """The layers and the imports between them (module counts on the arrows), as Mermaid."""
    mods, found = graph(package)
    top = (package or PACKAGE).name
    counts: dict[tuple[str, str], int] = {}
    for m, (targets, _) in found.items():
        for t in targets:
            a, b = layer(m) or top, layer(t) or top
            if a != b and a != top:
                counts[(a, b)] = counts.get((a, b), 0) + 1
    lines = ["```mermaid", "flowchart BT"]
    for name in (FITTING_LAYERS if package == FITTING else LAYERS):
        files = sum(1 for m in mods if layer(m) == name)
        lines.append(f'    {name.strip("_") or name}["{name} ({files} files)"]')
    for (a, b), k in sorted(counts.items()):
        lines.append(f"    {a.strip('_')} -->|{k}| {b.strip('_')}")
    lines.append("```")
    return "\n".join(lines)


def tree(package: pathlib.Path | None = None) -> str:
    """Every module and the modules of its package it imports, folder by folder."""
    mods, found = graph(package)
    top = (package or PACKAGE).name + "."
    rows = ["| module | imports |", "|---|---|"]
    for m in sorted(mods):
        targets = ", ".join(sorted(t.removeprefix(top) for t in found[m][0])) or "-"
        rows.append(f"| `{m}` | {targets} |")
    return "\n".join(rows)


BEGIN, END = "<!-- graph: begin (tools/architecture.py --write) -->", "<!-- graph: end -->"
FITTING_BEGIN, FITTING_END = "<!-- fitting graph: begin (tools/architecture.py --write) -->", "<!-- fitting graph: end -->"


def section() -> str:
    return f"{BEGIN}\n{mermaid()}\n\n{tree()}\n{END}"


def fitting_section() -> str:
    return f"{FITTING_BEGIN}\n{mermaid(FITTING)}\n\n{tree(FITTING)}\n{FITTING_END}"


def write_doc():
    text = DOC.read_text()
    for begin, end, body in ((BEGIN, END, section), (FITTING_BEGIN, FITTING_END, fitting_section)):
        text = re.sub(re.escape(begin) + ".*?" + re.escape(end), lambda _: body(), text, flags=re.S)
    DOC.write_text(text)


if __name__ == "__main__":
    problems = violations() + violations(FITTING)
    print(mermaid())
    print(mermaid(FITTING))
    if "--write" in sys.argv:
        write_doc()
        print(f"wrote {DOC.relative_to(ROOT)}")
    for p in problems:
        print("VIOLATION:", p)
    sys.exit(1 if problems else 0)
