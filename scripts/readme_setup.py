"""The two set-up commands of the README, for .ci/run.

``python scripts/readme_setup.py main`` prints the main-job command and ``test`` the
test command, exactly as the README's "Set-up on a fresh machine" block writes them
(the first and second command lines of its first fenced block), so CI runs what a
newcomer copies and the two can never drift apart.  ``output`` prints the image the
main-job command writes (its ``-o``/``--out`` argument).
"""

from __future__ import annotations

import pathlib
import re
import sys

README = pathlib.Path(__file__).resolve().parents[1] / "README.md"


def setup_commands(text: str) -> list[str]:
    """Command lines of the first fenced block after the set-up heading."""
    head = re.search(r"^## Set-up on a fresh machine\s*$", text, re.MULTILINE)
    if head is None:
        raise SystemExit("README.md: no '## Set-up on a fresh machine' section")
    block = re.search(r"^```[^\n]*\n(.*?)^```", text[head.end():], re.MULTILINE | re.DOTALL)
    if block is None:
        raise SystemExit("README.md: the set-up section has no fenced command block")
    lines = [ln.strip() for ln in block.group(1).splitlines()]
    cmds = [ln[2:] if ln.startswith("$ ") else ln for ln in lines if ln and not ln.startswith("#")]
    if len(cmds) < 2:
        raise SystemExit("README.md: the set-up block needs two commands (main job, tests)")
    return cmds


def main(argv: list[str]) -> int:
    what = argv[1] if len(argv) > 1 else ""
    cmds = setup_commands(README.read_text())
    if what == "main":
        print(cmds[0])
    elif what == "test":
        print(cmds[1])
    elif what == "output":
        m = re.search(r"(?:-o|--out)[ =](\S+)", cmds[0])
        if m is None:
            raise SystemExit("README.md: the main-job command names no output (-o/--out)")
        print(m.group(1))
    else:
        raise SystemExit("usage: readme_setup.py main|test|output")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
