"""Measurements read from files: DMA exports (:mod:`.dma`, the instruments' tables, their
shared parsing in :mod:`.rawfile`, Netzsch Eplexor .xls in :mod:`.eplexor`) and relaxation
moduli E(t) (:mod:`.relaxation`). numpy only: no JAX."""
