"""Whether a drawn matplotlib figure reads at a glance: the layout rules every saved figure
of the experiments passes (:func:`experiments._common.save_figure` raises on a breach).

Rules, each on the figure as saved (its last draw: after the layout engine, or cropped by
``bbox_inches="tight"``), for every visible non-empty text (titles, suptitle, axis labels,
drawn tick labels, offset texts, legend texts, annotations) and every visible legend box:

1. **clipped**: its window extent reaches more than :data:`SLACK_PX` outside the canvas;
2. **overlap**: two texts (or a legend box and a text not in it) overlap by more than
   :data:`SLACK_PX` in both directions: neighbouring tick labels, a title on tick labels,
   a label on a neighbouring panel's ticks;
3. **covered**: a text or legend lies on the plotting area of another axes than its own
   (its twins and insets are its own): it hides that panel or that panel hides it;
4. **legend without a drawing**: a legend names a label whose artists (those of the figure
   carrying that label) are all invisible, empty, non-finite or outside their axes' view.
   Proxy handles drawn nowhere (a legend of line styles) carry labels no drawn artist has
   and are not questioned;
5. **fractional ticks of whole numbers**: a linear axis whose data (lines and scatter points
   in data coordinates, at least three points) are all whole numbers, but which
   has a labelled tick between them (a roller count with a tick at 3.25);
6. **small text**: a text smaller than :data:`MIN_TEXT_PX` pixels when the image is shown
   at most :data:`PAGE_WIDTH_PX` wide (a markdown page): a very wide figure with tiny text.

What no rule sees (the figure module's business): colours that code something without a
legend, a legend covering data, a poor choice of scale.
"""
from __future__ import annotations

import io

import numpy as np
from matplotlib.axes import Axes
from matplotlib.axis import Axis
from matplotlib.collections import Collection, PathCollection
from matplotlib.container import Container
from matplotlib.legend import Legend
from matplotlib.lines import Line2D
from matplotlib.patches import Patch
from matplotlib.text import Text

__all__ = ["LayoutError", "problems", "render", "SLACK_PX", "MIN_TEXT_PX", "PAGE_WIDTH_PX"]

SLACK_PX = 1.0          # overlaps and overhangs up to this are antialiasing, not a collision
PAGE_WIDTH_PX = 1000    # a figure is read at most this wide (a markdown page: GitHub shows ~980 px)
MIN_TEXT_PX = 7.0       # smallest legible font size there (em height, pixels)


class LayoutError(ValueError):
    """A saved figure breaks :mod:`layout`'s rules: ``path`` and the list ``problems``."""

    def __init__(self, path, found):
        self.path, self.problems = str(path), list(found)
        lines = "\n".join(f"  - {p}" for p in self.problems)
        super().__init__(f"figure {self.path} does not read at a glance ({len(self.problems)} "
                         f"problem{'s' * (len(self.problems) > 1)}; experiments/figures/layout.py):\n{lines}")


def render(fig, format="png", dpi=150, **savefig_kw):
    """Save ``fig`` into memory; returns ``(bytes, problems)``, :func:`problems` of the figure
    as saved (checked in its last draw, where the saved layout and renderer are in force)."""
    found = []

    def check(event):
        found[:] = problems(fig, event.renderer)

    cid = fig.canvas.mpl_connect("draw_event", check)
    try:
        buf = io.BytesIO()
        fig.savefig(buf, format=format, dpi=dpi, **savefig_kw)
    finally:
        fig.canvas.mpl_disconnect(cid)
    return buf.getvalue(), found


def problems(fig, renderer=None) -> list:
    """Every breach of the module's rules in ``fig`` as drawn with ``renderer`` (default: draw
    it on its canvas now), one sentence each."""
    if renderer is None:
        fig.canvas.draw()
        renderer = fig.canvas.get_renderer()
    texts, legends = [], []
    _collect(fig, None, texts, legends)
    boxes = [(name, t.get_window_extent(renderer), owner, ax) for name, t, owner, ax in texts]
    boxes += [(f"legend box{_of(ax)}", leg.get_window_extent(renderer), leg, ax) for leg, ax in legends]
    found = _clipped(boxes, fig.bbox) + _overlaps(boxes) + _covered(boxes, fig)
    found += [p for leg, _ in legends for p in _undrawn(fig, leg)]
    found += [p for ax in fig.axes for p in _fractional_ticks(ax)]
    found += _small(texts, fig, renderer)
    return found


