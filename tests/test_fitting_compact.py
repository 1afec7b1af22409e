"""fitting.calibration.compact: the fewest-term series. Synthetic spectra whose answer is known: a series
of few terms is found again, the count stops where the accuracy on noisy points of a smooth
spectrum is held, and relaxation times stay inside the window. Expected values come from the
synthetic spectra, not from the code."""
import numpy as np
import pytest

from fitting.calibration import compact
from fitting.shared.evaluate import errors_at, loss_extrema


TRUE = compact.Series(1e6, np.array([4e8, 1e8, 3e7, 5e6]), np.array([1e-5, 1e-3, 1e-1, 10.0]))
WINDOW = (1e-4, 1e6)          # rad/s: times 1e-6 .. 1e4 s


def test_fit_terms_finds_a_few_term_series_again():
    s = compact.fit_terms(TRUE, 4, WINDOW)
    d = compact.deviation(s, TRUE, WINDOW)
    assert d["storage_max"] < 1e-3 and d["loss_max"] < 1e-3, d
    np.testing.assert_allclose(np.sort(s.times), TRUE.times, rtol=0.02)
    # fewer terms than the truth cannot match it
    assert compact.deviation(compact.fit_terms(TRUE, 2, WINDOW), TRUE, WINDOW)["loss_median"] > 0.05


def test_choose_stops_at_the_accuracy_and_keeps_times_in_the_window():
    """A smooth spectrum (a Gaussian in log tau, 3 times a decade over 15 decades) and noisy
    'DMA points' of it over 9 decades: a handful of terms holds its accuracy on the points."""
    tau = 10.0 ** np.arange(-7.5, 7.51, 1.0 / 3)
    full = compact.Series(1e6, 5e7 * np.exp(-0.5 * (np.log10(tau) + 1.0) ** 2), tau)
    rng = np.random.default_rng(3)
    w = np.logspace(-3.5, 5.5, 90)
    z = w[:, None] * tau
    st = (full.E0 + (z * z / (1 + z * z)) @ full.moduli) * 10 ** rng.normal(0, 0.01, len(w))
    lo = ((z / (1 + z * z)) @ full.moduli) * 10 ** rng.normal(0, 0.01, len(w))
    window = (w.min(), w.max())
    ref = errors_at(full, w, st, lo)
    c = compact.choose(full, window, errors_of=lambda s: errors_at(s, w, st, lo), target=(w, st, lo))
    n = len(c.series.times)
    assert c.met and n <= 12, (n, c.tried)
    for k in ("storage_median", "loss_median"):
        assert c.errors[k] <= 1.5 * ref[k]
        assert abs(c.errors[k] - errors_at(c.series, w, st, lo)[k]) < 1e-15
    assert c.extrema == loss_extrema(c.series, *window)
    # smooth within the scatter: the scatter is the full fit's median loss error on the points
    assert c.ripple < c.scatter == pytest.approx(ref["loss_median"], rel=1e-12)
    t = c.series.times
    assert t.min() >= 10 ** -compact.MARGIN_DECADES / w.max() and t.max() <= 10 ** compact.MARGIN_DECADES / w.min()
    # the count is the fewest: one term fewer was tried and fails the criterion
    tried = {row[0]: row for row in c.tried}
    assert any(tried[n - 1][1][k] > 1.5 * ref[k] for k in ("storage_median", "loss_median")) or tried[n - 1][2] >= c.scatter


def test_choose_needs_data_or_the_recorded_errors():
    with pytest.raises(ValueError, match="DMA data"):
        compact.choose(TRUE, WINDOW)
    with pytest.raises(ValueError, match="window"):
        compact.fit_terms(TRUE, 3, (1.0, 0.5))
    with pytest.raises(ValueError, match="window"):
        compact.placement(TRUE, (1.0, -2.0), 3)


@pytest.mark.parametrize("h", [0.8, 1.0, 1.5])
def test_ripple_is_that_of_a_sum_of_debye_peaks(h):
    """compact.ripple against a Maxwell sum evaluated here: equal moduli h decades apart (a
    flat spectrum, 121 terms), the loss modulus over one period in the middle: its relative
    half peak-to-peak and its largest log-log slope. Known values: 5.5 % at 1 decade, 23 % at 1.5."""
    tau = 10.0 ** (h * np.arange(-60, 61))
    x = np.linspace(0.0, h, 801)                       # log10 omega over one period
    z = 10.0 ** x[:, None] * tau
    loss = (z / (1 + z * z)).sum(axis=1)
    amp, slope = compact.ripple(h)
    assert abs((loss.max() - loss.min()) / (loss.max() + loss.min()) / amp - 1) < 0.03
    assert abs(np.abs(np.gradient(np.log10(loss), x)).max() / slope - 1) < 0.03
    assert abs(compact.ripple(1.0)[0] - 0.055) < 0.001 and abs(compact.ripple(1.5)[0] - 0.23) < 0.005


