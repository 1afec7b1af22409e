"""Grid and convergence studies and one-off studies behind numbers quoted in the docs: the
finite journal bearing's speed and grid study (``journal_finite``), the sub-cell rupture's
convergence, the 3D layer against finite elements and against plane-strain slices, the DMA fits
and finite-element export against pyvisco, the FEM cards per data set (``fem_cards``), the Prony
ripple of compact series, the torque twin
experiment and the gradient-based design examples. Run each with
``python -m experiments.studies.<module>``; they are not part of the main job.
"""
