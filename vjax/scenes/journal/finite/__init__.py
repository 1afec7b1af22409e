"""Finite-length journal bearing: the film over the bearing's width, the bodies in plane-strain slices.

Called by :func:`vjax.journal_bearing` with ``length=L``; docs/theory.md §16.

Geometry and frames
-------------------
Bore of radius R (centre O), journal of radius R - c, land z in [-L/2, L/2] with ambient
pressure at both ends. The grid theta_i = 2 pi i / n is fixed in the bearing: theta = 0
points along the load (its direction when the bearing is set up, so that derivatives with
respect to the load vector do not turn the bearing). An axial supply groove at
``supply_angle`` (rad from the load, counter-clockwise; default pi, opposite the load) holds
``supply_pressure`` over the central fraction ``supply_width`` of the land (1: the whole
width; a feed hole: its diameter over L); ``supply_angle=None``: no groove, the ends alone
set the datum. ``groove="circumferential"``: instead a groove round the mid-width z = 0 at
``supply_pressure`` (zero width: it splits the land into two of L/2). The journal centre
at axial position z sits at e + z gamma from the bore's axis: e the eccentricity vector
(unknown), gamma = ``tilt`` (rad, absolute x, y components: the journal's axis turned about
y by gamma_x and about -x by gamma_y, small angles), so that

    h(theta, z) = c - (e_x + z gamma_x) cos theta - (e_y + z gamma_y) sin theta

(grid axes), plus the bodies' deformations u_B + u_J (each positive where it opens the film).
Film equations: :mod:`vjax.films.film2d`. Cavitation "reynolds" (default), "jfo" (mass-conserving:
Elrod's universal unknown, as in 1D), "half_sommerfeld", "sommerfeld".

Bodies: ``housing`` (hole, liner, half-plane) and ``shaft`` (disc, sleeve, half-plane), as in
the long bearing, None for rigid. Each axial section deforms as the plane ring does under
its own pressure (plane strain: no axial coupling between the slices), with the ring's
steady-state viscoelastic operator, the pattern fixed in space moving at -omega relative to
each body; the exact limit of a long bearing, and of any bearing whose bodies are thin
against the pressure's axial length scale (a liner much thinner than L; a bonded layer's
axial coupling is of the order of its thickness over L). :func:`deformations`. A liner or
sleeve made with ``axial="3d"`` is instead the bonded layer in 3D elasticity over the land,
its ends sliding on rigid shoulders at z = +-L/2 (:mod:`vjax.bodies.land`: the pressure
piecewise linear in z, FFT in theta and DCT-I in z; uniform axial spacing; in the dynamic
coefficients by its whirl response,
:func:`vjax.bodies.land.whirl_symbol`).

Load control: the pressure force of the film on the journal balances ``load`` (N, the
external force on the journal, total for the bearing); the unknowns are the scaled pressures
and the eccentricity vector e/c (grid axes). With a tilt the film also exerts a moment on the
journal (``moment``, about the centre plane z = 0), which the shaft must carry; the tilt is
given, not solved for.

Outputs (SI totals for the bearing)
-----------------------------------
``force`` on the housing (N, absolute; the load at equilibrium), ``moment`` of the film on the
journal about the bore's centre point (N m, absolute x, y), ``position`` e (m, absolute),
``eccentricity`` |e|/c, ``attitude_angle`` (from the load line to e, counter-clockwise),
``line_of_centres_angle`` (absolute). ``min_film`` (m) and where: ``min_film_theta`` (grid
angle, from the load) and ``min_film_z`` (m); ``max_pressure`` (Pa). Torques by the fluid
(N m, counter-clockwise positive), shear tau_B = -h/2 dp/dx - eta (U_B - U_J)/h on the bore and
tau_J = -h/2 dp/dx + eta (U_B - U_J)/h on the journal (U = omega R): ``torque`` on the housing
about O, ``torque_shaft`` on the journal about its own centre, and their pressure-flow
(Poiseuille) parts ``torque_poiseuille``, ``torque_poiseuille_shaft`` and the viscoelastic
parts ``torque_viscoelastic``, ``torque_viscoelastic_shaft``: the moment of the pressure on
each slice's deformed profile about the body's centre, -R int int p du/dtheta dtheta dz (the
rest is Couette; the Reynolds cavity is taken as full of lubricant, as in Raimondi and Boyd);
-omega times a viscoelastic torque is the body's hysteretic dissipation. Flows (m^3/s):
``side_leakage`` out of both ends, ``supply_flow`` the groove's net outflow, ``inlet_flow``
the flow the groove sends downstream into the land (Raimondi and Boyd's Q). ``power_loss``
(W): the viscous dissipation in the film (with rough surfaces: the conductances' and the
Couette shear's factors, and the asperities' friction times the sliding speed, ``roughness=``
below); with the bodies' hysteresis it balances the power
put in, -omega_B torque - omega_J torque_shaft + p_s supply_flow = power_loss - omega_B
torque_viscoelastic - omega_J torque_viscoelastic_shaft, up to the pressure energy
sum p_i w_i of the flow let out within the rupture's cells (the rupture located within its
cell, :func:`vjax.films.reynolds.rupture_outflow`; ~1e-8 of the power), which the left side gains.

Solver: the core's damped Newton (:func:`vjax._core.solve.newton`, steps giving h <= 0 rejected).
An aligned bearing (``tilt`` None) has a pressure symmetric about mid-width: its unknowns are
the cells from mid-width to one end, mirrored (:func:`interior`), half the width's; a tilt,
even a zero one given, solves the whole width. Each Newton step (:func:`linear_model`): the
cell equations' Jacobian in the pressures, the deformation held, is a 9-point stencil, block
tridiagonal (a ring of n blocks across the width, cyclic), bordered by the eccentricity's two
columns and the two force rows. Rigid bodies: that is the Jacobian, solved exactly by a
block Thomas factorization and Woodbury (:mod:`vjax.films.blocks`, O(n k^3) for k cells across)
up to EXACT_WIDTH cells across, above that by GMRES preconditioned by an aggregation
multigrid V-cycle (:mod:`vjax.films.multigrid`, O(n k) per application). Deformable bodies
couple every cell of a slice through their compliance: a dense LU of the Jacobian from
jacfwd (``linear_solver="dense"``, up to a few thousand unknowns, O(N^3)), or GMRES with
matrix-free products (one FFT each, O(N log N)) preconditioned as the rigid film with each
node's own compliance added (``"krylov"``; "auto": from KRYLOV_MIN_CELLS cells). Under
Reynolds conditions a Newton that stalls restarts from the half-Sommerfeld solution; "jfo"
starts from the Reynolds solution (:func:`.steady._jfo_steady`); soft bodies fall back on
continuation in their compliance and the speed (:func:`.steady._steady`); cold solves on grids of
NESTED_MIN_CELLS cells or more start from a coarser grid's solution
(:func:`.steady.coarse_options`). Derivatives are implicit (:func:`vjax._core.solve.implicit_root`, the same linear solve and its transpose).
Dynamic coefficients: :func:`impedance`, the cell equations linearized in the pressures and
the journal's position (and tilt) and their rates, with the bodies by their whirl operators
and a "jfo" cavity's fraction by its own dynamics; matrix-free, one GMRES solve per whirl
frequency and load column, preconditioned as Newton's steps (rigid bodies on grids up to
EXACT_WIDTH cells across: the exact block solve alone). ``throw=True`` raises
:class:`~vjax.ConvergenceError` on failure, inside ``jit`` too.
"""
from .coefficients import finite_coefficients, force_at, impedance, tilt_coefficients
from .outputs import FiniteJournalResult
from .steady import finite_journal_bearing

__all__ = ["FiniteJournalResult", "finite_coefficients", "finite_journal_bearing", "force_at", "impedance",
           "tilt_coefficients"]