def test_placement_is_dense_where_the_loss_is_flat():
    """A Gaussian spectrum (centre tau = 0.1 s, 1.5 decades wide) seen over 16 decades: its
    loss modulus is flat at its peak (omega ~ 10 rad/s) and falls with slope near 1 far from
    it, so the placed times are closer together at the peak than out there."""
    tau = 10.0 ** np.arange(-9.0, 7.01, 1.0 / 3)
    full = compact.Series(1e5, 1e8 * np.exp(-0.5 * ((np.log10(tau) + 1.0) / 1.5) ** 2), tau)
    t = compact.placement(full, (1e-6, 1e10), 20)
    assert len(t) == 20 and np.all(np.diff(t) > 0)
    assert t.min() >= 10 ** -0.5 / 1e10 and t.max() <= 10 ** 0.5 / 1e-6
    gap = lambda at: np.diff(np.log10(t))[np.argmin(np.abs(np.log10(t[1:]) - at))]  # noqa: E731
    assert gap(-1.0) < 0.6 * gap(-8.0) and gap(-1.0) < 0.6 * gap(4.5)


def test_choose_gives_a_smooth_series_where_few_free_terms_ripple():
    """A nearly flat loss over 20 decades (a power-law spectrum, moduli ~ tau^-0.1, 3 times a
    decade: log-log loss slope 0.1, no extrema) and noisy points of it (1 % scatter): the
    default count is smooth within the scatter (no loss extremum with a prominence above the
    full fit's median loss error, counted here with scipy) and accurate, with times inside
    the window; a cap of 8 terms (2.5 decades apart: a 60 % ripple) cannot be smooth, and says
    so."""
    from scipy.signal import find_peaks
    tau = 10.0 ** np.arange(-11.0, 11.01, 1.0 / 3)
    full = compact.Series(1e5, 1e6 * tau ** -0.1, tau)
    rng = np.random.default_rng(5)
    w = np.logspace(-9, 9, 180)
    z = w[:, None] * tau
    st = (full.E0 + (z * z / (1 + z * z)) @ full.moduli) * 10 ** rng.normal(0, 0.01, len(w))
    lo = ((z / (1 + z * z)) @ full.moduli) * 10 ** rng.normal(0, 0.01, len(w))
    window, ref = (w.min(), w.max()), errors_at(full, w, st, lo)
    errors_of = lambda s: errors_at(s, w, st, lo)  # noqa: E731
    c = compact.choose(full, window, errors_of=errors_of, target=(w, st, lo))
    x = np.logspace(-9, 9, 5000)
    zc = x[:, None] * c.series.times
    loss = (zc / (1 + zc * zc)) @ c.series.moduli
    y = np.log10(loss)
    turns = sum(len(find_peaks(v, prominence=ref["loss_median"])[0]) for v in (y, -y))
    assert c.met and turns == 0 and len(c.series.times) < len(tau), (turns, len(c.series.times))
    assert all(c.errors[k] <= 1.5 * ref[k] for k in ("storage_median", "loss_median"))
    assert c.series.times.min() >= 10 ** -0.5 / w.max() and c.series.times.max() <= 10 ** 0.5 / w.min()
    capped = compact.choose(full, window, errors_of=errors_of, target=(w, st, lo), max_terms=8)
    assert not capped.met and len(capped.series.times) <= 8 and capped.ripple >= capped.scatter


@pytest.mark.parametrize("h", [1.0, 1.5, 2.0])
def test_ripple_of_a_sparse_sum_is_its_peak_to_trough(h):
    """ripple_of of equal moduli h decades apart against the same spectrum 10 times denser
    (no ripple): the peak-to-trough of log10 E'' over a period, measured here on the sparse
    sum itself (its middle, far from the ends)."""
    sparse = compact.Series(0.0, np.ones(41), 10.0 ** (h * np.arange(-20, 21)))
    dense = compact.Series(0.0, np.full(401, 0.1), 10.0 ** (h * np.arange(-200, 201) / 10))
    x = np.linspace(-3 * h, 3 * h, 3001)
    z = 10.0 ** x[:, None] * sparse.times
    y = np.log10((z / (1 + z * z)).sum(axis=1))
    window = (10.0 ** (-5 * h), 10.0 ** (5 * h))
    assert compact.ripple_of(sparse, dense, window) == pytest.approx(y.max() - y.min(), rel=0.02)
    assert compact.ripple_of(dense, dense, window) == 0.0
