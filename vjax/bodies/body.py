"""Bodies: what each ring of a scene is made of and how it is held.

A :class:`Body` pairs a :class:`~vjax.Material` with a geometry whose Green's function gives
its ring operator (:meth:`Body.operator`). Scenes take bodies (or a bare Material, meaning
the thesis's body for that ring, or None for a rigid one).

- :func:`hole`: a hole in an infinite plane (A.45); ``ref_length`` fixes its rigid mode 1.
  With ``axial="3d"``, in a finite journal bearing, a hole through a body as thick as the land.
- :func:`disc`: a solid cylinder fixed at its centre (A.60); ``ref_length`` likewise.
- :func:`half_plane`: the elastic half-plane on the ring's arc length (Chapter 3, Fig. 3.4).
- :func:`liner`: a layer of given thickness loaded on its bore, its outer surface bonded to a
  rigid housing (bushings, lined journal bearings, an outer race pressed into steel).
- :func:`sleeve`: a layer loaded on its outer surface, bonded to a rigid core (polymer-sleeved
  shafts and rollers, inner races).

A liner, sleeve or hole with ``axial="3d"`` is, in a finite journal bearing (``length=``), the
bonded layer (or the hole in a body of the land's thickness) in 3D elasticity over the land
(:mod:`vjax.bodies.layer3d`, :mod:`vjax.bodies.land`: its ends slide on rigid shoulders at the land's
ends); the default ``"slices"`` deforms each axial section as the plane ring. Plane scenes (and
the infinitely long bearing) use the plane-strain body either way: it is the 3D body's long-wave
limit. A 3D hole's ``ref_length`` fixes only its axially uniform response (the plane hole's mode
1); every axially varying one is a proper 3D response, independent of it.

Which to pick: a polymer part much thicker than the contact and its clearance (thesis
plates, solid polymer shafts) is a hole or a disc; a bushing, liner or sleeve whose
thickness is comparable to the contact width or the radius is a liner or a sleeve. Layers
have no log reference length: every mode, the rigid mode 1 included, is a proper elastic
response.
"""
from __future__ import annotations

import dataclasses

import jax
import numpy as np

from .._core import checks
from ..materials.viscoelastic import Material
from . import land
from .operator import ring_operator, whirl_symbol

AXIAL = ("slices", "3d")
_GREEN = {"hole": "hole", "disc": "cylinder", "half_plane": "half_plane", "liner": "liner", "sleeve": "sleeve"}


@jax.tree_util.register_dataclass
@dataclasses.dataclass(frozen=True)
class Body:
    """A ring body: ``material``, ``kind`` (static) and its geometric parameters (m)."""

    material: Material
    ref_length: jax.Array | None = None
    thickness: jax.Array | None = None
    kind: str = dataclasses.field(default="hole", metadata=dict(static=True))
    axial: str = dataclasses.field(default="slices", metadata=dict(static=True))

    def operator(self, R, n: int, omega=0.0, memory="periodic"):
        """Steady-state operator u = M sigma on the loaded surface of radius ``R`` (m), ``n``
        elements, for a pressure pattern moving at ``omega`` (rad/s) relative to the body."""
        ref = 1.0 if self.ref_length is None else self.ref_length
        return ring_operator(_GREEN[self.kind], self.material, R, n, omega, memory, ref, self.thickness)

    def whirl_symbol(self, R, n: int, omega, whirl):
        """Full-FFT symbol of the response to a perturbation at ``whirl`` (rad/s) of a pattern
        moving at ``omega`` relative to the body (:func:`vjax.bodies.operator.whirl_symbol`)."""
        ref = 1.0 if self.ref_length is None else self.ref_length
        return whirl_symbol(_GREEN[self.kind], self.material, R, n, omega, whirl, ref, self.thickness)

    def land_operator(self, R, n: int, m: int, length, omega=0.0, memory="periodic"):
        """A 3D layer's or hole's operator on a finite bearing's land grid (``n`` theta elements by
        ``m`` + 1 uniform axial nodes over ``length`` m; :func:`vjax.bodies.land.land_operator`)."""
        ref = 1.0 if self.ref_length is None else self.ref_length
        return land.land_operator(self.kind, self.material, R, self.thickness, length, n, m, omega, memory, ref)

    def land_whirl_symbol(self, R, n: int, m: int, length, omega, whirl):
        """The same body's whirl response on the land grid (:func:`vjax.bodies.land.whirl_symbol`,
        a hole with its ``ref_length``)."""
        ref = 1.0 if self.ref_length is None else self.ref_length
        return land.whirl_symbol(self.kind, self.material, R, self.thickness, length, n, m, omega, whirl, ref)

    def at_temperature(self, T, *deprecated) -> "Body":
        """The same body with its material at temperature ``T`` (C) under the material's own
        shift law (:meth:`Material.at_temperature`; the 0.2 form ``(shift, T)`` warns)."""
        return dataclasses.replace(self, material=self.material.at_temperature(T, *deprecated))


