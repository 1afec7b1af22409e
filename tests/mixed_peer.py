"""An independent peer of the rigid finite journal bearing in mixed lubrication (issue 43).

Written from the equations with numpy and scipy only (nothing from vjax), for tests to compare
against. Model (SI units throughout):

- Average Reynolds equation (Patir and Cheng 1978), x = R theta along the journal's motion:
      d/dx(phi_x h_c^3/(12 eta) dp/dx) + d/dz(phi_z h_c^3/(12 eta) dp/dz) = v d/dx(h_T + Vr sigma Phi_s)
  with v = omega R_J / 2 (only the journal turns), H = h/sigma, H_c = max(H, 0.5), h_c = sigma H_c,
  isotropic roughness (gamma = 1: phi_z = phi_x), h_T the Gaussian expected gap (unclipped),
  Vr = -1 (bush rough, journal smooth). The factors are evaluated at H_c.
- Greenwood and Tripp (1970) asperity pressure p_a = K E' F_{5/2}(H) (unclipped) with
  K = (16 sqrt 2 pi / 15)(eta_s beta sigma)^2 sqrt(sigma/beta), 1/E' = sum (1 - nu^2)/E.
- Journal shear stress (Patir and Cheng 1979), resisting the motion:
      tau = eta U/h_c (phi_f - Vr Phi_fs) + phi_fp (h_c/2) dp/dx,  U = omega R_J,
  plus the asperities' mu_b p_a.

Sources of the fits (gamma = 1): Patir and Cheng, ASME J. Lubr. Technol. 100 (1978) 12-17,
Eq. 23 / Table 1 (phi_x = 1 - 0.90 e^{-0.56 H}) and Eq. 26 / Table 2 (Phi_s = 1.899 H^0.98
e^{-0.92 H + 0.05 H^2} for H <= 5, 1.126 e^{-0.25 H} beyond); Patir and Cheng, ASME J. Lubr.
Technol. 101 (1979) 220-230: phi_f (their closed form of the mean of h/h_local over the density
(35/32)(1 - x^2)^3 of x = delta/(3 sigma), the 1/h_local singularity cut at (z + x) = 1/300),
Phi_fs = 11.1 H^2.31 e^{-2.38 H + 0.11 H^2} (fitted for 0.5 < H < 7; taken 0 for H >= 7, where
the table ends) and phi_fp = 1 - 1.40 e^{-0.66 H}. (The same constants appear in R. Boman's
EHD code, github.com/rboman/progs, apps/EHD/EHD/ehd_flow_cisail.c.)

Discretization (the finite film's finite volumes): n cells in theta, centres theta_i = 2 pi i/n
measured from the load direction (grid x axis: the load pushes the journal towards +x, so
h = c - e_x cos theta - e_y sin theta); m + 1 uniform axial nodes z_j from -L/2 to L/2, the end
nodes at ambient (0) pressure, one control volume R dtheta x w_j per interior node (w_j the
trapezoidal widths). Face films are the mean of the two nodes; every factor is evaluated on the
face film (H_c clip and h_T of the face h). Reynolds cavitation by an active set with the
sub-cell rupture share W (1 - beta)_+^2 / 2 (beta = sqrt p / (sqrt p_up - sqrt p), W the cell's
net Couette outflow), as tests/test_journal_finite_peer.py. p_a lives on all nodes (ends
included, half widths there).

Conventions fixed here: D = 2 R (bore diameter), L = (L/D) D. Areas R dtheta w_j (bore radius).
Friction force F_f = int (tau + mu_b p_a) R dtheta dz: the journal torque is R_J F_f, so F_f is
that torque over R_J (equivalently, with the arm R, torque over R). tau is evaluated on the theta
faces (where dp/dx lives) on every axial node, ends included (weights w_j), over the whole land,
the cavitated zone included (the full Couette shear there). Friction coefficient F_f / W;
asperity share |int p_a n dA| / W; force balance on normal forces only (film + asperities +
load = 0), solved for the journal centre (e_x, e_y) by scipy.optimize.root.
"""
import numpy as np
import scipy.optimize as so
import scipy.sparse as sp
import scipy.sparse.linalg as spla
from scipy.special import erf, gamma, pbdv

