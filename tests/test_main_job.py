"""The main job's scheduler (experiments/main.py): stages in worker processes, one core each."""
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
