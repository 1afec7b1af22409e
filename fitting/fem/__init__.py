"""Cards for FEM codes: Abaqus, ANSYS, LS-DYNA and COMSOL, with their readers (:mod:`.export`;
the fewest-term series a code can take: :mod:`fitting.calibration.compact`)."""
