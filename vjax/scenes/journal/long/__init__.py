"""Visco-elastohydrodynamic (VEHL) infinitely long journal bearing (thesis Chapter 3).

Geometry and frames
-------------------
Bearing bore (the ``housing``) of radius ``R`` (centre O), journal (the ``shaft``) of radius
R_J = R - c with c the ``radial_clearance`` (centre O'). The ring grid theta_i = 2 pi i / n is attached to the **line of
centres**: theta = 0 points from O towards O' (where the rigid gap is smallest). The load
line is at absolute angle ``load_angle`` (x axis = 0, counter-clockwise positive); the line
of centres is at absolute angle ``load_angle + attitude_angle``. Everything is rotationally
invariant (circulant rings, uniform surface speeds), so this frame loses nothing.

Film (positive-into-the-body convention of :mod:`vjax.bodies.operator`)
----------------------------------------------------------------
    h(theta) = c (1 - eps cos theta) + u_B(theta) + u_J(theta)

u_B: radial displacement of the bore, positive outward (into the bearing body); u_J: of
the journal, positive inward (into the journal). Fluid pressure pushes both surfaces away
from the film, so both *increase* h. The thesis writes h = h0 + g0 + u_r^B - u_r^J with
both u_r positive along the outward radius: the same thing (u_J = -u_r^J).
Deformations are the steady-state viscoelastic ring operators of each body at the speed
of the pressure pattern relative to it: the pattern is fixed in space, so it moves at
-omega_housing relative to the bearing (a bare Material: :func:`~vjax.hole`, A.45) and at
-omega_shaft relative to the journal (a bare Material: :func:`~vjax.disc`, A.60), or with
:func:`~vjax.half_plane` bodies (the comparison of Fig. 3.4). A hole's or disc's log
reference length ``ref_length`` (1 m as in the thesis) sets the n = 1 (rigid translation)
part of its response: it shifts ``eccentricity`` (which can exceed 1 with a soft liner) but
not ``eccentricity_effective`` (first Fourier mode of h over c).

Reynolds equation and cavitation (Eq. 3.41)
-------------------------------------------
Finite volumes on the ring with ``cavitation`` "reynolds" (default, Swift-Stieber as a
Fischer-Burmeister complementarity), "jfo" (mass-conserving Jakobsson-Floberg-Olsson /
Elrod-Adams conditions: pressure and film fraction as one universal unknown),
"half_sommerfeld" or "sommerfeld": :mod:`vjax.films.reynolds`. With "jfo" the cavity is a
striated film of liquid fraction ``film_fraction`` < 1 that carries only the Couette flow of
its liquid, so the shear stress of the Couette flow there acts on that fraction too.
The entrainment speed is v = (omega_B R_B + omega_J R_J)/2.

**Pressure datum.** A lubricant supply groove at ``supply_angle`` (snapped to the nearest
element) holds ``supply_pressure`` (gauge, Pa; default 0 = ambient) and supplies whatever
flow the film needs. Without it the 360-degree problem with Reynolds conditions is
degenerate: any constant can be added to the pressure of a full film and the cavitated
state is not fixed, so there is no unique solution. Where the groove is (``groove=``):

- ``"line_of_centres"`` (default, the classical theory): the groove turns with the line of
  centres, ``supply_angle`` measured from it (default pi, the largest rigid clearance);
- ``"fixed"``: the groove is fixed in the bearing, ``supply_angle`` measured from the load
  direction (default pi: opposite the load, the usual design). The grid is then attached to
  the load line and the line of centres turns over it: the film is
  c (1 - eps cos(theta - attitude)) + u_B + u_J on the grid angle theta. The result's
  arrays are on that grid, their ``theta`` given from the line of centres (theta_grid -
  attitude) as for the default.

Load control: the pressure force on the journal balances ``load`` (N/m, the external force
on the journal); the eccentricity ratio ``eps`` and the attitude angle are unknowns.
Viscous shear forces on the journal are O(c/R) of the load and are not included in
this balance (nor in classical theory).

Torques, dissipation (Eq. 3.43-3.46)
------------------------------------
All torques are exerted **by the fluid on the body**, counter-clockwise positive, N m/m.
``force`` is the pressure force the film exerts on the housing (absolute x, y; equal to the
load at equilibrium).
Shear tractions (3.45) at the faces: tau_B = -h/2 dp/ds - eta (U_B - U_J)/h,
tau_J = -h/2 dp/ds + eta (U_B - U_J)/h (U = omega R, surface speeds), on the film arc
ds = R_B dtheta. The pressure on a *deformed* profile has a moment about the body's
centre: -R_B int p du/dtheta dtheta (central differences); this is the viscoelastic
torque ``torque_viscoelastic`` (housing) / ``torque_viscoelastic_shaft``, and
-omega times it is the hysteretic dissipation (Eq. 3.46 with the sign fixed so that it is
non-negative for both bodies: power into a body = int p du/dt ds, du/dt = -Omega du/dtheta
for a pattern moving at Omega relative to it):

- ``torque`` (on the housing) about O: R_B^2 int tau_B dtheta + torque_viscoelastic.
- ``torque_shaft`` about the journal's own centre O': R_J R_B int tau_J dtheta +
  torque_viscoelastic_shaft. ``torque_shaft_about_O`` = torque_shaft + e x F (the
  thesis's choice, = -torque up to O(c/R) by the fluid's moment balance).
- Power balance (exact for the discrete equations with Reynolds/Sommerfeld conditions):
  -omega_B torque - omega_J torque_shaft + p_s Q_s + sum_i p_i (q_{i+1/2} - q_{i-1/2})
  = dissipation_fluid + dissipation_housing + dissipation_shaft, the sum (over the cells but
  the groove's) the pressure energy of the flow let out within the rupture's cell, the only
  pressurized cell with a net outflow (:func:`vjax.films.reynolds.rupture_outflow`; ~1e-8 of the power).

Mixed lubrication (``roughness=``)
----------------------------------
Rough surfaces (a :class:`~vjax.Roughness`): Patir and Cheng's average flow in the fluxes
(:mod:`vjax.films.reynolds`), Greenwood and Tripp's asperity pressure p_a(h) at every cell,
which joins the film's pressure in the force balance and in the load on deformable bodies (then
p_a / p_ref is an unknown per cell, p_a - p_a(h) = 0, solved with the rest by a dense LU), the
film's shear with Patir and Cheng's shear stress factors and the asperities' friction mu_b p_a.
Per unit length as everything here; docs/theory.md §18.2. Not with ``cavitation="jfo"``.

Solver
------
Unknowns p/p_ref (n values), eps, attitude (and the asperity pressures, see above): n + 2
equations (cell balances / FB, groove datum, two force components; and p_a - p_a(h) per
cell). The core's damped Newton (:func:`vjax._core.solve.newton`; steps
giving h <= 0 are rejected), each step solved (``options.linear_solver``) with the exact
dense AD Jacobian (LU, O(n^3)) or matrix-free by GMRES (Jacobian-vector products,
O(n log n)) preconditioned by the film's cyclic tridiagonal Jacobian plus the bodies' compliance on
its lowest Fourier modes (:func:`vjax.scenes.journal.long.film.linear_model`; exact for rigid bodies); "auto" switches to
GMRES above n = 1024, and the implicit derivatives use the same solve. The bodies'
deformation takes its Fourier mode 1 (a rigid translation) from the load, which the film
force equals at the root, not from the iterate's pressure: the same root, without a
translation of up to hundreds of clearances for Newton to find (docs/theory.md §10).
``options.strategy="auto"`` first tries Newton from the rigid half-Sommerfeld estimate (with
bodies on n >= 128 elements, rigid on n >= 512, from the solution on a 4x coarser grid,
interpolated by C1 cubics: a second compiled solver, which pays only where the direct start
needs many steps or fails; or from ``initial``, e.g. the previous point of a sweep); if it fails or lands on the spurious
branch (effective eccentricity <= 0: the supply at the minimum gap), it continues from a
rigid solution at a higher entrainment speed (such that the rigid eccentricity is about
0.6), ramping the compliance in and the speed down over at most ``options.stages`` Newton
solves. Derivatives of the converged solution are implicit
(:func:`vjax._core.solve.implicit_root`), not through the iterations.

Convergence: ``iterations`` (Newton steps on the final grid, summed over continuation
stages), ``stages`` (continuation stages used, 0 = direct), ``residual`` (max-norm of the
scaled equations), ``result`` (0 = converged on the physical branch). ``throw=True``
raises :class:`~vjax.ConvergenceError` on failure, inside ``jit`` too.
"""
from .outputs import JournalResult
from .steady import long_journal_bearing

__all__ = ["JournalResult", "long_journal_bearing"]
