#!/usr/bin/env python3
"""The reference course loop in Mitsuba 3: the straw-in-a-glass course pictures of `bentstraw bench`.

usage: mitsuba_course.py [--threads N] [--repeat R] [--loop symbolic|evaluated|compressed]
                         [--hit preliminary|full] [--view 1|2|3|4 ...]
                         [--check BENTSTRAW]

Needs Mitsuba 3 and Dr.Jit (pip install mitsuba drjit; tried with mitsuba 3.9.1, drjit 1.5.0) and
libLLVM 16 or newer (tried with 19.1.7) for the vectorised CPU backend. For each of the four zoomed
views that `bentstraw bench` times (1024x768, 50 degrees) it traces one ray per pixel centre by the
course's law (nearest face; the straw ends the ray with its section's code; a water face refracts,
or reflects totally; at most 10 events; escaping or dropped rays get 0), the whole picture as one
vectorised Dr.Jit loop around Mitsuba's ray intersection. It prints one JSON line per view in the
form of `bentstraw bench --json`: the median of --repeat pictures after one warm-up picture (which
also compiles the kernel).

--check BENTSTRAW renders each view with `BENTSTRAW render --mode course --raw` instead of timing
and prints the share of pixels whose codes agree (they should differ only on colour boundaries,
where single-precision intersections fall either way).
"""
import argparse
import json
import math
import os
import statistics
import subprocess
import sys
import tempfile
import time

import drjit as dr
import mitsuba as mi

# llvm_ad_rgb is the vectorised CPU variant the PyPI wheels ship (there is no llvm_rgb wheel).
mi.set_variant("llvm_ad_rgb")
# Dr.Jit loads the newest libLLVM it finds (or DRJIT_LIBLLVM_PATH). With LLVM 14 and 15 its
# kernels abort in code generation ("Cannot select: fmaximum"); 19 works (16-18 untried).
if dr.detail.llvm_version()[0] < 16:
    sys.exit(f"mitsuba_course.py: Dr.Jit found LLVM {dr.detail.llvm_version()[0]}, which cannot "
             "compile its kernels; install a newer libLLVM (Debian 12: apt-get install libllvm19) "
             "or point DRJIT_LIBLLVM_PATH at one")

WIDTH, HEIGHT, FOV_DEG = 1024, 768, 50.0
GLASS_RADIUS = 0.04
STRAW_RADIUS, STRAW_HEIGHT = 0.005, 0.25
SECTION_HEIGHT, SECTIONS = 0.05, 5
N_WATER, MAX_EVENTS = 1.333, 10

# The four zoomed views of `bentstraw bench`: observer, straw axis, water height, target.
VIEWS = {
    1: ((0.0, 0.1, 0.1), (0.02, 0.01), 0.15, (0.02, 0.01, 0.15)),
    2: ((0.1, 0.0, 0.1), (0.02, 0.01), 0.15, (0.02, 0.01, 0.15)),
    3: ((0.1, 0.0, 0.3), (0.02, 0.01), 0.20, (0.02, 0.01, 0.20)),
    4: ((0.1, 0.0, -0.1), (0.0, 0.0), 0.20, (0.0, 0.0, 0.05)),
}


def disk(centre, radius):
    """Mitsuba's disk is the unit disk in the plane z = 0: scaled, then moved."""
    t = mi.ScalarTransform4f().translate(list(centre)).scale([radius, radius, 1.0])
    return {"type": "disk", "to_world": t}


def build_scene(straw, water_height):
    """The glass of water (no thickness: an open cylinder and two disks) and the closed straw."""
    xp, yp = straw
    shapes = {
        "water_side": {"type": "cylinder", "p0": [0, 0, 0], "p1": [0, 0, water_height],
                       "radius": GLASS_RADIUS},
        "water_top": disk((0, 0, water_height), GLASS_RADIUS),
        "water_bottom": disk((0, 0, 0), GLASS_RADIUS),
        "straw_side": {"type": "cylinder", "p0": [xp, yp, 0], "p1": [xp, yp, STRAW_HEIGHT],
                       "radius": STRAW_RADIUS},
        "straw_top": disk((xp, yp, STRAW_HEIGHT), STRAW_RADIUS),
        "straw_bottom": disk((xp, yp, 0), STRAW_RADIUS),
    }
    scene = mi.load_dict({"type": "scene", **shapes})
    by_id = {s.id(): mi.ShapePtr(s) for s in scene.shapes()}
    return scene, by_id


def camera_basis(eye, target):
    """The pinhole camera of the physics contract: forward, right = forward x z, up = right x forward."""
    f = [t - e for t, e in zip(target, eye)]
    n = math.sqrt(sum(c * c for c in f))
    f = [c / n for c in f]
    r = [f[1], -f[0], 0.0]  # f x z
    rn = math.hypot(r[0], r[1])
    r = [1.0, 0.0, 0.0] if rn < 1e-9 else [c / rn for c in r]
    u = [r[1] * f[2] - r[2] * f[1], r[2] * f[0] - r[0] * f[2], r[0] * f[1] - r[1] * f[0]]
    return f, r, u