def _axes_name(ax):
    title = next((ax.get_title(loc) for loc in ("center", "left", "right") if ax.get_title(loc)), "")
    label = title or ax.get_ylabel() or ax.get_xlabel()
    return f"axes {ax.figure.axes.index(ax) + 1}" + (f" ({_short(label)!r})" if label else "")


def _short(s, n=40):
    s = " ".join(s.split())
    return s if len(s) <= n else s[: n - 3] + "..."


def _shown(t):
    return t.get_visible() and t.get_text().strip() != "" and t.get_alpha() != 0


def _drawn_ticks(axis):
    """The ticks an axis draws: those at its locator's locations inside its view interval."""
    low, high = sorted(axis.get_view_interval())
    lo, hi = sorted(axis.get_transform().transform([low, high]))
    eps = 1e-9 * max(abs(hi - lo), 1e-300)
    out = []
    for tick in [*axis.get_major_ticks(), *axis.get_minor_ticks()]:
        loc = axis.get_transform().transform(tick.get_loc())
        if np.isfinite(loc) and lo - eps <= loc <= hi + eps:
            out.append(tick)
    return out


def _of(ax):
    return f" of {_axes_name(ax)}" if ax is not None else ""


def _collect(artist, ax, texts, legends):
    """Append ``(name, Text, owner, axes)`` for every shown text under ``artist`` (owner: the
    legend a text belongs to, else the text; axes: the Axes it belongs to, None for the
    figure's) and ``(Legend, axes)`` for every visible legend."""
    for child in artist.get_children():
        if not child.get_visible():
            continue
        if isinstance(child, Axes):
            _collect(child, child, texts, legends)
        elif isinstance(child, Axis):
            if not ax.axison:      # ax.axis("off"): no axis is drawn
                continue
            xy = child.axis_name
            for tick in _drawn_ticks(child):
                for label in (tick.label1, tick.label2):
                    if _shown(label):
                        texts.append((f"{xy} tick label {label.get_text()!r}{_of(ax)}", label, label, ax))
            for t, kind in ((child.label, "axis label"), (child.offsetText, "offset text")):
                if _shown(t):
                    texts.append((f"{xy} {kind} {_short(t.get_text())!r}{_of(ax)}", t, t, ax))
        elif isinstance(child, Legend):
            legends.append((child, ax))
            for t in [*child.get_texts(), child.get_title()]:
                if _shown(t):
                    texts.append((f"legend text {_short(t.get_text())!r}{_of(ax)}", t, child, ax))
        elif isinstance(child, Text):
            if _shown(child):
                kind = "figure text" if ax is None else "text" if child in ax.texts else "title"
                texts.append((f"{kind} {_short(child.get_text())!r}{_of(ax)}", child, child, ax))
        else:
            _collect(child, ax, texts, legends)


def _clipped(boxes, canvas):
    out = []
    for name, b, _, _ in boxes:
        over = max(canvas.x0 - b.x0, b.x1 - canvas.x1, canvas.y0 - b.y0, b.y1 - canvas.y1)
        if over > SLACK_PX:
            out.append(f"clipped: {name} reaches {over:.0f} px outside the canvas")
    return out


def _overlaps(boxes):
    if len(boxes) < 2:
        return []
    e = np.array([[b.x0, b.y0, b.x1, b.y1] for _, b, _, _ in boxes])
    dx = np.minimum(e[:, None, 2], e[None, :, 2]) - np.maximum(e[:, None, 0], e[None, :, 0])
    dy = np.minimum(e[:, None, 3], e[None, :, 3]) - np.maximum(e[:, None, 1], e[None, :, 1])
    owners = [id(o) for _, _, o, _ in boxes]
    out = []
    for i, j in zip(*np.nonzero(np.triu((dx > SLACK_PX) & (dy > SLACK_PX), 1))):
        if owners[i] != owners[j]:     # a legend's own texts lie in its box
            out.append(f"overlap: {boxes[i][0]} and {boxes[j][0]} ({dx[i, j]:.0f} x {dy[i, j]:.0f} px)")
    return out


def _covered(boxes, fig):
    """Texts and legends lying on another axes' plotting area (they hide it or it hides them);
    an axes' twins (same area) and insets are its own."""
    areas = [(ax, ax.get_window_extent()) for ax in fig.axes if ax.get_visible()]
    out = []
    for name, b, _, mine in boxes:
        for ax, area in areas:
            if ax is mine or (mine is not None and (area.bounds == mine.bbox.bounds or ax in mine.child_axes
                                                    or mine in ax.child_axes)):
                continue
            dx, dy = min(b.x1, area.x1) - max(b.x0, area.x0), min(b.y1, area.y1) - max(b.y0, area.y0)
            if dx > SLACK_PX and dy > SLACK_PX:
                out.append(f"covered: {name} lies on the plotting area of {_axes_name(ax)} ({dx:.0f} x {dy:.0f} px)")
    return out


