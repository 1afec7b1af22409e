"""Bodies: the steady-state viscoelastic Green's functions of circular bodies (:mod:`.green`),
the ring operator that applies them in Fourier space (:mod:`.operator`), the bonded layer in
3D elasticity (:mod:`.layer3d`) and its operator on a finite bearing's land (:mod:`.land`),
and :class:`Body` with its constructors (:mod:`.body`)."""
from .body import Body, as_body, check_fits, disc, half_plane, hole, liner, sleeve

__all__ = ["Body", "as_body", "check_fits", "disc", "half_plane", "hole", "liner", "sleeve"]