def course_picture(scene, shapes, view, loop_mode, hit_mode):
    """The colour code (0..5) of every pixel centre, row by row from the top, as one Dr.Jit kernel."""
    eye, (xp, yp), _, target = view
    f, r, u = camera_basis(eye, target)
    tan_half = math.tan(math.radians(FOV_DEG) / 2)

    idx = dr.arange(mi.UInt32, WIDTH * HEIGHT)
    row, col = idx // WIDTH, idx % WIDTH
    a = (2.0 * (mi.Float(col) + 0.5) / WIDTH - 1.0) * (tan_half * WIDTH / HEIGHT)
    b = (1.0 - 2.0 * (mi.Float(row) + 0.5) / HEIGHT) * tan_half
    d = dr.normalize(mi.Vector3f(f) + a * mi.Vector3f(r) + b * mi.Vector3f(u))
    ray = mi.Ray3f(mi.Point3f(eye), d)

    straw_side, straw_top, straw_bottom = (shapes["straw_side"], shapes["straw_top"],
                                           shapes["straw_bottom"])
    water_side, water_bottom = shapes["water_side"], shapes["water_bottom"]

    def cond(ray, inside, events, code, active):
        return active

    def body(ray, inside, events, code, active):
        if hit_mode == "full":
            si = scene.ray_intersect(ray, mi.RayFlags.Minimal, True, active)
        else:
            # Mitsuba's nearest hit without its surface interaction (a virtual call per shape);
            # the point and the water's normal from the geometry instead: the same pixels, faster.
            pi = scene.ray_intersect_preliminary(ray, True, active)
            si = dr.zeros(mi.SurfaceInteraction3f)
            si.t, si.shape, si.p = pi.t, pi.shape, ray(pi.t)
            radial = dr.normalize(mi.Vector3f(si.p.x, si.p.y, 0.0))
            si.n = dr.select(pi.shape == water_side, radial, mi.Vector3f(0.0, 0.0, 1.0))
        hit = active & si.is_valid()
        # The straw's bottom cap and the water's bottom disk lie in the same plane z = 0: the
        # contract's tie rule (the opaque straw wins) is applied here, as Mitsuba picks either.
        on_foot = (dr.square(si.p.x - xp) + dr.square(si.p.y - yp)) <= STRAW_RADIUS ** 2
        bottom = (si.shape == straw_bottom) | ((si.shape == water_bottom) & on_foot)
        band = mi.UInt32(dr.clip(dr.floor(si.p.z / SECTION_HEIGHT), 0, SECTIONS - 1)) + 1
        straw_code = dr.select(si.shape == straw_top, SECTIONS, dr.select(bottom, 1, band))
        on_straw = hit & ((si.shape == straw_side) | (si.shape == straw_top) | bottom)
        code = dr.select(on_straw, straw_code, code)

        water = hit & ~on_straw & (events < MAX_EVENTS)
        # Snell-Descartes with the normal turned against the ray; total reflection past the
        # critical angle. `inside` says which side of the water the ray is on.
        n = mi.Vector3f(si.n)
        cos_i = -dr.dot(ray.d, n)
        n = dr.select(cos_i < 0, -n, n)
        cos_i = dr.abs(cos_i)
        eta = dr.select(inside, N_WATER, 1.0 / N_WATER)
        sin2_t = dr.square(eta) * (1.0 - dr.square(cos_i))
        tir = sin2_t > 1.0
        refracted = eta * ray.d + (eta * cos_i - dr.safe_sqrt(1.0 - sin2_t)) * n
        reflected = ray.d + 2.0 * cos_i * n
        new_d = dr.normalize(dr.select(tir, reflected, refracted))
        # Mitsuba's own offset off the surface, on the side the new direction leaves to.
        ray = dr.select(water, si.spawn_ray(new_d), ray)
        inside = dr.select(water & ~tir, ~inside, inside)
        events = dr.select(water, events + 1, events)
        return ray, inside, events, code, water

    # Full-width initial state: the compressed loop needs a per-ray condition from the start.
    n = WIDTH * HEIGHT
    state = (ray, dr.full(mi.Bool, False, n), dr.zeros(mi.UInt32, n), dr.zeros(mi.UInt32, n),
             dr.full(mi.Bool, True, n))
    kw = {"mode": "evaluated", "compress": True} if loop_mode == "compressed" else {"mode": loop_mode}
    _, _, _, code, _ = dr.while_loop(state, cond, body, **kw)
    return code


def picture_now(scene, shapes, view, loop_mode, hit_mode):
    code = course_picture(scene, shapes, view, loop_mode, hit_mode)
    dr.eval(code)
    dr.sync_thread()
    return code


