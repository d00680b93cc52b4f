"""vgxsim sweep: the grid, its checks, results equal to direct api.render calls, a
failing point reported while the others finish."""

import csv

import numpy as np
import pytest

from vgxsim.cli import main
from vgxsim.farm import LocalExecutor
from vgxsim.farm.sweep import SweepConfigError, grid_points, load_config, run_sweep

CONFIG = """
[sweep]
name = "tiny"

[grid]
scene = ["cubes", "balls"]
size = [[20, 16]]
mode = ["shadows", "objects"]
subpixel = [false, true]
soft = [0, 2]

[fixed]
seed = 5
"""


@pytest.fixture()
def config(tmp_path):
    path = tmp_path / "tiny.toml"
    path.write_text(CONFIG)
    return load_config(path)


def test_grid_is_the_product_of_the_axes(config):
    points = grid_points(config)
    assert len(points) == 2 * 1 * 2 * 2 * 2
    assert points[0].scene == "cubes" and points[-1].scene == "balls"
    assert points[0].settings == {"seed": 5, "size": (20, 16), "mode": "shadows",
                                  "subpixel": False, "soft": 0}
    assert points[-1].settings["soft"] == 2 and points[-1].settings["subpixel"] is True


def test_unknown_keyword_is_refused_with_file_and_line(tmp_path):
    path = tmp_path / "bad.toml"
    path.write_text('[grid]\nscene = ["cubes"]\ntechnique_x = ["a"]\n')
    with pytest.raises(SweepConfigError, match=r"bad\.toml:3: grid\.technique_x is not a "
                                               r"keyword"):
        load_config(path)
    path.write_text('[grid]\nmode = "shadows"\n')
    with pytest.raises(SweepConfigError, match=r"bad\.toml:2: grid\.mode must be a non-empty"):
        load_config(path)


def test_sweep_on_two_workers_equals_direct_renders(config, threads_cluster, reference):
    report = run_sweep(config, threads_cluster, keep=True)
    assert not report.failed
    from vgxsim.shadow import api

    scenes = {n: api.load_scene(n) for n in config.scenes}
    for row in report.rows:
        ref = reference(scenes[row.point.scene], **row.point.settings)
        assert np.array_equal(row.result.value["colour"], ref.colour), row.point
        assert np.array_equal(row.result.value["depth"], ref.depth), row.point
        assert row.result.timing.worker in threads_cluster.workers
    # warmed before timing: no task compiled anything
    assert all(r.result.timing.compile_s == 0.0 for r in report.rows)
    assert set(report.warm_up_s) == set(threads_cluster.workers)
    local = run_sweep(config, LocalExecutor())
    assert [r.colour_sha256 for r in local.rows] == [r.colour_sha256 for r in report.rows]
    assert [r.depth_sha256 for r in local.rows] == [r.depth_sha256 for r in report.rows]


def test_failing_point_is_reported_and_the_sweep_goes_on(tmp_path, threads_cluster):
    path = tmp_path / "fail.toml"
    path.write_text('[grid]\nscene = ["cubes"]\nsize = [[16, 12]]\nlight = [0, 7, 1]\n')
    report = run_sweep(load_config(path), threads_cluster)
    assert [r.point.settings["light"] for r in report.failed] == [7]
    assert "light must be 0..1, not 7" in report.failed[0].result.error
    assert all(r.colour_sha256 for r in report.rows if r.point.settings["light"] != 7)


def test_cli_sweep_writes_report_and_exit_status(tmp_path, capsys):
    path = tmp_path / "cli.toml"
    path.write_text('[sweep]\noutput = "png"\n[grid]\nscene = ["cubes"]\nsize = [[16, 12]]\n'
                    'light = [0, 9]\n')
    assert main(["sweep", str(path), "--local"]) == 1
    err = capsys.readouterr().err
    assert "point 1 failed (scene cubes, settings {'size': (16, 12), 'light': 9})" in err
    with open(tmp_path / "cli-report.csv") as fh:
        rows = list(csv.DictReader(fh))
    assert [r["light"] for r in rows] == ["0", "9"]
    assert rows[0]["error"] == "" and "light must be" in rows[1]["error"]
    assert rows[0]["worker"] == "in-process"
    md = (tmp_path / "cli-report.md").read_text()
    assert "## Point 1 failed: scene cubes" in md and "Traceback" in md
    assert len(list((tmp_path / "png").glob("*.png"))) == 1


def test_cli_sweep_bad_config_exit_2(tmp_path, capsys):
    path = tmp_path / "x.toml"
    path.write_text("[grid\n")
    assert main(["sweep", str(path), "--local"]) == 2
    assert "x.toml" in capsys.readouterr().err


def test_example_config_parses_and_uses_existing_axes(tmp_path, capsys):
    assert main(["sweep", "--example"]) == 0
    path = tmp_path / "ex.toml"
    path.write_text(capsys.readouterr().out)
    cfg = load_config(path)
    assert set(cfg.axes) == {"size", "mode", "subpixel", "soft"}
