"""The journal bearing: one scene, two films.

- :mod:`.long`: the infinitely long bearing of the thesis (Chapter 3), the film on the ring;
- :mod:`.finite`: the finite bearing, the film over the land (theta, z), bodies in slices or
  in 3D, tilt, and its coefficients in position and tilt.

Below both: :mod:`.options` (their static options) and :mod:`.setup` (the argument checks and
the bodies they share). Above both: :func:`journal_bearing` (:mod:`.bearing`) and
:func:`journal_coefficients` (:mod:`.dynamics`), which pick the film from ``length``, and
:func:`stribeck_curve` (:mod:`.stribeck`), a speed sweep of a bearing with rough surfaces.
"""
from .bearing import journal_bearing
from .dynamics import JournalCoefficients, journal_coefficients, lund, stability_threshold
from .finite import FiniteJournalResult, finite_coefficients, tilt_coefficients
from .long import JournalResult
from .options import FiniteJournalOptions, JournalOptions
from .stribeck import StribeckCurve, stribeck_curve

__all__ = ["FiniteJournalOptions", "FiniteJournalResult", "JournalCoefficients", "JournalOptions", "JournalResult",
           "finite_coefficients", "journal_bearing", "journal_coefficients", "lund", "stability_threshold",
           "tilt_coefficients", "StribeckCurve", "stribeck_curve"]
