"""The figure layout checker (experiments/figures/layout.py): small figures built to break one
rule each must be reported for that rule (and only it), a tidy figure passes, and
experiments._common.save_figure refuses a bad figure with its path and problems."""
import matplotlib

matplotlib.use("Agg")

import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import pytest  # noqa: E402
from matplotlib.ticker import MaxNLocator  # noqa: E402

from experiments import _common  # noqa: E402
from experiments.figures import layout  # noqa: E402


def _problems(fig, **savefig_kw):
    try:
        return layout.render(fig, dpi=100, **savefig_kw)[1]
    finally:
        plt.close(fig)


def _tidy():
    fig, ax = plt.subplots(figsize=(5, 3.5), layout="constrained")
    x = np.linspace(0.0, 2.0, 50)
    ax.plot(x, np.sin(x), label="sin")
    ax.plot(x, np.cos(x), "--", label="cos")
    ax.set(title="two curves", xlabel="x (rad)", ylabel="value (-)")
    ax.legend()
    return fig, ax


def _rules(found):
    return sorted({p.split(":")[0] for p in found})


def test_a_tidy_figure_passes_constrained_and_cropped():
    assert _problems(_tidy()[0]) == []
    fig, ax = plt.subplots(figsize=(5, 3.5))
    ax.plot([0, 1], [0, 1], label="line")
    ax.set_title("a title wider than this small axes, saved cropped " * 2)   # the crop keeps it
    ax.legend()
    assert _problems(fig, bbox_inches="tight") == []


def test_a_title_wider_than_the_canvas_is_clipped():
    fig, ax = _tidy()
    ax.set_title("a title far too long for a figure five inches wide, running off both of its sides")
    found = _problems(fig)
    assert _rules(found) == ["clipped"] and len(found) == 1, found
    assert found[0].startswith("clipped: title")
    assert "title 'a title far too long" in found[0] and "of axes 1" in found[0]


def test_a_legend_outside_the_canvas_is_clipped():
    fig, ax = plt.subplots(figsize=(4, 3))       # fixed margins, saved uncropped
    ax.plot([0, 1], [0, 1], label="a line with a long name")
    ax.legend(loc="upper left", bbox_to_anchor=(1.0, 1.0))
    found = _problems(fig)
    assert _rules(found) == ["clipped"] and "legend" in found[0], found


def test_crowded_tick_labels_overlap():
    fig, ax = plt.subplots(figsize=(3, 2), layout="constrained")
    ax.plot([0, 1], [0, 1])
    ax.set_xticks(np.linspace(0, 1, 21), [f"{v:.3f}" for v in np.linspace(0, 1, 21)])
    found = _problems(fig)
    assert _rules(found) == ["overlap"], found
    assert all("x tick label" in p.split(" and ")[0] and "x tick label" in p.split(" and ")[1] for p in found)


def test_symlog_labels_crowding_zero_overlap():
    """The dynamics figure's case: symlog ticks at +-1e-3 .. +-1e3 on a small axes."""
    fig, ax = plt.subplots(figsize=(3, 2.5), layout="constrained")
    ax.plot([-1e3, 1e3], [0, 1])
    ax.set_xscale("symlog", linthresh=1e-3)
    assert "overlap" in _rules(_problems(fig))


def test_panels_without_room_between_them_cover_each_others_labels():
    fig, axes = plt.subplots(2, 1, figsize=(4, 3), gridspec_kw=dict(hspace=0.0))
    for ax in axes:
        ax.plot([0, 1], [0, 1])
        ax.set_xlabel("x")
    axes[1].set_title("lower panel")
    found = _problems(fig, bbox_inches="tight")
    assert {"covered", "overlap"} <= set(_rules(found)), found
    assert any(p.startswith("covered: title 'lower panel' of axes 2") and p.split(" area of ")[1].startswith("axes 1")
               for p in found), found
    assert any(p.startswith("covered: x tick label '0.4' of axes 1") for p in found), found
    assert any("y tick label '0.0' of axes 1" in p and "y tick label '1.0' of axes 2" in p for p in found), found


