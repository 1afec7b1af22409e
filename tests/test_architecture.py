"""The layout's rules (tools/architecture.py), for vjax's layers and fitting's rooms: no import
circle, no private name used outside its folder, each layer importing only those below it,
files of at most 500 lines, fitting on vjax's public names only, and the drawings in
docs/architecture.md current."""
import importlib.util
import pathlib

ROOT = pathlib.Path(__file__).resolve().parents[1]
spec = importlib.util.spec_from_file_location("architecture", ROOT / "tools" / "architecture.py")
architecture = importlib.util.module_from_spec(spec)
spec.loader.exec_module(architecture)


def test_the_layout_keeps_its_rules():
    assert architecture.violations() == []
    assert architecture.violations(architecture.FITTING) == []


def test_the_drawing_is_current():
    text = architecture.DOC.read_text()
    stale = "docs/architecture.md is stale: run python tools/architecture.py --write"
    assert architecture.section() in text, stale
    assert architecture.fitting_section() in text, stale


def test_a_long_file_is_named_only_while_it_is_long():
    # the named debts are real: a file split below the limit leaves the list
    for path in architecture.TOO_LONG:
        assert (architecture.ROOT / path).read_text().count("\n") > architecture.MAX_LINES, path


def test_a_circle_is_found():
    edges = {"a": {"b"}, "b": {"c"}, "c": {"a"}, "d": {"a"}}
    assert architecture.cycles(edges) == [["a", "b", "c"]]
    assert architecture.cycles({"a": {"b"}, "b": set()}) == []


def test_a_private_name_across_folders_is_found(tmp_path, monkeypatch):
    """A module of a scene that uses a private name of the films' folder breaks the rule."""
    package = tmp_path / "vjax"
    (package / "films").mkdir(parents=True)
    (package / "scenes").mkdir()
    for init in (package, package / "films", package / "scenes"):
        (init / "__init__.py").write_text("")
    (package / "films" / "film.py").write_text("def _secret():\n    return 1\n")
    (package / "scenes" / "scene.py").write_text("from ..films import film\nx = film._secret()\n")
    monkeypatch.setattr(architecture, "ROOT", tmp_path)
    monkeypatch.setattr(architecture, "PACKAGE", package)
    found = architecture.violations()
    assert len(found) == 1 and "private name _secret" in found[0], found


def test_fitting_beyond_vjax_public_names_is_found(tmp_path, monkeypatch):
    """A fitting room that imports vjax's private core, or a module inside a layer, breaks the rule."""
    package = tmp_path / "fitting"
    (package / "shared").mkdir(parents=True)
    for init in (package, package / "shared"):
        (init / "__init__.py").write_text("")
    (package / "shared" / "cache.py").write_text("from vjax._core.cache import default_cache_dir\n"
                                                "from vjax.materials.lubricant import Lubricant\n"
                                                "from vjax import Material\nfrom vjax.materials import KELVIN\n")
    monkeypatch.setattr(architecture, "ROOT", tmp_path)
    monkeypatch.setattr(architecture, "FITTING", package)
    found = architecture.violations(package)
    assert len(found) == 2 and all("beyond its public names" in f for f in found), found
