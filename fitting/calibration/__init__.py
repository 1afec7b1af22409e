"""A material from DMA data: shift factors and laws (:mod:`.master`), Prony series with free
times (:mod:`.prony`) or on a fixed grid with a smoothness penalty (:mod:`.spectrum`), the fewest-term series
for FEM codes (:mod:`.compact`), the material JSON file (:mod:`.io`), the whole chain (:mod:`.pipeline`, ``fitting.calibrate``)
and its figures (:mod:`.plots`; :mod:`.figures` draws them in parallel, from the fork server
:mod:`.figure_server` preloads)."""
