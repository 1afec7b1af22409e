"""Drivers of external codes that vjax is compared with. ``ross_peer`` runs ROSS's
``PlainJournal`` on the finite journal bearing's rigid case; it imports neither vjax nor jax and
runs in ROSS's own interpreter (``$VJAX_ROSS_PYTHON experiments/peers/ross_peer.py ...``),
started by ``experiments.studies.journal_finite``.
"""
