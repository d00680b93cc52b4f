"""pytest-benchmark suite for the core pipeline (issue 2, deliverable 9).

Run with ``python -m pytest bench --benchmark-enable``.  Each workload sits beside
a loop that only touches the same memory, measured in the same run: the ratio of
the two, not the absolute time, is the figure to compare across machines.
"""

import pytest
import scenes

WORKLOADS = {
    "zstencil_fill": scenes.zstencil_fill,
    "touch_zstencil": scenes.touch_zstencil_run,
    "colour_blend_fill": scenes.colour_blend_fill,
    "touch_colour": scenes.touch_colour_run,
    "small_triangles": scenes.small_triangles,
}


@pytest.mark.parametrize("name", list(WORKLOADS))
def test_workload(benchmark, name):
    run, units = WORKLOADS[name]()
    run()  # compile / warm caches outside the timed region
    benchmark.extra_info["units_per_call"] = units
    benchmark.pedantic(run, rounds=5, iterations=1)
