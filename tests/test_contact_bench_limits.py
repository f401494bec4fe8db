"""The contact benchmark's limits: it refuses, before any work, what the machine's memory
cannot hold (the peers' maps, the free 4096 x 4096 solve of ``--big``: its bytes a pixel
times the pixels, not less), and its verdict counts a target reached exactly as met."""
from __future__ import annotations

import pytest

from asperity import resources
from asperity.contact import bench
from asperity.errors import ResourceError


def no_work(*args, **kwargs):
    raise AssertionError("the benchmark started work it should have refused")


@pytest.fixture
def memory(monkeypatch):
    """Free memory set by the test; any map or child solve fails the test."""
    monkeypatch.setattr(bench, "self_affine", no_work)
    monkeypatch.setattr(bench, "_child", no_work)

    def set_free(nbytes):
        monkeypatch.setattr(resources, "available_memory", lambda: int(nbytes))
    return set_free


def test_big_solve_needs_its_bytes_per_pixel_times_the_pixels(memory):
    need = bench.TARGETS["bytes_per_pixel_free"] * bench.BIG ** 2
    memory(need / resources.MEMORY_SHARE * 0.9)          # 10 % short of the solve alone
    with pytest.raises(ResourceError, match=f"free {bench.BIG} x {bench.BIG}"):
        bench.bench_contact(n=64, free_n=64, big=True, peers=())


def test_peer_maps_need_their_bytes_per_pixel(memory):
    n = 2048
    memory(bench.PEER_BYTES_PER_PIXEL * n * n / resources.MEMORY_SHARE * 0.9)
    with pytest.raises(ResourceError, match=f"{n} x {n} maps"):
        bench.bench_contact(n=n, free_n=64, peers=())


def test_verdict_counts_a_target_reached_exactly_as_met():
    T = bench.TARGETS
    row = {"seconds": 1.0, "bytes_per_pixel": T["bytes_per_pixel_free"]}
    out = {"cases": {
        "periodic": {"asperity": {"seconds": 1.0, "bytes_per_pixel":
                                  T["bytes_per_pixel_periodic"]},
                     "contactmechanics": {"seconds": T["speedup_vs_contactmechanics"]},
                     "plain": {"seconds": T["speedup_vs_plain"]}},
        "free": {"asperity": dict(row), "plain": {"seconds": 0.999 * T["speedup_vs_plain"]}},
        f"free {bench.BIG}": {"asperity": dict(row, bytes_per_pixel=1.001 * row[
            "bytes_per_pixel"])},
        "periodic curve": {"asperity": {"seconds": T["curve_in_single_solves"]}}}}
    v = bench.verdict(out)
    assert v["periodic speedup_vs_contactmechanics"]["met"] is True
    assert v["periodic speedup_vs_plain"]["met"] is True
    assert v["free speedup_vs_plain"]["met"] is False
    assert v["free speedup_vs_contactmechanics"]["met"] is None        # not measured
    assert v["periodic bytes_per_pixel"]["met"] is True
    assert v["free bytes_per_pixel"]["met"] is True
    assert v[f"free {bench.BIG} bytes_per_pixel"]["met"] is False
    assert v["load curve in single solves"]["met"] is True
    assert v["load curve in single solves"]["value"] == T["curve_in_single_solves"]