R_J, R, ETA, LOAD, MU_B = 25e-3, 25.05e-3, 0.03, 2000.0, 0.1    # m, m, Pa s, N, -
C = R - R_J                                                       # 50 um radial clearance
E_PRIME = 1.0 / ((1 - 0.3**2) / 210e9 + (1 - 0.4**2) / 3e9)      # steel on polymer (Pa)
K_GT = 16 * np.sqrt(2) * np.pi / 15 * 0.05**2 * np.sqrt(0.005)   # eta_s beta sigma = 0.05, sigma/beta = 0.005
VR, CLIP, CUTOFF = -1.0, 0.5, 1.0 / 300.0


_GH_X, _GH_W = np.polynomial.hermite_e.hermegauss(60)
_GH_W = _GH_W / np.sqrt(2 * np.pi)


# ---- roughness functions (dimensionless, of H = h/sigma) --------------------------------------
def F52(H):
    """Greenwood-Tripp F_{5/2}(H) = (2 pi)^-1/2 int_H^inf (s - H)^{5/2} e^{-s^2/2} ds: through the
    parabolic cylinder function, Gamma(7/2) (2 pi)^-1/2 e^{-H^2/4} D_{-7/2}(H), for -8 <= H < 38;
    0 above (below 1e-300); below -8 (where that product overflows) the mean of (s - H)^{5/2}
    by 60-point Gauss-Hermite (the part s < H, e^{-32}, dropped)."""
    H = np.asarray(H, float)
    Hs = np.clip(H, -8.0, 38.0)
    F = gamma(3.5) / np.sqrt(2 * np.pi) * np.exp(-Hs**2 / 4) * pbdv(-3.5, Hs)[0]
    Hn = np.minimum(H, -8.0)[..., None]
    deep = (np.maximum(_GH_X - Hn, 0.0) ** 2.5) @ _GH_W
    return np.where(H < -8.0, deep, np.where(H < 38.0, F, 0.0))


def expected_gap(H):
    """h_T/sigma = [H + H erf(H/sqrt 2) + sqrt(2/pi) e^{-H^2/2}]/2 (Gaussian heights)."""
    return 0.5 * (H + H * erf(H / np.sqrt(2)) + np.sqrt(2 / np.pi) * np.exp(-H**2 / 2))


def phi_x(H):
    """Pressure flow factor, Patir and Cheng 1978, gamma = 1."""
    return 1 - 0.90 * np.exp(-0.56 * H)


def Phi_s(H):
    """Shear flow factor of one rough surface, Patir and Cheng 1978, gamma = 1."""
    Hs = np.clip(H, 1e-300, 5.0)
    return np.where(H <= 5, 1.899 * Hs**0.98 * np.exp(-0.92 * Hs + 0.05 * Hs**2), 1.126 * np.exp(-0.25 * H))


_GL_X, _GL_W = np.polynomial.legendre.leggauss(24)


def phi_f(H):
    """Patir and Cheng's 1979 shear stress factor phi_f = E[h/h_local], heights with density
    (35/32)(1 - x^2)^3, x = delta/(3 sigma) in [-1, 1], z = H/3. With (1 - x^2)^3 =
    (1 - z^2)^3 + (z + x) q(x; z), q a quintic: (35/32) z [(1 - z^2)^3 int dx/(z + x) + int q dx]
    over the gaps (x > -z), the log integral cut at z + x = 1/300 where the surfaces may touch
    (z <= 1); the quintic by Gauss-Legendre (exact). For z > 2 the mean of z/(z + x) directly by
    24-point Gauss-Legendre (analytic: error below 1e-20; no cancellation)."""
    z = np.asarray(H, float)[..., None] / 3.0
    a = np.maximum(-z, -1.0)                                       # lower end of the gaps
    x = a + (1 - a) * (_GL_X + 1) / 2                              # nodes on [a, 1]
    q = ((1 - x**2) ** 3 - (1 - z**2) ** 3) / (z + x)
    log = np.where(z <= 1, np.log((1 + z) / CUTOFF), np.log((z + 1) / np.maximum(z - 1, 1e-300)))
    split = 35 / 32 * z[..., 0] * ((1 - z**2) ** 3 * log + (1 - a) / 2 * (q @ _GL_W[:, None]))[..., 0]
    direct = 35 / 32 * (((1 - _GL_X**2) ** 3 * z / (z + _GL_X)) @ _GL_W)
    return np.where(z[..., 0] <= 2, split, direct)


