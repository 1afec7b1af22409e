"""The FEM cards' term counts per data set (docs/fem_export.md, "Default cards on the data").

For each shipped data set (and the polystyrene melt of tests/data), fitted with WLF (nu 0.45):
the default compact series (:func:`fitting.fem.export.prepare`): its count, the data's scatter about
the full fit (median |log10(E''_fit/E''_measured)|), its loss-modulus ripple
(:func:`fitting.calibration.compact.ripple_of`) and its accuracy against the full fit's; whether LS-DYNA's six
cards hold the data's window, else the widest window they do hold (the refusal's message); and
``--window`` set to that window: the compact count and accuracy there, and LS-DYNA's deviation.

    python -m experiments.studies.fem_cards [out_dir]

Writes ``<out_dir>/fem_cards.md`` (the table) and prints it.
"""
import os
import sys
import time

import jax

jax.config.update("jax_enable_x64", True)

from fitting.measurements import dma  # noqa: E402
from fitting.fem import export
from fitting.calibration.pipeline import calibrate  # noqa: E402
from fitting.fem.export import CARD_LIMIT  # noqa: E402

HERE = os.path.dirname(dma.default_data("pyvisco"))
ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
DATASETS = [("pyvisco Eplexor raw (.xls)", [os.path.join(HERE, "freq_Eplexor_raw.xls")], 25.0),
            ("pyvisco relaxation E(t)", [os.path.join(HERE, "time_user_raw.csv")], 25.0),
            ("dmasuite E 0-105 C", [dma.default_data("dmasuite")], 70.0),
            ("polystyrene melt (tests/data)", [os.path.join(ROOT, "tests", "data", "ps_melt", "ps_melt.csv")], 160.0)]
NU = 0.45


def _acc(note):
    """The accuracy clause of a card's note."""
    return note[note.index("accuracy"):].split("; it ")[0]


def main(out_dir="experiments/out"):
    os.makedirs(out_dir, exist_ok=True)
    rows = []
    for i, (name, paths, T_ref) in enumerate(DATASETS):
        t0 = time.perf_counter()
        mat, shift, rep = calibrate(paths, T_ref, law="WLF", nu=NU)
        path = os.path.join(out_dir, f"fem_cards_{i}.json")
        rep.save(path, mat, shift, "E", files=[os.path.abspath(p) for p in paths])
        m = export.load(path, nu=NU)
        c = export.prepare(m, "compact")
        try:
            export.prepare(m, "full", None, None, CARD_LIMIT["lsdyna"])
            lsdyna, win = "holds the data's window", None
        except ValueError as e:
            msg = str(e)
            win = msg.split("--window ")[1].split(" ")[0] if "--window " in msg else None
            lsdyna = f"refused; widest window held: {win.replace(',', '..')} s" if win else "refused"
        cw = lw = None
        if win:
            window = tuple(float(v) for v in win.split(","))
            cw = export.prepare(m, "compact", window=window)
            lw = export.prepare(m, "full", None, window, CARD_LIMIT["lsdyna"])
        rows.append((name, len(m.G), c, lsdyna, win, cw, lw, m.liquid))
        print(f"[{name}] {time.perf_counter() - t0:.1f} s: {c.note}", flush=True)
    lines = ["# FEM cards per data set (WLF, nu = 0.45; python -m experiments.studies.fem_cards)", "",
             "| data set | full fit | default card | ripple vs scatter (decades) | accuracy of the default card "
             "| LS-DYNA (6 cards) | `--window` = that window: compact card | its accuracy | LS-DYNA there |",
             "|---|---|---|---|---|---|---|---|---|"]
    for name, nf, c, lsdyna, win, cw, lw, liquid in rows:
        rip = c.note.split("ripple ")[1].split(" decades")[0]
        sc = c.note.split("the data's scatter ")[1].split(" decades")[0]
        ls_dev = lw.note.split("deviation from the full fit there: ")[1] if lw else ""
        lines.append(f"| {name}{' (E_inf = 0)' if liquid else ''} | {nf} terms | {len(c.G)} terms | {rip} vs {sc} | "
                     f"{_acc(c.note)} | {lsdyna} | {len(cw.G) if cw else ''} terms | "
                     f"{_acc(cw.note) if cw else ''} | {ls_dev} |")
    text = "\n".join(lines) + "\n"
    with open(os.path.join(out_dir, "fem_cards.md"), "w") as fh:
        fh.write(text)
    print(text)


if __name__ == "__main__":
    main(*sys.argv[1:])
