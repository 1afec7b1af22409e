"""A bearing from a case file (``vjax-bearing``): units (:mod:`.case_units`), the TOML tables
and their checks (:mod:`.case_table`), the case (:mod:`.case`), its sweep of vjax scenes
(:mod:`.run`) and its outputs (:mod:`.output`)."""
