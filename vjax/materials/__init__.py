"""Material laws: viscoelastic solids (Prony, SLS, creep spectrum), shift laws, lubricants."""
