"""vjax.sweep on JAX's distributed runtime: two processes on 127.0.0.1 (gloo collectives on
CPU), launched by experiments/benchmarks/distributed_sweep.py, against one process; and a process that
dies mid-run stops the run with a message naming it, without a result file."""
import pytest

from experiments.benchmarks import distributed_sweep


@pytest.mark.slow
def test_two_processes_equal_one(tmp_path):
    res = distributed_sweep.main(processes=2, points=12, n=64, out_dir=tmp_path)
    assert res["max_difference"] <= 1e-12
    assert [r["process"] for r in res["multi"]] == [0, 1]
    assert all(r["processes"] == 2 and r["devices"] == 2 and r["points"] == 12 for r in res["multi"])
    assert (tmp_path / "distributed_sweep.npz").exists()
    assert "points/s" in (tmp_path / "distributed_sweep.txt").read_text()


def test_a_dying_process_stops_the_run(tmp_path):
    result = tmp_path / "result.npz"
    with pytest.raises(RuntimeError, match="process 1 of 2 exited with code 3"):
        distributed_sweep.launch(2, 8, 64, str(result), timeout=300, die=1)
    assert not result.exists()
