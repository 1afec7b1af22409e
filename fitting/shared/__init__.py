"""What the rooms share: atomic writes (:mod:`.files`), a material's formulas in numpy (errors,
loss-modulus extrema, G/E: :mod:`.evaluate`), the least-squares drivers (:mod:`.optim`) and
the tools' compilation cache (:mod:`.jax_cache`)."""
