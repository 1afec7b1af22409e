"""Scenes: bodies, a contact or film residual and the solver core composed into a machine
element: the pin in its hole (:mod:`.pin`), the needle roller bearing (:mod:`.roller`), the
journal bearing (:mod:`.journal`). Each holds its geometry, its equations and its outputs."""
