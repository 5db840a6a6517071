"""No memory growth over 1e5 calls of every kind (the result arrays own the library's buffers;
the namedtuple types and the shapes' caches are made once)."""
import gc
import os

import numpy as np
import pytest

import fcl_superellipsoid as fse


def resident_kib():
    with open("/proc/self/status") as status:
        for line in status:
            if line.startswith("VmRSS:"):
                return int(line.split()[1])
    raise RuntimeError("no VmRSS in /proc/self/status")


@pytest.mark.skipif("LD_PRELOAD" in os.environ and "asan" in os.environ["LD_PRELOAD"],
                    reason="AddressSanitizer's quarantine holds freed memory back; the Release "
                           "build checks growth")
def test_no_growth_over_1e5_calls():
    shape = fse.Superellipsoid((3.5, 3.0, 2.0), (0.4, 0.3))
    box = fse.Box(1.0, 1.0, 1.0)
    pose = (np.eye(3), np.array([3.0, 0.5, 0.2]))
    rng = np.random.default_rng(51)
    points = rng.uniform(-5, 5, size=(16, 3))
    points32 = points.astype(np.float32)

    def calls(n):
        for i in range(n):
            k = i % 6
            if k == 0:
                shape.signed_distance(points[i % 16])
            elif k == 1:
                shape.closest_points(points)
            elif k == 2:
                shape.closest_points(points32)
            elif k == 3:
                shape.within_margin(points, 0.5)
            elif k == 4:
                fse.distance(shape, None, box, pose)
            else:
                fse.collide(shape, None, box, pose)
                try:
                    shape.signed_distance(np.array([np.nan, 0.0, 0.0]))
                except ValueError:
                    pass

    calls(20000)  # warm up: allocator pools, caches
    gc.collect()
    before = resident_kib()
    calls(100000)
    gc.collect()
    growth = resident_kib() - before
    assert growth < 2048, f"resident memory grew by {growth} KiB over 1e5 calls"
