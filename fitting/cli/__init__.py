"""The command-line tools: ``vjax-fit`` (:mod:`.fit`), ``vjax-fit-torque`` (:mod:`.torque`),
``vjax-export`` (:mod:`.export`), ``vjax-bearing`` (:mod:`.bearing`)."""
