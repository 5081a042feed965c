"""Threads mesh in parallel: the library releases the GIL while it meshes. The same meshes as one
after another, and (the `timing` test, run alone by ctest) in less wall time on two cores."""
import concurrent.futures
import os
import time

import numpy as np
import pytest

import curvemesh

SMALL = ["diffusion-curves", "open-curves", "overlapping-shapes", "transforms-and-use"]


def same(a, b):
    return (
        np.array_equal(a.nodes, b.nodes)
        and np.array_equal(a.triangles, b.triangles)
        and np.array_equal(a.lines, b.lines)
        and np.array_equal(a.line_tags, b.line_tags)
    )


def mesh_all(jobs, threads):
    """Meshes every (source, options) job, with `threads` threads (0: one after another in this
    thread); returns the meshes and the wall time."""
    start = time.perf_counter()
    if threads == 0:
        meshes = [curvemesh.mesh(source, **options) for source, options in jobs]
    else:
        with concurrent.futures.ThreadPoolExecutor(threads) as pool:
            meshes = list(pool.map(lambda job: curvemesh.mesh(job[0], **job[1]), jobs))
    return meshes, time.perf_counter() - start


def test_threads_give_the_same_meshes(examples):
    jobs = [(examples / f"{name}.svg", {}) for name in SMALL]
    jobs += [(examples / f"{name}.svg", {"linear": True}) for name in SMALL]
    one_by_one, _ = mesh_all(jobs, 0)
    threaded, _ = mesh_all(jobs, 4)
    assert all(same(a, b) for a, b in zip(one_by_one, threaded))


def test_meshing_releases_the_gil(examples):
    """While a thread meshes, this thread runs Python: it would wait for the whole meshing if the
    library held the GIL."""
    import threading

    done = threading.Event()
    result = {}

    def work():
        result["mesh"] = curvemesh.mesh(examples / "overlapping-shapes.svg", edge_length=0.01)
        done.set()

    spins, slices = 0, set()
    start = time.perf_counter()
    worker = threading.Thread(target=work)
    worker.start()
    while not done.is_set():
        spins += 1
        slices.add(int((time.perf_counter() - start) * 50))  # which 20 ms slice of the meshing
    worker.join()
    seconds = time.perf_counter() - start
    assert len(result["mesh"].triangles) > 0
    # Python ran in most 20 ms slices of the meshing (with the GIL held: in none but the first).
    assert seconds > 0.1 and len(slices) > 0.5 * seconds * 50, (seconds, len(slices), spins)


def test_errors_in_threads(examples):
    jobs = [(examples / "square-with-hole.svg", {}), ("<svg><path d='M 0 0 L 1 1'/>", {})] * 3
    with concurrent.futures.ThreadPoolExecutor(3) as pool:
        futures = [pool.submit(curvemesh.mesh, source, **options) for source, options in jobs]
    for k, f in enumerate(futures):
        if k % 2:
            assert isinstance(f.exception(), ValueError)
        else:
            assert len(f.result().triangles) > 0


@pytest.mark.timing
def test_four_threads_take_less_wall_time(examples):
    """Four drawings of about 0.7 s each: four threads against one after another, each the best of
    up to three rounds, so that a moment's load elsewhere on the machine does not decide it (ctest
    runs this test alone: RUN_SERIAL)."""
    cores = len(os.sched_getaffinity(0))
    if cores < 2:
        pytest.skip("one core: threads cannot run in parallel")
    jobs = [(examples / f"{name}.svg", {"edge_length": 0.008}) for name in SMALL]
    curvemesh.mesh(examples / "square-with-hole.svg")  # warm up: the library loaded and ready
    sequential, threaded = [], []
    for _ in range(3):
        reference, seconds = mesh_all(jobs, 0)
        sequential.append(seconds)
        meshes, seconds = mesh_all(jobs, 4)
        threaded.append(seconds)
        assert all(same(a, b) for a, b in zip(reference, meshes))
        if min(threaded) < 0.8 * min(sequential):
            break
    ratio = min(threaded) / min(sequential)
    print(
        f"\none after another {min(sequential):.2f} s, four threads {min(threaded):.2f} s on {cores} cores "
        f"(best of {len(threaded)}): ratio {ratio:.2f}, speed-up {1 / ratio:.2f}x; "
        f"load average {os.getloadavg()[0]:.1f}"
    )
    assert ratio < 0.8
