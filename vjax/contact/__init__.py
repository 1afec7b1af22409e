"""Dry contact: the projected / NNLS complementarity fixed point of a ring operator under a
gap and a load (:mod:`.solve`)."""
from .solve import ContactOptions, ContactSolution, solve_contact

__all__ = ["ContactOptions", "ContactSolution", "solve_contact"]
