"""Timings and robustness runs, never part of the main job: first calls and warm calls of every
scene (``bench_*``), error against run time (``work_precision``), stiff and extreme cases
(``stability``), the sharded and multi-process sweeps (``bench_sweep``, ``distributed_sweep``),
and ``calibrate``, a fixed workload whose one printed line goes beside every timing reported so
that timings from different machines can be compared. Run each with
``python -m experiments.benchmarks.<module>``; they write CSV, PNG and Markdown under
``experiments/out`` unless given another folder.
"""