def time_view(number, threads, repeat, loop_mode, hit_mode):
    view = VIEWS[number]
    scene, shapes = build_scene(view[1], view[2])
    picture_now(scene, shapes, view, loop_mode, hit_mode)  # warm-up: compiles the kernel
    times = []
    for _ in range(repeat):
        start = time.perf_counter()
        picture_now(scene, shapes, view, loop_mode, hit_mode)
        times.append(time.perf_counter() - start)
    seconds = statistics.median(times)
    rays = WIDTH * HEIGHT
    return {"simulation": number, "mode": "course", "threads": threads, "width": WIDTH,
            "height": HEIGHT, "rays": rays, "seconds": seconds, "rays_per_s": rays / seconds}


def check_view(number, bentstraw, loop_mode, hit_mode):
    view = VIEWS[number]
    scene, shapes = build_scene(view[1], view[2])
    ours = list(picture_now(scene, shapes, view, loop_mode, hit_mode))  # no numpy needed
    eye, straw, he, target = view
    fmt = lambda v: ",".join(repr(float(c)) for c in v)
    with tempfile.TemporaryDirectory() as tmp:
        raw = os.path.join(tmp, "view.csv")
        subprocess.run([bentstraw, "render", "--observer", fmt(eye), "--straw", fmt(straw),
                        "--water-height", repr(he), "--target", fmt(target), "--fov", "50",
                        "--size", f"{WIDTH}x{HEIGHT}", "--mode", "course",
                        "--output", os.path.join(tmp, "view.png"), "--raw", raw],
                       check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        theirs = [0] * (WIDTH * HEIGHT)
        with open(raw) as fh:
            next(fh)  # row,col,color
            for line in fh:
                i, j, c = line.split(",")
                theirs[int(i) * WIDTH + int(j)] = int(c)
    differ = [k for k in range(WIDTH * HEIGHT) if ours[k] != theirs[k]]
    # A difference is expected only where bentstraw's picture itself changes code within one
    # pixel (its 8 neighbours): there the single-precision faces may fall either way.
    def on_boundary(k):
        i, j = divmod(k, WIDTH)
        return any(theirs[ii * WIDTH + jj] != theirs[k]
                   for ii in range(max(i - 1, 0), min(i + 2, HEIGHT))
                   for jj in range(max(j - 1, 0), min(j + 2, WIDTH)))
    inland = sum(1 for k in differ if not on_boundary(k))
    total = WIDTH * HEIGHT
    print(f"view {number}: {total - len(differ)}/{total} pixels agree "
          f"({100 * (total - len(differ)) / total:.3f} %); {len(differ)} differ, {inland} of them "
          f"away from bentstraw's colour boundaries; straw pixels: bentstraw "
          f"{sum(1 for b in theirs if b)}, mitsuba {sum(1 for a in ours if a)}", flush=True)
    return len(differ) / total


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                formatter_class=argparse.RawDescriptionHelpFormatter,
                                epilog="\n\n".join(__doc__.split("\n\n")[2:]))
    p.add_argument("--threads", type=int, default=os.cpu_count(),
                   help="Dr.Jit LLVM backend threads (default: all cores)")
    p.add_argument("--repeat", type=int, default=20, help="timed pictures per view (median)")
    # Symbolic is the fastest form measured here: one kernel keeps each ray's state in registers,
    # while the evaluated forms write it back after every step (2-3 times slower).
    p.add_argument("--loop", choices=["symbolic", "evaluated", "compressed"], default="symbolic",
                   help="Dr.Jit loop form: symbolic (default, one kernel per picture), evaluated "
                        "(one kernel per step), compressed (evaluated, finished rays dropped)")
    p.add_argument("--hit", choices=["preliminary", "full"], default="preliminary",
                   help="preliminary (default): ray_intersect_preliminary, point and normal from "
                        "the geometry; full: ray_intersect's surface interaction (about a fifth slower "
                        "here, same pixels)")
    p.add_argument("--view", type=int, action="append", choices=sorted(VIEWS),
                   help="only this view (repeatable; default: all four)")
    p.add_argument("--check", metavar="BENTSTRAW",
                   help="compare each view's codes with BENTSTRAW render --raw instead of timing")
    args = p.parse_args()
    if args.threads < 1 or args.repeat < 1:
        p.error("--threads and --repeat must be at least 1")
    dr.set_thread_count(args.threads)
    # On stderr, so that stdout stays one JSON line per view as bench --json prints.
    print(f"mitsuba {mi.__version__} ({mi.variant()}), drjit {dr.__version__}, LLVM "
          f"{'.'.join(map(str, dr.detail.llvm_version()))}, {args.threads} threads, "
          f"{args.loop} loop, {args.hit} hits", file=sys.stderr)
    views = args.view or sorted(VIEWS)
    if args.check:
        worst = max(check_view(v, args.check, args.loop, args.hit) for v in views)
        sys.exit(0 if worst <= 0.001 else 1)
    for v in views:
        print(json.dumps(time_view(v, args.threads, args.repeat, args.loop, args.hit)), flush=True)


if __name__ == "__main__":
    main()
