"""Scenes: bodies, a contact or film residual and the solver core composed into a machine
element: the pin in its hole (:mod:`.pin`), the needle roller bearing (:mod:`.roller`), the
journal bearing (:mod:`.journal`; its finite film's temperature field, level 2:
:mod:`.journal.finite.thermal`). Each holds its geometry, its equations and its outputs.
Above them, :mod:`.thermal`: each scene at the effective temperature its own dissipation sets
(level 1), a scene over the scenes."""