def test_twins_and_colorbars_do_not_cover_their_axes():
    fig, ax = plt.subplots(figsize=(5, 3.5), layout="constrained")
    ax.plot([0, 1], [0, 1], "C0")
    ax.set_ylabel("left (m)", color="C0")
    twin = ax.twinx()
    twin.plot([0, 1], [1, 0], "C1")
    twin.set_ylabel("right (s)", color="C1")
    image = ax.imshow([[0, 1], [1, 0]], extent=(0, 1, 0, 1), aspect="auto")
    fig.colorbar(image, ax=[ax, twin], label="value (-)")
    assert _problems(fig) == []


def test_a_legend_naming_an_undrawn_line_is_reported():
    fig, ax = _tidy()
    ax.plot([], [], "o", label="empty")                 # no data
    ax.plot([np.nan, np.nan], [0, 1], label="nan")      # no finite point
    ax.plot([5.0, 6.0], [0, 1], label="off view")       # outside the view
    ax.set_xlim(0, 2)
    hidden, = ax.plot([0, 1], [0, 1], label="hidden")
    hidden.set_visible(False)
    ax.legend()
    found = _problems(fig)
    assert _rules(found) == ["legend without a drawing"], found
    assert sorted(p.split("'")[1] for p in found) == ["empty", "hidden", "nan", "off view"]


def test_proxy_handles_and_scatter_and_fills_count_as_drawn():
    fig, ax = _tidy()
    ax.scatter([0.5, 1.0], [0.2, 0.4], label="points")
    ax.fill_between([0, 1], [0, 0], [0.1, 0.2], label="band")
    proxy = matplotlib.lines.Line2D([], [], ls=":", color="k", label="dotted: proxy")
    handles, labels = ax.get_legend_handles_labels()
    ax.legend([*handles, proxy], [*labels, "dotted: proxy"])
    assert _problems(fig) == []


def test_fractional_ticks_of_whole_numbers():
    fig, ax = plt.subplots(figsize=(4, 3), layout="constrained")
    ax.plot([3, 4, 5], [1.0, 2.5, 2.0], "o-")
    ax.set(xlabel="loaded rollers", ylabel="load (N)")
    found = _problems(fig)
    assert _rules(found) == ["fractional ticks of whole numbers"] and "the x data" in found[0], found
    fig, ax = plt.subplots(figsize=(4, 3), layout="constrained")
    ax.plot([3, 4, 5], [1.0, 2.5, 2.0], "o-")
    ax.xaxis.set_major_locator(MaxNLocator(integer=True))
    ax.axhline(0.5)          # in axes coordinates along x: not data
    assert _problems(fig) == []
    fig, ax = plt.subplots(figsize=(4, 3), layout="constrained")
    ax.plot([1.0, 10.0, 100.0], [3, 3, 3], "o-")     # the test bearing's count: 3 rollers at every speed
    ax.set_xscale("log")                              # log axes are not questioned
    found = _problems(fig)
    assert _rules(found) == ["fractional ticks of whole numbers"] and "the y data" in found[0], found


def test_tiny_text_on_a_very_wide_figure():
    fig, axes = plt.subplots(1, 5, figsize=(21, 4.2), layout="constrained")
    for ax in axes:
        ax.plot([0, 1], [0, 1])
        ax.set_title("panel")
    found = _problems(fig)
    assert _rules(found) == ["small text"], found


def test_save_figure_writes_the_file_then_raises_with_path_and_problems(tmp_path):
    fig, ax = _tidy()
    ax.set_title("a title far too long for a figure five inches wide, running off both of its sides")
    path = tmp_path / "bad.png"
    with pytest.raises(layout.LayoutError, match=r"bad\.png does not read at a glance .*\n  - clipped: title"):
        _common.save_figure(fig, path)
    assert path.stat().st_size > 1000 and not plt.fignum_exists(fig.number)
    fig, _ = _tidy()
    assert _common.save_figure(fig, tmp_path / "good.png") == tmp_path / "good.png"
