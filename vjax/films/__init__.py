"""Films: Reynolds equations (1D and 2D), cavitation, their linear solvers, rough-surface models."""
