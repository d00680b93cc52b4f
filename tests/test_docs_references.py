"""What the documentation names in backticks exists, so a doc cannot go stale silently.

Two kinds of reference are checked, in inline code spans (text between single backticks)
outside fenced code blocks:

* a repository path, ``vgxsim/gl/_core.py`` or ``tests/conformance/``: a file (or a
  folder, written with a trailing slash) under the repository root, or under
  ``vgxsim/`` (pages that speak of the package write ``gl/_window.py``);
* a dotted name starting with ``vgxsim.``, ``vgxsim.pipeline.records.DrawState``: the
  longest importable module prefix is imported and the rest is looked up with
  ``getattr`` (so class attributes and methods count, instance attributes set in
  ``__init__`` do not -- write those without the ``vgxsim.`` prefix).

Anything else in backticks (``v3f``, ``stencil(TRUE, ref, SF_EQUAL, ...)``,
``ctx.stream``, file names without a folder) is prose and is not checked.
Paths under ``shared/`` (the project's reference notes, outside the repository) are
not checked either.
"""

from __future__ import annotations

import importlib
import re
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
#: The documents checked: every page of docs/ and the README.
DOCUMENTS = sorted((ROOT / "docs").glob("*.md")) + [ROOT / "README.md"]

_FENCE = re.compile(r"^```.*?^```[^\n]*$", re.M | re.S)
_SPAN = re.compile(r"`([^`\n]+)`")
_SEGMENT = r"[A-Za-z0-9_][A-Za-z0-9_.-]*"
#: A relative path with at least one folder: a file with a known suffix, or a folder
#: written with a trailing slash.
_PATH = re.compile(rf"^(?:{_SEGMENT}/)+(?:{_SEGMENT}\.(?:py|md|toml|sh|txt|json|cfg)|)$")
#: A dotted Python name in the vgxsim package.
_NAME = re.compile(r"^vgxsim(?:\.[A-Za-z_][A-Za-z0-9_]*)+$")
_UNCHECKED_PREFIXES = ("shared/",)


def references(text: str) -> tuple[list[str], list[str]]:
    """(paths, dotted names) written in the inline code spans of a Markdown text."""
    text = _FENCE.sub("", text)
    paths, names = [], []
    for span in _SPAN.findall(text):
        span = span.strip()
        if _PATH.match(span) and not span.startswith(_UNCHECKED_PREFIXES):
            paths.append(span)
        elif _NAME.match(span):
            names.append(span)
    return paths, names


def resolve(name: str) -> object:
    """The object a dotted name denotes; AttributeError or ImportError if none."""
    parts = name.split(".")
    for cut in range(len(parts), 0, -1):
        module_name = ".".join(parts[:cut])
        try:
            obj = importlib.import_module(module_name)
        except ModuleNotFoundError as exc:
            # Only "this prefix is not a module" moves on to a shorter prefix; a
            # module that exists but fails to import is an error of its own.
            if exc.name is not None and module_name.startswith(exc.name) and (
                    module_name == exc.name or module_name.startswith(exc.name + ".")):
                continue
            raise
        for attr in parts[cut:]:
            obj = getattr(obj, attr)
        return obj
    raise ImportError(name)


def _cases(kind: int) -> list:
    out = []
    for doc in DOCUMENTS:
        for ref in dict.fromkeys(references(doc.read_text(encoding="utf-8"))[kind]):
            out.append(pytest.param(doc, ref, id=f"{doc.name}:{ref}"))
    return out


@pytest.mark.parametrize(("doc", "path"), _cases(0))
def test_path_exists(doc: Path, path: str) -> None:
    bases = (ROOT, ROOT / "vgxsim")
    if path.endswith("/"):
        assert any((b / path).is_dir() for b in bases), (
            f"{doc.name} names the folder {path!r}, which does not exist")
    else:
        assert any((b / path).is_file() for b in bases), (
            f"{doc.name} names the file {path!r}, which does not exist")


@pytest.mark.parametrize(("doc", "name"), _cases(1))
def test_name_exists(doc: Path, name: str) -> None:
    try:
        resolve(name)
    except (ImportError, AttributeError) as exc:
        pytest.fail(f"{doc.name} names {name!r}, which does not exist ({exc})")


def test_architecture_page_is_checked() -> None:
    """The walk of the pipeline names enough files and names for the check to mean
    something (a regex that matched nothing would pass every test above)."""
    paths, names = references((ROOT / "docs" / "architecture.md").read_text(encoding="utf-8"))
    assert len(set(paths)) >= 30
    assert len(set(names)) >= 100


def test_prose_is_not_taken_for_references() -> None:
    text = ("`v3f` `stencil(TRUE, ref, SF_EQUAL, ...)` `ctx.stream` `frame_0000.png` "
            "`p @ mvp` `(H, W) uint32` `vgxsim run PROGRAM.py` `import gl` "
            "`/tmp/x.py` `shared/reference/irisgl_reference.md` `0.27 G/s`\n"
            "```\nvgxsim/not/a/real/file.py\n```\n"
            "`kernels/decode.py` `tests/conformance/` `vgxsim.batch.CommandBatch.flush`")
    paths, names = references(text)
    assert paths == ["kernels/decode.py", "tests/conformance/"]
    assert names == ["vgxsim.batch.CommandBatch.flush"]


def test_missing_references_are_caught() -> None:
    with pytest.raises(AttributeError):
        resolve("vgxsim.batch.CommandBatch.no_such_method")
    with pytest.raises((ImportError, AttributeError)):
        resolve("vgxsim.no_such_module.thing")
    assert resolve("vgxsim.kernels.decode.decode_stream") is not None
