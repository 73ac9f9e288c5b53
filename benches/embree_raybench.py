#!/usr/bin/env python3
"""Embree's closest-hit rate on the triangles and rays `raybench --dump DIR` wrote.

Run by hand, not in CI (it needs `pip install embreex`, Embree 4.4's Python binding):

    cargo run --release -p invlight-trace --example raybench -- /tmp/scenes/sponza.obj 1000000 --dump /tmp/rb
    python3 benches/embree_raybench.py /tmp/rb [passes]

embreex casts one `rtcIntersect1` per ray from a Cython loop on the calling thread, so
its rate is one core's, as raybench's "per core" column; the time is this thread's CPU
time (best of the passes), which does not count the time other processes on a shared
machine take the core. The BVH build (Embree's default quality, threaded) is left out.
The binding's loop costs something per ray (it copies each hit into NumPy arrays):
the same rays against one far-away triangle measure it, and the rate less that cost is
printed too, an upper bound of what Embree's own traversal does.
The distances are checked against `Accel`'s (t.f32): the same rays must hit the same
surfaces, or the two rates would not measure the same work.
"""

import sys
import time

import numpy as np
from embreex import rtcore_scene
from embreex.mesh_construction import TriangleMesh


def main():
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    folder = sys.argv[1]
    passes = int(sys.argv[2]) if len(sys.argv) > 2 else 3
    tris = np.fromfile(f"{folder}/tris.f32", dtype="<f4").reshape(-1, 3, 3)
    rays = np.fromfile(f"{folder}/rays.f32", dtype="<f4").reshape(-1, 2, 3)
    ours = np.fromfile(f"{folder}/t.f32", dtype="<f4")
    origins = np.ascontiguousarray(rays[:, 0])
    dirs = np.ascontiguousarray(rays[:, 1])

    scene = rtcore_scene.EmbreeScene()
    TriangleMesh(scene, tris)
    start = time.perf_counter()
    scene.run(origins[:1], dirs[:1])  # commits the scene: builds the BVH
    build = time.perf_counter() - start

    best = 0.0
    for _ in range(passes):
        start = time.thread_time()
        hit = scene.run(origins, dirs, output=1)
        seconds = time.thread_time() - start
        best = max(best, len(rays) / seconds)
    # The binding's own cost per ray: the same rays against one triangle none of them
    # comes near, so Embree's traversal stops at its root.
    far = np.array([[[1e6, 1e6, 1e6], [1e6 + 1, 1e6, 1e6], [1e6, 1e6 + 1, 1e6]]], dtype=np.float32)
    empty = rtcore_scene.EmbreeScene()
    TriangleMesh(empty, far)
    empty.run(origins[:1], dirs[:1])
    floor = 0.0
    for _ in range(passes):
        start = time.thread_time()
        empty.run(origins, dirs, output=1)
        floor = max(floor, len(rays) / (time.thread_time() - start))
    t = np.where(hit["geomID"] >= 0, hit["tfar"], np.inf)
    both = np.isfinite(t) & np.isfinite(ours)
    agree = np.isfinite(t) == np.isfinite(ours)
    close = np.abs(t[both] - ours[both]) <= 1e-4 * np.maximum(1.0, ours[both])
    print(f"{folder}: {len(tris)} triangles, {len(rays)} rays; Embree build {build:.3f} s")
    print(f"Embree rtcIntersect1: {best / 1e6:.2f} M rays/s per core (best of {passes})")
    print(
        f"embreex's loop alone (rays missing one far triangle): {floor / 1e6:.2f} M rays/s; "
        f"less its {1e9 / floor:.0f} ns per ray, Embree traces {1e-6 / (1 / best - 1 / floor):.2f} M rays/s"
    )
    print(
        f"hits {100 * np.isfinite(t).mean():.1f} %; hit/miss as Accel's for "
        f"{100 * agree.mean():.4f} % of rays, the same distance (1e-4 relative) for "
        f"{100 * close.mean():.4f} % of the rays both hit"
    )


if __name__ == "__main__":
    main()
