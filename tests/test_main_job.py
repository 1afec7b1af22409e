"""The main job's scheduler (experiments/main.py): stages in worker processes, one core each."""
import os
import subprocess
import sys
from pathlib import Path

import pytest

from experiments import main as main_job


def test_a_stage_that_raises_stops_the_job_with_its_error(tmp_path):
    # in a worker process (jobs=2): the error comes back, and the pools close (no hang)
    with pytest.raises(ValueError, match="no stage 'missing'"):
        main_job._run_stages(["missing"], tmp_path, True, 2, cache=False)


@pytest.mark.slow     # ~4 s of two worker processes beside the suite's; the main job itself runs every stage
def test_two_stages_side_by_side_pass_their_checks(tmp_path):
    # two workers (calibration without XLA flags, foundation with them), each on a core of its own
    status = main_job.main(["--quick", "--only", "calibration", "foundation", "--jobs", "2", "--no-cache",
                            "--out", str(tmp_path)])
    assert status == 0
    rows = [line for line in (tmp_path / "summary.md").read_text().splitlines() if line.endswith(("| PASS |", "| FAIL |"))]
    assert {r.split("|")[1].strip() for r in rows} == {"calibration", "foundation"}
    assert all(r.endswith("| PASS |") for r in rows)


@pytest.mark.skipif(not hasattr(os, "sched_getaffinity"), reason="Linux only")
def test_pin_to_core_puts_a_process_on_one_core_only_when_there_are_enough():
    # in a child process: pinning this one would pin the rest of the suite
    code = ("import os; from experiments import _common; "
            "many = _common.pin_to_core(0, 10**6); before = len(os.sched_getaffinity(0)); "
            "one = _common.pin_to_core(1, 1); print(many, before, one, len(os.sched_getaffinity(0)))")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True,
                         cwd=Path(__file__).resolve().parents[1]).stdout.split()
    assert out[0] == "False" and int(out[1]) == len(os.sched_getaffinity(0))
    assert out[2] == "True" and out[3] == "1"
