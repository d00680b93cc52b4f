"""docs/api_coverage.md stays in step with what vgxsim.gl exports."""

import re
from pathlib import Path

import vgxsim.gl as gl

DOC = Path(__file__).resolve().parents[1] / "docs" / "api_coverage.md"
ROW = re.compile(r"^\| `(\w+)` \| (yes|no) \|(.*)\|\s*$")


def rows() -> list[tuple[str, str, str]]:
    out = []
    for line in DOC.read_text(encoding="utf-8").splitlines():
        m = ROW.match(line)
        if m:
            out.append((m.group(1), m.group(2), m.group(3).strip()))
    return out


def exported() -> set[str]:
    return {n for n in dir(gl) if callable(getattr(gl, n)) and hasattr(getattr(gl, n),
                                                                         "gl_record")}


def test_every_call_is_listed_once():
    names = [n for n, _, _ in rows()]
    assert len(names) > 500
    assert len(names) == len(set(names)), sorted(n for n in set(names) if names.count(n) > 1)


def test_implemented_rows_match_the_exports():
    listed_yes = {n for n, s, _ in rows() if s == "yes"}
    have = exported()
    assert have - listed_yes == set(), "exported but not listed as implemented"
    assert listed_yes - have == set(), "listed as implemented but not exported"


def test_left_out_calls_say_why_and_really_are_absent():
    for name, status, why in rows():
        if status == "no":
            assert why, name
            assert not callable(getattr(gl, name, None)), f"{name} exists now: mark it yes"


def test_totals_line_matches_the_table():
    text = DOC.read_text(encoding="utf-8")
    m = re.search(r"Totals: (\d+) entry points; vgxsim implements (\d+), (\d+) are left out",
                  text)
    assert m, "the totals line is missing"
    r = rows()
    yes = sum(1 for _, s, _ in r if s == "yes")
    assert (int(m.group(1)), int(m.group(2)), int(m.group(3))) == (len(r), yes, len(r) - yes)
