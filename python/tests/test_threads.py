"""Concurrent calls from a Python thread pool: the GIL is released inside the queries, the
answers are those of serial calls, and nothing deadlocks."""
from concurrent.futures import ThreadPoolExecutor

import numpy as np

import fcl_superellipsoid as fse


def test_concurrent_calls_give_the_serial_answers():
    shapes = [fse.Superellipsoid((3.5, 3.0, 2.0), (0.4, 0.3)),
              fse.Superellipsoid((1.0, 2.0, 4.0), (0.1, 1.9))]
    rng = np.random.default_rng(41)
    work = []
    for k in range(48):
        points = rng.uniform(-6, 6, size=(int(rng.integers(1, 5000)), 3))
        if k % 3 == 1:
            points = points.astype(np.float32)
        work.append((shapes[k % 2], points, k % 4))

    def run(item):
        shape, points, kind = item
        if kind == 0:
            return (shape.signed_distance(points),)
        if kind == 1:
            return tuple(shape.closest_points(points))
        if kind == 2:
            return tuple(shape.within_margin(points, 0.3))
        return (fse.distance(shape, None, fse.Box(1, 1, 1), (np.eye(3), points[0])).distance,
                shape.signed_distance(points[0]))

    serial = [run(item) for item in work]
    with ThreadPoolExecutor(max_workers=8) as pool:
        for _ in range(3):
            futures = [pool.submit(run, item) for item in work]
            concurrent = [f.result(timeout=120) for f in futures]
            for a, b in zip(concurrent, serial):
                for x, y in zip(a, b):
                    np.testing.assert_array_equal(x, y)


def test_a_new_shapes_float_copy_is_made_once_under_threads():
    shape = fse.Superellipsoid((2.0, 1.0, 0.5), (1.7, 0.1))
    points = np.random.default_rng(42).uniform(-3, 3, size=(2000, 3)).astype(np.float32)
    with ThreadPoolExecutor(max_workers=8) as pool:
        answers = list(pool.map(lambda _: shape.signed_distance(points), range(16)))
    for a in answers[1:]:
        np.testing.assert_array_equal(a, answers[0])
