"""The solver core, private to vjax: the solution record and result codes, one damped Newton,
continuation and homotopy, the implicit-derivative helper and the one failure path
(:mod:`.solve`); the scalar root searched upwards for its bracket (:mod:`.root`); GMRES
(:mod:`.krylov`); the XLA options of the largest programs (:mod:`.xla`); argument checks
(:mod:`.checks`, also public as ``vjax.checks``); the scenes' result contract (:mod:`.scene`).
It imports nothing else of vjax."""
