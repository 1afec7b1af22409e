"""vjax has one version string: pyproject.toml's ``version``, which the package metadata carries
once installed, and ``vjax.__version__`` reads (a checkout never installed says "0+unknown")."""
import importlib.metadata
import json
import os
import pathlib
import subprocess
import sys
import tomllib
import urllib.parse

import pytest

import vjax

ROOT = pathlib.Path(__file__).resolve().parents[1]


def _installed_from():
    """The folder the installed vjax was installed from (pip's direct_url.json), or None."""
    text = importlib.metadata.distribution("vjax").read_text("direct_url.json")
    url = json.loads(text).get("url", "") if text else ""
    if not url.startswith("file://"):
        return None
    return pathlib.Path(urllib.parse.unquote(urllib.parse.urlsplit(url).path)).resolve()


def test_version_is_the_package_metadata():
    assert vjax.__version__ == importlib.metadata.version("vjax")
    assert "__version__" in vjax.__all__


def test_installed_version_is_pyprojects():
    version = tomllib.loads((ROOT / "pyproject.toml").read_text())["project"]["version"]
    source = _installed_from()
    if source is not None and source != ROOT:
        pytest.skip(f"the installed vjax is {source}'s, not this checkout's ({ROOT}): its version says nothing here")
    assert vjax.__version__ == version, (
        f"vjax.__version__ is {vjax.__version__!r} but pyproject.toml says {version!r}: the installed metadata is "
        f"stale, reinstall with pip install -e .")


def test_a_checkout_never_installed_says_unknown():
    # the import with the metadata lookup failing as it does where no vjax is installed
    code = ("import importlib.metadata as m\n"
            "def missing(name): raise m.PackageNotFoundError(name)\n"
            "m.version = missing\n"
            "import vjax; print(vjax.__version__)")
    env = dict(os.environ, PYTHONPATH=str(ROOT), JAX_ENABLE_X64="1", JAX_PLATFORMS="cpu")
    out = subprocess.run([sys.executable, "-c", code], env=env, capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "0+unknown"
