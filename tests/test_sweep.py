"""vjax.sweep: chunked, sharded vmap against a plain loop; padding; 2 simulated devices."""
import os
import subprocess
import sys
import textwrap
from pathlib import Path

import jax
import jax.numpy as jnp
import numpy as np
import pytest

import vjax
from vjax.sweep import SweepInfo, batch_size, sweep

ROOT = Path(__file__).resolve().parents[1]


def _fn(p):
    # a PyTree in, a PyTree out, with a non-trivial per-point computation
    x = p["x"]
    return {"s": jnp.sum(jnp.sin(x * p["a"])), "v": x * p["a"] ** 2, "n": jnp.linalg.norm(x)}


def _params(B, seed=0):
    rng = np.random.default_rng(seed)
    return {"x": rng.normal(size=(B, 3)), "a": rng.uniform(0.5, 2.0, size=B)}


def _loop(params):
    B = batch_size(params)
    rows = [_fn(jax.tree_util.tree_map(lambda a: a[i], params)) for i in range(B)]
    return jax.tree_util.tree_map(lambda *xs: np.stack([np.asarray(x) for x in xs]), *rows)


@pytest.mark.parametrize("B,chunk,partition", [(10, 3, "shard_map"), (10, 5, "auto"), (10, 10, "shard_map"),
                                               (10, 64, "shard_map"), (1, 4, "auto"), (7, 1, "shard_map")])
def test_matches_loop(B, chunk, partition):
    params = _params(B)
    out, info = sweep(_fn, params, chunk_size=chunk, progress=False, return_info=True, partition=partition)
    ref = _loop(params)
    for k in ref:
        assert out[k].shape == ref[k].shape
        np.testing.assert_allclose(out[k], ref[k], rtol=1e-13, atol=1e-14)
    assert isinstance(info, SweepInfo)
    assert info.points == B
    assert info.chunk_size % info.devices == 0
    assert info.chunks * info.chunk_size - info.padded == B
    assert info.chunks == -(-B // info.chunk_size)


def test_padding_uses_valid_points():
    # a function that fails loudly (NaN) at zero parameters: padding must not feed zeros
    f = lambda p: jnp.log(p)
    out, info = sweep(f, jnp.arange(1.0, 8.0), chunk_size=4, progress=False, return_info=True)
    assert info.padded == 1 and info.chunks == 2
    np.testing.assert_allclose(out, np.log(np.arange(1.0, 8.0)), rtol=1e-15)


def test_progress_bar_and_memory(capsys):
    out, info = sweep(lambda p: p * 2.0, jnp.arange(6.0), chunk_size=2, desc="demo", return_info=True)
    err = capsys.readouterr().err
    assert "demo" in err and "3/3 chunks" in err
    np.testing.assert_allclose(out, 2.0 * np.arange(6.0))
    if info.memory is not None:
        assert info.memory["argument"] >= 2 * 8 and info.memory["total"] >= info.memory["argument"]


def test_bad_input():
    with pytest.raises(ValueError, match="different leading"):
        sweep(_fn, {"x": np.ones((3, 3)), "a": np.ones(4)}, progress=False)
    with pytest.raises(ValueError, match="scalar leaf"):
        sweep(_fn, {"x": np.ones((3, 3)), "a": 1.0}, progress=False)
    with pytest.raises(ValueError, match="partition"):
        sweep(_fn, _params(3), progress=False, partition="pmap")
    with pytest.raises(ValueError, match="chunk_size"):
        sweep(_fn, _params(3), chunk_size=0, progress=False)


def test_scene_sweep_matches_vmap():
    # a real scene: pin-in-hole torque over speed and load, the same as a plain vmap
    m = vjax.Material.sls(1e6, 1e7, 0.01, 0.5)

    def torque(p):
        r = vjax.pin_in_hole(m, 0.08, 0.005, p["load"], omega_shaft=p["omega"], options=vjax.PinOptions(n=64),
                             throw=False)
        return {"torque": r.torque, "converged": r.converged}

    params = {"omega": jnp.linspace(1.0, 300.0, 5), "load": jnp.linspace(2000.0, 3000.0, 5)}
    out = sweep(torque, params, chunk_size=2, progress=False)
    ref = jax.vmap(torque)(params)
    assert out["converged"].all()
    np.testing.assert_allclose(out["torque"], np.asarray(ref["torque"]), rtol=1e-10)


def test_two_simulated_devices():
    code = textwrap.dedent("""
        import jax
        jax.config.update("jax_enable_x64", True)
        import jax.numpy as jnp, numpy as np
        from vjax.sweep import sweep
        assert len(jax.devices()) == 2, jax.devices()
        def f(p):
            return {"y": jnp.sin(p["x"]) * p["a"], "z": jnp.sum(p["x"] ** 2) * jnp.ones(2)}
        x = np.linspace(0, 1, 33)
        p = {"x": np.stack([x, x + 1], axis=1), "a": np.arange(33.0)}
        for part in ("shard_map", "auto"):
            out, info = sweep(f, p, chunk_size=5, progress=False, return_info=True, partition=part)
            assert info.devices == 2 and info.chunk_size == 6 and info.chunks == 6 and info.padded == 3, info
            np.testing.assert_allclose(out["y"], np.sin(p["x"]) * p["a"][:, None], rtol=1e-14)
            np.testing.assert_allclose(out["z"], np.repeat((p["x"] ** 2).sum(1)[:, None], 2, 1), rtol=1e-14)
        # each device computes its own block: a per-device count through shard_map's axis index
        out = sweep(lambda q: q * 0 + jax.lax.axis_index("batch"), np.arange(8.0), progress=False)
        assert out.tolist() == [0, 0, 0, 0, 1, 1, 1, 1], out
        print("OK", info.devices)
    """)
    env = dict(os.environ, XLA_FLAGS="--xla_force_host_platform_device_count=2", JAX_PLATFORMS="cpu",
               PYTHONPATH=str(ROOT))
    r = subprocess.run([sys.executable, "-c", code], env=env, capture_output=True, text=True, timeout=120)
    assert r.returncode == 0, r.stderr[-2000:]
    assert "OK 2" in r.stdout