def _points(artist):
    """Display coordinates of what ``artist`` draws (None: not a kind this module reads)."""
    if isinstance(artist, Line2D):
        return artist.get_transform().transform(np.asarray(artist.get_xydata(), float).reshape(-1, 2))
    if isinstance(artist, PathCollection):      # scatter: markers at the offsets
        return artist.get_offset_transform().transform(np.asarray(artist.get_offsets(), float).reshape(-1, 2))
    if isinstance(artist, Collection):          # fill_between, line collections, meshes
        vertices = [p.vertices for p in artist.get_paths() if len(p.vertices)]
        return artist.get_transform().transform(np.concatenate(vertices) if vertices else np.zeros((0, 2)))
    if isinstance(artist, Patch):
        return artist.get_transform().transform(artist.get_path().vertices)
    return None


def _drawn(artist):
    """Whether ``artist`` leaves a mark: visible, with a finite point inside its axes."""
    if isinstance(artist, Container):
        return any(_drawn(a) for a in artist.get_children() if a is not None)
    if not artist.get_visible() or artist.get_alpha() == 0:
        return False
    ax = artist.axes
    pts = _points(artist)
    if pts is None or ax is None:
        return True
    pts = pts[np.all(np.isfinite(pts), axis=1)]
    box = ax.bbox
    inside = ((pts[:, 0] >= box.x0 - SLACK_PX) & (pts[:, 0] <= box.x1 + SLACK_PX)
              & (pts[:, 1] >= box.y0 - SLACK_PX) & (pts[:, 1] <= box.y1 + SLACK_PX))
    return bool(inside.any())


def _undrawn(fig, legend):
    labelled = {}
    for ax in fig.axes:
        for handle, label in zip(*ax.get_legend_handles_labels()):
            labelled.setdefault(label, []).append(handle)
    out = []
    for t in legend.get_texts():
        handles = labelled.get(t.get_text())
        if _shown(t) and handles and not any(_drawn(h) for h in handles):
            out.append(f"legend without a drawing: {t.get_text()!r} names no visible point of the figure")
    return out


def _fractional_ticks(ax):
    out = []
    for axis, column in ((ax.xaxis, 0), (ax.yaxis, 1)):
        if axis.get_scale() != "linear" or not ax.axison:
            continue
        values = []
        for artist in [*ax.lines, *ax.collections]:
            if not artist.get_visible():
                continue
            if isinstance(artist, Line2D):
                xy, transform = artist.get_xydata(), artist.get_transform()
            elif isinstance(artist, PathCollection):
                xy, transform = artist.get_offsets(), artist.get_offset_transform()
            else:
                continue
            if transform.contains_branch_seperately(ax.transData)[column]:
                values.append(np.asarray(xy, float).reshape(-1, 2)[:, column])
        v = np.concatenate(values) if values else np.zeros(0)
        v = v[np.isfinite(v)]
        if len(v) < 3 or np.any(np.abs(v - np.round(v)) > 1e-9 * np.maximum(1.0, np.abs(v))):
            continue
        fractional = [t.label1.get_text() for t in _drawn_ticks(axis)
                      if _shown(t.label1) and abs(t.get_loc() - round(t.get_loc())) > 1e-9]
        if fractional:
            out.append(f"fractional ticks of whole numbers: the {axis.axis_name} data of {_axes_name(ax)} are whole "
                       f"numbers, ticks at {', '.join(fractional)} (matplotlib.ticker.MaxNLocator(integer=True))")
    return out


def _small(texts, fig, renderer):
    scale = min(1.0, PAGE_WIDTH_PX / fig.bbox.width)
    found = {}
    for name, t, _, _ in texts:
        px = t.get_fontsize() * renderer.points_to_pixels(1.0) * scale
        if px < MIN_TEXT_PX:
            found.setdefault(round(t.get_fontsize(), 1), (name, px))
    width_in = fig.bbox.width / renderer.points_to_pixels(72.0)
    return [f"small text: {name} is {px:.1f} px high on a {PAGE_WIDTH_PX} px page ({size:g} pt on a figure "
            f"{width_in:.1f} in wide; at least {MIN_TEXT_PX:g} px)" for size, (name, px) in found.items()]
