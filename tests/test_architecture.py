"""The layout's rules (tools/architecture.py): no import circle, no private name used outside
its folder, each layer importing only those below it, files of at most 500 lines, and the
drawing in docs/architecture.md current."""
import importlib.util
import pathlib

ROOT = pathlib.Path(__file__).resolve().parents[1]
spec = importlib.util.spec_from_file_location("architecture", ROOT / "tools" / "architecture.py")
architecture = importlib.util.module_from_spec(spec)
spec.loader.exec_module(architecture)


def test_the_layout_keeps_its_rules():
    assert architecture.violations() == []


def test_the_drawing_is_current():
    text = architecture.DOC.read_text()
    assert architecture.section() in text, "docs/architecture.md is stale: run python tools/architecture.py --write"


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