def _with_ref_length(kind, material, ref_length, axial="slices"):
    checks.instance("material", material, Material, "a vjax.Material")
    checks.positive("ref_length", ref_length)
    checks.scalar("ref_length", ref_length)
    checks.one_of("axial", axial, AXIAL)
    return Body(material, ref_length=ref_length, kind=kind, axial=axial)


def hole(material: Material, ref_length=1.0, axial: str = "slices") -> Body:
    """A hole in an infinite plane of ``material`` (A.45). ``ref_length`` (m): the distance
    at which the plane is held (the thesis's log R with R in metres: 1 m). ``axial``: how a
    finite journal bearing deforms it over the land, "slices" (plane strain per axial section)
    or "3d" (a hole through a body of the land's thickness whose faces slide on rigid shoulders,
    in 3D elasticity, :mod:`vjax.bodies.land`)."""
    return _with_ref_length("hole", material, ref_length, axial)


def disc(material: Material, ref_length=1.0) -> Body:
    """A solid cylinder of ``material`` fixed at its centre (A.60); ``ref_length`` as for
    :func:`hole`."""
    return _with_ref_length("disc", material, ref_length)


def half_plane(material: Material, ref_length=1.0) -> Body:
    """An elastic half-plane of ``material`` on the ring's arc length; ``ref_length`` (m) is
    the additive constant of its log kernel (not stated in the thesis)."""
    return _with_ref_length("half_plane", material, ref_length)


def _layer(kind, material, thickness, axial):
    checks.instance("material", material, Material, "a vjax.Material")
    checks.positive("thickness", thickness)
    checks.scalar("thickness", thickness)
    checks.one_of("axial", axial, AXIAL)
    return Body(material, thickness=thickness, kind=kind, axial=axial)


def liner(material: Material, thickness, axial: str = "slices") -> Body:
    """A layer of ``material``, ``thickness`` (m) thick, loaded on its bore and bonded on its
    outer surface to a rigid housing (Michell's solution, :func:`vjax.bodies.green.mode_compliance`).
    ``axial``: how a finite journal bearing deforms it over the land, "slices" (plane strain
    per axial section) or "3d" (the bonded layer in 3D elasticity, :mod:`vjax.bodies.land`)."""
    return _layer("liner", material, thickness, axial)


def sleeve(material: Material, thickness, axial: str = "slices") -> Body:
    """A layer of ``material``, ``thickness`` (m) thick, loaded on its outer surface and bonded
    on its inner surface to a rigid core; ``axial`` as for :func:`liner`."""
    return _layer("sleeve", material, thickness, axial)


def as_body(name: str, x, default, allowed) -> Body | None:
    """A scene's body argument: None (rigid) stays None, a bare Material becomes
    ``default(x)``, a Body must be of a kind in ``allowed``."""
    if x is None:
        return None
    if isinstance(x, Material):
        return default(x)
    if isinstance(x, Body):
        if x.kind not in allowed:
            raise ValueError(f"{name} must be one of the bodies {', '.join(allowed)} (or a Material, or None "
                             f"for rigid), got a {x.kind}")
        return x
    raise ValueError(f"{name} must be a vjax body ({', '.join(allowed)}), a vjax.Material or None (rigid), "
                     f"got {type(x).__name__}")


def check_fits(name: str, body: Body | None, R) -> None:
    """A layer on a ring of radius ``R`` (m) must be at least 1e-3 R thick (the modal sum of
    its operator resolves thinner layers poorly), and a sleeve thinner than R (it needs a core)."""
    if body is None or body.kind not in ("liner", "sleeve"):
        return
    t, r = checks.values("thickness", body.thickness), checks.values("R", R)
    if t is None or r is None:
        return
    if not np.all(t >= 1e-3 * r) or (body.kind == "sleeve" and not np.all(t < r)):
        raise ValueError(f"{name}: a {body.kind}'s thickness must be at least 1e-3 times its radius"
                         f"{' and below it' if body.kind == 'sleeve' else ''}, got thickness={float(np.max(t)):.4g} m "
                         f"on radius {float(np.max(r)):.4g} m")