def Phi_fs(H):
    """Shear stress factor Phi_fs, Patir and Cheng 1979, gamma = 1 (fit for 0.5 < H < 7; 0 beyond)."""
    Hs = np.clip(H, 1e-300, 7.0)
    return np.where(H < 7, 11.1 * Hs**2.31 * np.exp(-2.38 * Hs + 0.11 * Hs**2), 0.0)


def phi_fp(H):
    """Shear stress factor phi_fp, Patir and Cheng 1979, gamma = 1."""
    return 1 - 1.40 * np.exp(-0.66 * H)


# ---- the film --------------------------------------------------------------------------------
class Bearing:
    """Grid and operators of one case: L/D, sigma (m; None: smooth surfaces, no asperities),
    n theta cells, m axial intervals."""

    def __init__(self, L_over_D, sigma, n=32, m=16):
        if not L_over_D > 0:
            raise ValueError(f"L_over_D must be > 0, got {L_over_D}")
        if sigma is not None and not sigma > 0:
            raise ValueError(f"sigma must be > 0 (m) or None (smooth), got {sigma}")
        if n < 8 or m < 2:
            raise ValueError(f"n must be >= 8 and m >= 2, got n={n}, m={m}")
        self.sigma, self.n, self.m, self.L = sigma, n, m, L_over_D * 2 * R
        self.theta = 2 * np.pi * np.arange(n) / n
        self.dth = 2 * np.pi / n
        self.z = np.linspace(-self.L / 2, self.L / 2, m + 1)
        dz = np.diff(self.z)
        self.w = 0.5 * (np.r_[0.0, dz] + np.r_[dz, 0.0])
        # unknowns: interior nodes (i, j), j = 1..m-1, index i (m - 1) + j - 1
        self.idx = np.full((n, m + 1), -1)
        self.idx[:, 1:-1] = np.arange(n * (m - 1)).reshape(n, m - 1)
        self.active = None                                      # warm start of the active set

    def film(self, e):
        """Nominal film h (n, m + 1) (m) with the journal centre at e = (e_x, e_y) (m)."""
        return C - e[0] * np.cos(self.theta)[:, None] - e[1] * np.sin(self.theta)[:, None] + 0 * self.z

    def factors(self, hf):
        """Poiseuille term g = phi h_c^3 (m^3) and Couette gap (m) on face films hf."""
        if self.sigma is None:
            return hf**3, hf
        s = self.sigma
        Hc = np.maximum(hf / s, CLIP)
        return phi_x(Hc) * (s * Hc) ** 3, s * expected_gap(hf / s) + VR * s * Phi_s(Hc)

    def pressure(self, h, v):
        """Film pressure (n, m + 1) (Pa) at entrainment speed v (m/s): Reynolds conditions."""
        n, m, w, dz = self.n, self.m, self.w, np.diff(self.z)
        hx = 0.5 * (h + np.roll(h, -1, axis=0))                 # face (i + 1/2, j)
        hz = 0.5 * (h[:, 1:] + h[:, :-1])                       # face (i, j + 1/2)
        gx, cx = self.factors(hx)
        gz, _ = self.factors(hz)
        gx = gx / (12 * ETA) / (R * self.dth) * w[None, :]
        gz = gz / (12 * ETA) / dz[None, :] * R * self.dth
        # net outflow A p + b: each face adds g (p_a - p_b) to a and g (p_b - p_a) to b
        a = np.r_[self.idx[:, 1:-1].ravel(), self.idx[:, :-1].ravel()]
        b = np.r_[np.roll(self.idx, -1, axis=0)[:, 1:-1].ravel(), self.idx[:, 1:].ravel()]
        g = np.r_[gx[:, 1:-1].ravel(), gz.ravel()]
        rows, cols, vals = [], [], []
        for u, t in ((a, b), (b, a)):
            ok = u >= 0
            rows += [u[ok], u[ok & (t >= 0)]]
            cols += [u[ok], t[ok & (t >= 0)]]
            vals += [g[ok], -g[ok & (t >= 0)]]
        N = n * (m - 1)
        A = sp.csr_matrix((np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols))), shape=(N, N))
        couette = (v * (cx - np.roll(cx, 1, axis=0)) * w[None, :])[:, 1:-1].ravel()
        up = np.roll(self.idx, 1, axis=0)[:, 1:-1].ravel()      # upstream cell (v > 0)
        Wp = np.maximum(couette, 0.0)

        def share(p):
            """Rupture share and its derivatives in p and in p_upstream."""
            s = np.sqrt(np.maximum(p, 0.0))
            su = s[up]
            falling = su > s
            d = np.where(falling, su - s, 1.0)
            f = np.where(falling, np.maximum((su - 2 * s) / d, 0.0), 0.0)       # (1 - beta)_+
            ds = np.where(f > 0, -su / d**2, 0.0) * 0.5 / np.maximum(s, 1e-300) * (p > 0)
            dsu = np.where(f > 0, s / d**2, 0.0) * 0.5 / np.maximum(su, 1e-300) * (su > 0)
            return Wp * f**2 / 2, Wp * f * ds, Wp * f * dsu

        active = np.ones(N, bool) if self.active is None else self.active.copy()
        bscale = np.max(np.abs(couette)) + 1e-300
        seen = set()
        for _ in range(300):
            S = np.flatnonzero(active)
            p = np.zeros(N)
            if S.size:
                p[S] = spla.spsolve(A[S][:, S].tocsc(), -couette[S])
            for _ in range(30):                    # Newton: A p + b - share(p) = 0 on S
                sh, dself, dup = share(p)
                r = (A @ p + couette - sh)[S]
                converged = not S.size or np.max(np.abs(r)) <= 1e-12 * bscale
                if converged:
                    break
                J = A - sp.diags(dself) - sp.csr_matrix((dup, (np.arange(N), up)), shape=(N, N))
                dp = spla.spsolve(J.tocsr()[S][:, S].tocsc(), r)
                for t in 0.5 ** np.arange(30):     # backtracking: the share has kinks at p = 0
                    q = p.copy()
                    q[S] -= t * dp
                    if np.max(np.abs((A @ q + couette - share(q)[0])[S])) < np.max(np.abs(r)):
                        break
                p = q
            # (an unconverged Newton: some active cell wants p < 0; the set's update removes it)
            outflow = A @ p + couette - share(p)[0]
            new = (active & (p > 0)) | (~active & (outflow < 0))
            if np.array_equal(new, active):
                if not converged:
                    raise RuntimeError("the peer's Newton on the rupture share did not converge")
                break
            if new.tobytes() in seen:          # a cycle: admit one cell, the most starved
                adds = np.flatnonzero(new & ~active)
                if adds.size:
                    new = active.copy()
                    new[adds[np.argmin(outflow[adds])]] = True
            seen.add(active.tobytes())
            active = new
        else:
            raise RuntimeError("the peer's active set did not settle")
        self.active = active
        P = np.zeros((n, m + 1))
        P[:, 1:-1] = p.reshape(n, m - 1)
        return P

    def asperity(self, h):
        """Greenwood-Tripp asperity pressure on all nodes (Pa)."""
        return np.zeros_like(h) if self.sigma is None else K_GT * E_PRIME * F52(h / self.sigma)

    def force(self, P):
        """Force (N, grid axes) of a pressure on all nodes on the journal: -int P e_r R dtheta dz."""
        return -R * self.dth * np.array([np.cos(self.theta) @ P @ self.w, np.sin(self.theta) @ P @ self.w])

    def state(self, e, omega):
        """Everything at journal centre e (m) and speed omega (rad/s)."""
        h = self.film(e)
        P = self.pressure(h, 0.5 * omega * R_J)
        Pa = self.asperity(h)
        return h, P, Pa, self.force(P), self.force(Pa)

    def solve(self, omega, guess):
        """Equilibrium at omega (rad/s) from a guess of (e_x, e_y)/c: film + asperities + load = 0."""
        def residual(x):
            _, _, _, F, Fa = self.state(x * C, omega)
            return (F + Fa + [LOAD, 0.0]) / LOAD
        sol = so.root(residual, guess, method="hybr", options=dict(xtol=1e-11))
        if np.max(np.abs(residual(sol.x))) > 1e-8:
            raise RuntimeError(f"the peer's force balance failed at omega={omega}: {sol.message}")
        return self.outputs(sol.x * C, omega)

    def outputs(self, e, omega):
        """Outputs at journal centre e (m) and speed omega (rad/s) (see :func:`stribeck`)."""
        h, P, Pa, F, Fa = self.state(e, omega)
        U = omega * R_J
        hx = 0.5 * (h + np.roll(h, -1, axis=0))
        dpdx = (np.roll(P, -1, axis=0) - P) / (R * self.dth)
        if self.sigma is None:
            tau = ETA * U / hx + 0.5 * hx * dpdx
        else:
            Hc = np.maximum(hx / self.sigma, CLIP)
            hc = self.sigma * Hc
            tau = ETA * U / hc * (phi_f(Hc) - VR * Phi_fs(Hc)) + phi_fp(Hc) * 0.5 * hc * dpdx
        area = R * self.dth * self.w[None, :]
        Fv, Fb = np.sum(tau * area), MU_B * np.sum(Pa * area)
        return dict(omega=omega, e=e, eccentricity=np.hypot(*e) / C, attitude=np.arctan2(e[1], e[0]),
                    asperity_share=np.hypot(*Fa) / LOAD, friction_viscous=Fv, friction_boundary=Fb,
                    friction_coefficient=(Fv + Fb) / LOAD, h_min=h.min(),
                    lam=np.inf if self.sigma is None else h.min() / self.sigma,
                    wrap=np.sum(Pa * area) / max(np.hypot(*Fa), 1e-300), pressure=P, asperity_pressure=Pa)


