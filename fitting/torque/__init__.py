"""Refine a Prony material and its WLF shift against measured bearing friction torque.

Data: torque-versus-speed curves of a bearing, as a CSV (:func:`read_torque_csv`)::

    # comment lines start with '#'
    speed_rpm, temperature_C, load_N_per_m, torque_Nm_per_m[, scatter_Nm_per_m]

``speed_rpm`` is the shaft (inner ring or pin) speed in rev/min, > 0; ``temperature_C`` in
C; ``load_N_per_m`` the radial load per unit axial length (N/m), > 0; ``torque_Nm_per_m``
the friction torque per unit length (N m/m); the optional ``scatter`` column is the
standard deviation of each torque (same unit, > 0). Columns are matched by name
(case-insensitive, units in the name optional: ``rpm``, ``speed``, ``T``, ``temperature``,
``load``, ``F``, ``torque``, ``scatter``, ``sigma``, ``std``).

Model: a bearing scene evaluated at each point with the material at the point's
temperature (:meth:`vjax.Material.at_temperature`): :func:`roller_model` (needle roller
bearing, torque on the fixed outer ring), :func:`pin_model` (a polymer pin joint: rigid
pin turning in a viscoelastic plate) or :func:`journal_model` (a finite lubricated journal
bearing with a liner of the material; the CSV's load and torque are then the rig's totals
divided by the bearing's length). The scenes carry implicit derivatives, so the
gradient of the torque with respect to the material is one linear solve per solve at the
converged state, not a differentiation through iterations.

Parameters (:class:`Params`): log E0, log E_k, optionally log tau_k, log C1, log C2, and
optionally scene parameters (``extras``): mixed lubrication's boundary friction coefficient
mu_b and composite rms roughness sigma (a :func:`journal_model` with ``roughness=``, torque
along a Stribeck curve through lift-off), or the rig's heat transfer hA (a model with
``heat_transfer=``: the scene at the effective temperature its own dissipation sets, the
data's T the supply/ambient temperature). The fit works on the logarithms: positivity is
automatic and a step means the same relative change for a 1e9 Pa modulus and a C1 of 20.

Objective (dimensionless, a chi^2 per torque point)::

    loss = (1/N_t) [ sum_i ((T_model,i - T_i) / s_i)^2 + w_dma sum_j (r_j / s_dma)^2 ]

with r_j the log10 residuals of the storage and loss moduli on raw DMA points (the material
stays consistent with its DMA; ``w_dma = 0`` fits the torque only), s_i the torque scatter
(or ``rel_scatter`` times the torque when the file has none) and s_dma the DMA scatter in
decades.

Optimizer: optax Adam on the log-parameters, then a Levenberg-Marquardt polish. Why Adam:
the parameters span 10+ decades in value and their torque sensitivities span several more
(a relaxation time far outside the tested frequencies has almost none); Adam's
per-parameter step normalization makes the step a relative change of roughly the learning
rate for every parameter, whatever its scale, and it is robust far from the optimum, where
a Gauss-Newton model of a nearly singular J^T J (exactly what the torque data give, see the
identifiability report) is poor. Near the optimum Adam crawls along the valley; a few
Marquardt-scaled Levenberg-Marquardt steps on the same Jacobian then reach the noise floor
(noise-free pin data in the tests: loss 0.70 after 40 Adam steps, 6e-26 after 20 more LM
steps). optax rather than jaxopt: jaxopt is unmaintained. The Jacobian (forward mode through the
implicit derivatives, one compiled function that returns residuals and Jacobian together)
gives both the gradient 2 J^T r / N_t and, at the end, the Gauss-Newton covariance
(J^T J)^-1 and the singular values that say which parameters the torque cannot identify.
"""
from .data import TorqueData, TorqueFormatError, read_torque_csv, write_torque_csv
from .fit import TorqueFit, evaluate, fit_torque, gauss_newton_cov, gradient_check, identifiability, residual_jacobian
from .models import journal_model, oil_viscosity, pin_model, roller_model, water_viscosity
from .params import EXTRAS, Params

__all__ = ["TorqueData", "TorqueFormatError", "read_torque_csv", "write_torque_csv", "roller_model", "pin_model",
           "journal_model", "water_viscosity", "oil_viscosity", "evaluate", "EXTRAS",
           "Params", "TorqueFit", "fit_torque", "residual_jacobian", "identifiability", "gauss_newton_cov",
           "gradient_check"]
