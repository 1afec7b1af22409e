"""The example notebooks are stored executed, and their stored outputs are current.

notebooks/_make.py writes them from its cell sources and, with ``--execute``, runs each in a
fresh Jupyter kernel and stores its outputs (figures as PNG), so the repository page shows
every figure. Here: the stored cells are the generator's; each notebook, re-executed as stored
(the full notebook, under a minute on two cores), prints the stored text (numbers to a relative
1e-3, timings and memory addresses stripped; stderr, where library warnings go, is not
compared), and shows a figure in each cell where the stored notebook has one, and no more.
Otherwise the test fails and says how to regenerate.
"""
import base64
import importlib.util
import os
import re
from pathlib import Path

import pytest

nbformat = pytest.importorskip("nbformat")
pytest.importorskip("nbclient")
pytest.importorskip("ipykernel")

ROOT = Path(__file__).resolve().parents[1]
NOTEBOOKS = sorted((ROOT / "notebooks").glob("*.ipynb"))
RTOL, ATOL = 1e-3, 1e-9   # ATOL: below it a printed number is round-off (residuals, -0)

_spec = importlib.util.spec_from_file_location("nbmake", ROOT / "notebooks" / "_make.py")
nbmake = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(nbmake)

_NUMBER = re.compile(r"[-+]?(?:\d+\.\d*|\.\d+|\d+)(?:[eE][-+]?\d+)?")
_TIMING = re.compile(r"(?i)\b(time|elapsed|took|in)\s+[-+.\deE]+\s*(?:ms|s)\b")
_ADDRESS = re.compile(r"\b0x[0-9a-fA-F]+")


def regenerate(name):
    return (f"Regenerate with `python notebooks/_make.py --execute {Path(name).stem}` (about a minute; "
            f"all notebooks: `python notebooks/_make.py --execute`), then commit notebooks/{Path(name).name}.")


def cell_text(cell):
    """What a code cell shows as text: its stdout and the text/plain of its results and
    displays, with timings and memory addresses stripped."""
    parts = []
    for o in cell.get("outputs", []):
        if o["output_type"] == "stream" and o["name"] == "stdout":
            parts.append(o["text"])
        elif o["output_type"] in ("execute_result", "display_data"):
            parts.append(str(o["data"].get("text/plain", "")) + "\n")
        elif o["output_type"] == "error":
            parts.append(f"ERROR {o['ename']}: {o['evalue']}\n")
    text = _ADDRESS.sub("0x?", "".join(parts))
    return _TIMING.sub(r"\1 <time>", text)


def figures(cell):
    """The PNG images a code cell shows, decoded."""
    return [base64.b64decode(o["data"]["image/png"]) for o in cell.get("outputs", [])
            if o["output_type"] in ("display_data", "execute_result") and "image/png" in o["data"]]


def same_text(a, b):
    """True if `a` and `b` differ only in numbers within RTOL (or both below ATOL)."""
    if _NUMBER.sub("#", a) != _NUMBER.sub("#", b):
        return False
    for x, y in zip(_NUMBER.findall(a), _NUMBER.findall(b)):
        x, y = float(x), float(y)
        if abs(x - y) > RTOL * max(abs(x), abs(y)) + ATOL:
            return False
    return True


def differences(stored, fresh):
    """Human-readable list of how `fresh` (just executed) differs from `stored`, per code cell."""
    out = []
    code_s = [c for c in stored.cells if c.cell_type == "code"]
    code_f = [c for c in fresh.cells if c.cell_type == "code"]
    if len(code_s) != len(code_f):
        return [f"{len(code_s)} code cells stored, {len(code_f)} executed"]
    for k, (s, f) in enumerate(zip(code_s, code_f)):
        where = f"code cell {k} ({s.get('id', '?')})"
        ts, tf = cell_text(s), cell_text(f)
        if not same_text(ts, tf):
            out.append(f"{where}: text differs\n--- stored:\n{ts[-1500:]}\n--- now:\n{tf[-1500:]}")
        ns, nf = len(figures(s)), len(figures(f))
        if ns != nf:
            out.append(f"{where}: {ns} figures stored, {nf} now")
    return out


def test_comparison_can_fail():
    # the checks above on hand-made outputs: a 1 % change, a lost figure and a changed word
    # are differences; round-off, timings and addresses are not
    def nb(text, n_fig=1):
        outs = [nbformat.v4.new_output("stream", name="stdout", text=text)]
        outs += [nbformat.v4.new_output("display_data", data={"image/png": "iVBORw0KGgo=",
                                                              "text/plain": "<Figure size 640x480 with 1 Axes>"})] * n_fig
        cell = nbformat.v4.new_code_cell("x", outputs=outs)
        return nbformat.v4.new_notebook(cells=[cell])
    ref = nb("torque 0.0031059 N m/m, residual 4.9e-13\ntime            7.43 s\n<f at 0x7f3a2c>\n")
    assert differences(ref, nb("torque 0.0031059001 N m/m, residual 3.1e-12\ntime  12.1 s\n<f at 0x55aa>\n")) == []
    assert differences(ref, nb("torque 0.0031370 N m/m, residual 4.9e-13\ntime 7.43 s\n<f at 0x7f3a2c>\n"))
    assert differences(ref, nb("torque 0.0031059 N m, residual 4.9e-13\ntime 7.43 s\n<f at 0x7f3a2c>\n"))
    assert differences(ref, nb("torque 0.0031059 N m/m, residual 4.9e-13\ntime 7.43 s\n<f at 0x7f3a2c>\n",
                               n_fig=0))


def test_notebooks_match_generator():
    # the notebooks are generated by notebooks/_make.py: every cell's kind and source as there
    assert [p.name for p in NOTEBOOKS] == sorted(nbmake.NOTEBOOKS)
    for path in NOTEBOOKS:
        stored = nbformat.read(path, as_version=4)
        made = nbmake.notebook(nbmake.NOTEBOOKS[path.name])
        assert [(c.cell_type, c.source) for c in stored.cells] == \
               [(c.cell_type, c.source) for c in made.cells], f"{path.name} is not the generator's. " \
                                                               + regenerate(path.name)


@pytest.mark.parametrize("path", NOTEBOOKS, ids=lambda p: p.stem)
def test_stored_outputs_are_current(path, tmp_path):
    stored = nbformat.read(path, as_version=4)
    code = [c for c in stored.cells if c.cell_type == "code"]
    assert all(c.execution_count is not None for c in code), \
        f"{path.name} is stored without (some of) its outputs. " + regenerate(path.name)
    stored_figures = [img for c in code for img in figures(c)]
    assert stored_figures, f"{path.name} stores no figure. " + regenerate(path.name)
    assert all(img.startswith(b"\x89PNG\r\n\x1a\n") for img in stored_figures), path.name

    env = {}
    if os.environ.get("VJAX_TEST_XLA_CACHE"):
        # the suite's XLA cache (conftest.py), through JAX's environment variables: the
        # notebooks solve some of the tests' scenes (the thesis roller and journal)
        env.update(JAX_COMPILATION_CACHE_DIR=os.environ["VJAX_TEST_XLA_CACHE"],
                   JAX_PERSISTENT_CACHE_MIN_COMPILE_TIME_SECS="0.2")
    fresh = nbmake.execute(nbmake.notebook(nbmake.NOTEBOOKS[path.name]), tmp_path, env=env)
    diff = differences(stored, fresh)
    assert not diff, f"{path.name}: the stored outputs are not what the notebook gives now. " \
                     + regenerate(path.name) + "\n\n" + "\n\n".join(diff[:4])