def _deeper(bearing, omega, x):
    """The equilibrium at omega from guesses at growing eccentricity along x = e/c."""
    for k in range(1, 21):
        try:
            return bearing.solve(omega, x * (1 + 0.0025 * k))
        except RuntimeError:
            pass
    raise RuntimeError(f"the peer found no equilibrium at omega={omega} near e/c={x}")


SCALARS = ("omega", "eccentricity", "attitude", "asperity_share", "friction_coefficient",
           "friction_viscous", "friction_boundary", "h_min", "lam", "wrap", "jump")


def stribeck(L_over_D, sigma, omegas, n=32, m=16, guess=(0.7, 0.35)):
    """Stribeck curve of the case (L/D, sigma (m) or None for smooth surfaces) on an n x (m + 1)
    grid at the speeds ``omegas`` (rad/s), solved from the fastest down (warm-started). Returns a
    dict of arrays in the order of ``omegas``: omega (rad/s), eccentricity (|e|/c), attitude
    (rad, atan2(e_y, e_x), from the load direction towards the rotation), asperity_share (-),
    friction_coefficient (-), friction_viscous and friction_boundary (N), h_min (m), lam
    (h_min/sigma), wrap (int p_a dA / |int p_a n dA|, -), jump (True where the warm-started
    branch had ended at a fold and the solve moved to the deeper branch).

    Resolution: the asperity contact spans only a few theta cells at n = 32, so in the mixed
    regime the curve is a property of the grid (n = 32, 64, 128 at L/D = 0.5,
    sigma = 1 um, 1 rad/s: asperity share 0.205, 0.109, 0.098); on 32 x 16 the model has a fold
    near 0.1-0.25 rad/s (two equilibria: share 0.23 and 0.50 at 0.22 rad/s). Compare codes on
    the same grid; quote physical curves from n >= 128."""
    omegas = np.asarray(omegas, float)
    if omegas.ndim != 1 or not np.all(omegas > 0):
        raise ValueError(f"omegas must be a 1D array of positive speeds (rad/s), got {omegas!r}")
    bearing = Bearing(L_over_D, sigma, n, m)
    x = np.asarray(guess, float)
    out = {}
    last = None
    for k in np.argsort(-omegas):
        # a failed step is retried in smaller steps in log omega from the last solved speed;
        # if the branch itself ends (a fold: the model has one in mixed lubrication, where two
        # equilibria coexist over a band of speeds), the journal is pushed deeper to find the
        # other branch, and the point is flagged as a jump
        todo, jump = [omegas[k]], False
        while todo:
            try:
                r = bearing.solve(todo[-1], x)
            except RuntimeError:
                if last is None:
                    raise
                if len(todo) <= 6:
                    todo.append(np.sqrt(last * todo[-1]))
                    continue
                r = _deeper(bearing, todo[-1], x)
                jump = True
            x, last = r["e"] / C, todo.pop()
        out[k] = dict(r, jump=jump)
    return {key: np.array([out[k][key] for k in range(len(omegas))]) for key in SCALARS}
