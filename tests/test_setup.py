"""What a newcomer's fresh machine relies on: the README's two set-up commands and
declared dependencies.

.ci/run runs the README's commands in a brand-new virtual environment; these tests
keep the pieces it relies on honest on every test run: the commands parse out of the
README, the main job names the image it writes, and every third-party module the
package imports at module level is declared in pyproject.toml (a machine that happens
to have it installed would otherwise hide the gap).
"""

from __future__ import annotations

import ast
import importlib.util
import pathlib
import re
import sys

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[1]

tomllib = pytest.importorskip("tomllib") if sys.version_info >= (3, 11) else None


def _readme_setup():
    spec = importlib.util.spec_from_file_location("readme_setup",
                                                  ROOT / "scripts" / "readme_setup.py")
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


def test_readme_block_gives_main_job_and_test_command():
    cmds = _readme_setup().setup_commands((ROOT / "README.md").read_text())
    main, test = cmds[0], cmds[1]
    assert main.startswith("pip install . && vgxsim ")
    assert re.search(r"(?:-o|--out)[ =]\S+\.png", main)
    assert test == "bash scripts/test.sh"
    ci = (ROOT / ".ci" / "run").read_text()
    assert "readme_setup.py main" in ci and "readme_setup.py test" in ci
    assert "python3 -m venv" in ci and "--system-site-packages" not in ci


def test_setup_parser_rejects_readme_without_block():
    mod = _readme_setup()
    with pytest.raises(SystemExit, match="no '## Set-up"):
        mod.setup_commands("# vgxsim\n")
    with pytest.raises(SystemExit, match="two commands"):
        mod.setup_commands("## Set-up on a fresh machine\n\n```\npip install .\n```\n")
    assert mod.setup_commands(
        "## Set-up on a fresh machine\n```\n$ a -o x.png\n# note\nb\n```\n") == [
        "a -o x.png", "b"]


# Import names whose distribution is spelled differently on PyPI.
_DIST = {"PIL": "pillow", "OpenGL": "pyopengl", "yaml": "pyyaml", "skimage": "scikit-image",
         "pygame": "pygame-ce"}


# Optional packages: their modules may import what their extra declares (and nothing
# else imports them at module level, so the core runs without it).
_OPTIONAL = {"vgxsim/window": "window"}


def _declared(extra: str | None = None) -> set[str]:
    if tomllib is None:
        pytest.skip("tomllib needs Python 3.11")
    proj = tomllib.loads((ROOT / "pyproject.toml").read_text())["project"]
    deps = list(proj["dependencies"])
    if extra is not None:
        deps += proj["optional-dependencies"][extra]
    names = set()
    for dep in deps:
        names.add(re.split(r"[<>=!~\[; ]", dep, maxsplit=1)[0].strip().lower())
    return {n.replace("_", "-") for n in names}


def test_module_level_imports_are_declared():
    stdlib = set(sys.stdlib_module_names)
    missing = []
    for folder in ("vgxsim", "kernels"):
        for path in (ROOT / folder).rglob("*.py"):
            rel = path.relative_to(ROOT).as_posix()
            declared = _declared(next((extra for pkg, extra in _OPTIONAL.items()
                                       if rel.startswith(pkg + "/")), None))
            for node in ast.parse(path.read_text()).body:
                if isinstance(node, ast.Import):
                    mods = [a.name.split(".")[0] for a in node.names]
                elif isinstance(node, ast.ImportFrom) and node.level == 0 and node.module:
                    mods = [node.module.split(".")[0]]
                else:
                    continue
                for mod in mods:
                    if mod in stdlib or mod in ("vgxsim", "__future__"):
                        continue
                    if _DIST.get(mod, mod).lower().replace("_", "-") not in declared:
                        missing.append(f"{path.relative_to(ROOT)}: {mod}")
    assert missing == []


def test_trimesh_graph_engine_is_declared():
    # mesh.facets (scene polygons) needs a graph engine; trimesh ships none itself.
    assert {"networkx", "scipy"} & _declared()
