"""fitting.compact: the fewest-term series. Synthetic spectra whose answer is known: a series
of few terms is found again, the count stops where the accuracy on noisy points of a smooth
spectrum is held, and relaxation times stay inside the window. Expected values come from the
synthetic spectra, not from the code."""
import numpy as np
import pytest

from fitting import compact
from fitting.evaluate import errors_at, loss_extrema


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
    assert c.extrema == loss_extrema(c.series, *window) <= 3
    t = c.series.times
    assert t.min() >= 10 ** -compact.MARGIN_DECADES / w.max() and t.max() <= 10 ** compact.MARGIN_DECADES / w.min()
    # the count is the fewest: one term fewer was tried and fails the criterion
    tried = {row[0]: row for row in c.tried}
    assert any(tried[n - 1][1][k] > 1.5 * ref[k] for k in ("storage_median", "loss_median")) or tried[n - 1][2] > 3


def test_choose_needs_data_or_the_recorded_errors():
    with pytest.raises(ValueError, match="DMA data"):
        compact.choose(TRUE, WINDOW)
    with pytest.raises(ValueError, match="window"):
        compact.fit_terms(TRUE, 3, (1.0, 0.5))
