"""The main job's stages: each module here draws one stage of ``python -m experiments.main``
(foundation, pin, roller, journal, bodies, dynamics, bores) and returns its checks, figures and
text as an :class:`experiments._common.StageReport`; ``persson`` holds the pin's comparison with
the analytical solution that the pin stage and the benchmarks share, ``journal_finite_plot``
the journal stage's finite-length figure, and ``layout`` the rules every saved figure passes
(:func:`experiments._common.save_figure` checks them). Each stage also runs alone,
``python -m experiments.figures.<module> [out_dir] [--quick]``, writing PNG and CSV files under
``out_dir`` (default ``experiments/out``).
"""
