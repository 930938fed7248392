"""Speed against error on three scenes, tumble and heyoka side by side on the same machine.

For `free-body`, `heavy-top` and `free-hoop` at their default parameters and horizons, prints
the time each tool needs to reach a final-state error of 1e-10, 1e-12 and 1e-14, and the ratio
tumble / heyoka (below 1: tumble is faster).

- tumble: `tumble work-precision SCENE --integrators LIST` (its ladders, timing and error
  against its own reference, in its norm `max |dy_i| / (1 + |ref_i|)` over the quaternion, the
  bead angle and the body angular velocity); the time at an error is interpolated log-log
  between the two rungs around it; the best of the listed methods is reported.
- heyoka: `taylor_adaptive` on the scene's equations in heyoka's expression system (the
  rotation matrix R' = R hat(w) and the body angular momentum Pi' = Pi x w + torque, plus the
  bead angle and its momentum for the hoop: the free hoop's Euler-Poisson equations of
  `tools/heyoka_map.py` with the whole rotation), over a ladder of tolerances; each
  `propagate_until` timed (median of repeats, JIT compilation excluded); the final state turned
  into tumble's coordinates (quaternion from R, sign matched) and measured in tumble's norm
  against a reference computed by heyoka in extended precision (`np.longdouble`, tol 1e-19).
  The script also prints how far tumble's own reference run lies from that reference.

The two sides alternate, `--rounds` times; each figure is the median over rounds.
Not run by CI; needs heyoka (`python3 -m venv /tmp/hy && /tmp/hy/bin/pip install heyoka`):

    /tmp/hy/bin/python tools/heyoka_scenes.py --tumble target/release/tumble --rounds 2

Sources: heyoka (F. Biscani, D. Izzo, "Revisiting high-order Taylor methods for astrodynamics
and celestial mechanics", MNRAS 504, 2021); the rigid-body equations as in Holm, "Geometric
Mechanics" part II (Euler-Poincare with a heavy top's Gamma = R^T e_z).
"""

import argparse
import csv
import math
import os
import statistics
import subprocess
import tempfile
import time

import numpy as np

TARGETS = (1e-10, 1e-12, 1e-14)


# --- the scenes, as tumble defines them (defaults of `tumble scenes`) -------------------------


def rot_x(a):
    c, s = math.cos(a), math.sin(a)
    return np.array([[1, 0, 0], [0, c, -s], [0, s, c]], dtype=float)


def rot_y(a):
    c, s = math.cos(a), math.sin(a)
    return np.array([[c, 0, s], [0, 1, 0], [-s, 0, c]], dtype=float)


def rigid(hy, inertia, mgl):
    """R (row-major) and Pi of a body with principal moments `inertia` under gravity acting
    at body z (heavy top: V = mgl e_z . R e_3; mgl = 0: torque-free)."""
    r = hy.make_vars(*[f"r{i}{j}" for i in range(3) for j in range(3)])
    p = hy.make_vars("px", "py", "pz")
    w = [p[k] / inertia[k] for k in range(3)]
    g = (r[6], r[7], r[8])  # Gamma = R^T e_z: the third row of R
    torque = (mgl * g[1], -mgl * g[0], 0.0)  # mgl Gamma x e_3
    pd = [
        p[1] * w[2] - p[2] * w[1] + torque[0],
        p[2] * w[0] - p[0] * w[2] + torque[1],
        p[0] * w[1] - p[1] * w[0] + torque[2],
    ]
    return r, w, pd


def rotation_rhs(r, w):
    """R' = R hat(w), row-major."""
    out = []
    for i in range(3):
        a, b, c = r[3 * i], r[3 * i + 1], r[3 * i + 2]
        out += [b * w[2] - c * w[1], c * w[0] - a * w[2], a * w[1] - b * w[0]]
    return out


def free_body(hy):
    inertia = (1.0, 2.0, 3.0)
    r, w, pd = rigid(hy, inertia, 0.0)
    p = hy.make_vars("px", "py", "pz")
    sys_ = list(zip(r, rotation_rhs(r, w))) + list(zip(p, pd))
    y0 = np.concatenate([np.eye(3).ravel(), [0.4, -0.8, 0.6]])

    def coords(y):
        return quaternion(y[:9]), [y[9 + k] / inertia[k] for k in range(3)]

    return sys_, y0, 20.0, coords


def heavy_top(hy):
    inertia, mgl, tilt0, spin0 = (5.0, 5.0, 1.0), 20.0, 0.05, 50.0
    r, w, pd = rigid(hy, inertia, mgl)
    p = hy.make_vars("px", "py", "pz")
    sys_ = list(zip(r, rotation_rhs(r, w))) + list(zip(p, pd))
    y0 = np.concatenate([rot_x(tilt0).ravel(), [0.0, 0.0, inertia[2] * spin0]])

    def coords(y):
        return quaternion(y[:9]), [y[9 + k] / inertia[k] for k in range(3)]

    return sys_, y0, 10.0, coords


def free_hoop(hy):
    hoop_m, bead_m, radius, gravity = 1.0, 0.1, 1.0, 9.81
    omega0, alpha0, alpha_dot0, theta0 = 4.0, 0.5, 0.0, math.pi / 2
    jd, jn, mu, k = 0.5 * hoop_m * radius**2, hoop_m * radius**2, bead_m * radius**2, bead_m * gravity * radius
    r = hy.make_vars(*[f"r{i}{j}" for i in range(3) for j in range(3)])
    px, py, pz, al, pa = hy.make_vars("px", "py", "pz", "al", "pa")
    gx, gy, gz = r[6], r[7], r[8]
    s, c = hy.sin(al), hy.cos(al)
    inv = 1.0 / (jd * (jd + mu))
    wx = inv * ((jd + mu * c * c) * px + mu * c * s * py)
    wy = inv * (mu * c * s * px + (jd + mu * s * s) * py)
    wz = (pz - pa) / jn
    adot = pa / mu - wz
    sys_ = list(zip(r, rotation_rhs(r, (wx, wy, wz)))) + [
        (px, py * wz - pz * wy - k * gz * s),
        (py, pz * wx - px * wz + k * gz * c),
        (pz, px * wy - py * wx + k * (gx * s - gy * c)),
        (al, adot),
        (pa, mu * (s * c * (wx * wx - wy * wy) - (c * c - s * s) * wx * wy) - k * (gy * c - gx * s)),
    ]
    rot = rot_y(theta0)
    w0 = omega0 * rot[2]  # body angular velocity of a spin about the lab vertical
    sa, ca = math.sin(alpha0), math.cos(alpha0)
    j = np.array([[jd + mu * sa * sa, -mu * ca * sa, 0.0], [-mu * ca * sa, jd + mu * ca * ca, 0.0], [0.0, 0.0, jn + mu]])
    pi0 = j @ w0 + np.array([0.0, 0.0, mu]) * alpha_dot0
    y0 = np.concatenate([rot.ravel(), pi0, [alpha0, mu * w0[2] + mu * alpha_dot0]])

    def coords(y):
        p0, p1, p2, a, q = (float(v) for v in y[9:14])
        s, c = math.sin(a), math.cos(a)
        w_x = ((jd + mu * c * c) * p0 + mu * c * s * p1) / (jd * (jd + mu))
        w_y = (mu * c * s * p0 + (jd + mu * s * s) * p1) / (jd * (jd + mu))
        w_z = (p2 - q) / jn
        return quaternion(y[:9]) + [a], [w_x, w_y, w_z, q / mu - w_z]

    return sys_, y0, 10.0, coords


SCENES = {
    "free-body": (free_body, "split-exact2,split-exact4,taylor,vern9"),
    "heavy-top": (heavy_top, "taylor,split-exact8,vern8,vern9"),
    "free-hoop": (free_hoop, "taylor,dop853,vern8,vern9,gauss8"),
}

# tumble's reference run: the work-precision study's own (its `reference` line).
REFERENCE = {
    "free-body": ("taylor-dd", "--tol", "1e-30"),
    "heavy-top": ("taylor-dd", "--tol", "1e-30"),
    "free-hoop": ("gauss12", "--dt", "6.25e-4"),
}


def quaternion(r):
    """Unit quaternion (w, x, y, z) of a row-major rotation matrix (Shepperd's method)."""
    m = np.array([float(v) for v in r]).reshape(3, 3)
    t = m.trace()
    if t > max(m[0, 0], m[1, 1], m[2, 2]):
        s = 2.0 * math.sqrt(1.0 + t)
        return [0.25 * s, (m[2, 1] - m[1, 2]) / s, (m[0, 2] - m[2, 0]) / s, (m[1, 0] - m[0, 1]) / s]
    i = int(np.argmax([m[0, 0], m[1, 1], m[2, 2]]))
    j, k = (i + 1) % 3, (i + 2) % 3
    s = 2.0 * math.sqrt(1.0 + m[i, i] - m[j, j] - m[k, k])
    q = [0.0] * 4
    q[0] = (m[k, j] - m[j, k]) / s
    q[1 + i] = 0.25 * s
    q[1 + j] = (m[j, i] + m[i, j]) / s
    q[1 + k] = (m[k, i] + m[i, k]) / s
    return q


def error(y, ref):
    """tumble's work-precision norm, the quaternion compared up to its sign."""

    def norm(flip):
        return max(abs((-a if flip and i < 4 else a) - b) / (1.0 + abs(b)) for i, (a, b) in enumerate(zip(y, ref)))

    return min(norm(False), norm(True))


def flat(coords, y):
    q, rates = coords(y)
    return [float(v) for v in q] + [float(v) for v in rates]


# --- heyoka ------------------------------------------------------------------------------------


def heyoka_reference(hy, scene):
    sys_, y0, t_end, coords = SCENES[scene][0](hy)
    ta = hy.taylor_adaptive(sys_, np.array(y0, dtype=np.longdouble), tol=np.longdouble(1e-19), fp_type=np.longdouble)
    ta.propagate_until(np.longdouble(t_end))
    return flat(coords, ta.state)


def heyoka_ladder(hy, scene, ref, tols):
    """(tol, error, seconds per run) for each tolerance; JIT excluded."""
    sys_, y0, t_end, coords = SCENES[scene][0](hy)
    rows = []
    for tol in tols:
        ta = hy.taylor_adaptive(sys_, y0, tol=tol)
        times = []
        repeats = None
        while True:
            ta.time = 0.0
            ta.state[:] = y0
            start = time.perf_counter()
            ta.propagate_until(t_end)
            times.append(time.perf_counter() - start)
            if repeats is None:
                repeats = max(5, min(2000, int(0.2 / max(times[0], 1e-7))))
            if len(times) >= repeats:
                break
        rows.append((tol, error(flat(coords, ta.state), ref), statistics.median(times)))
    return rows


# --- tumble ------------------------------------------------------------------------------------


def tumble_ladders(exe, scene, integrators):
    """{integrator: [(error, seconds)]} from `tumble work-precision`."""
    with tempfile.TemporaryDirectory() as d:
        out = os.path.join(d, "wp")
        cmd = [exe, "work-precision", scene, "--integrators", integrators, "-o", out]
        subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        ladders = {}
        with open(os.path.join(out, "work-precision.csv")) as f:
            for r in csv.DictReader(f):
                ladders.setdefault(r["integrator"], []).append((float(r["error"]), float(r["wall_time_s"])))
    return ladders


def tumble_reference_gap(exe, scene, ref):
    """How far tumble's reference run (`REFERENCE`, the work-precision study's) ends from the
    extended reference."""
    method, flag, value = REFERENCE[scene]
    with tempfile.TemporaryDirectory() as d:
        out = os.path.join(d, "run.csv")
        cmd = [exe, "simulate", scene, "--integrator", method, flag, value, "--check", "off", "-o", out]
        subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        with open(out) as f:
            rows = list(csv.DictReader(f))
    last = rows[-1]
    names = ["qw", "qx", "qy", "qz"] + (["alpha"] if "alpha" in last else [])
    names += ["omega_x", "omega_y", "omega_z"] + (["alpha_dot"] if "alpha_dot" in last else [])
    return error([float(last[n]) for n in names], ref)


def time_at(points, target):
    """Seconds to reach `target` error: log-log interpolated between two rungs around it, or,
    where no pair of rungs brackets it (a method whose errors all lie below), the quickest
    rung at or below it."""
    pts = sorted((e, t) for e, t in points if e > 0 and math.isfinite(e))
    best = min((t for e, t in pts if e <= target), default=math.inf)
    for (e1, t1), (e2, t2) in zip(pts, pts[1:]):
        if e1 < target <= e2:
            x = (math.log(target) - math.log(e1)) / (math.log(e2) - math.log(e1))
            best = min(best, math.exp(math.log(t1) + x * (math.log(t2) - math.log(t1))))
    return best


def fmt(seconds):
    if not math.isfinite(seconds):
        return "—"
    return f"{seconds * 1e6:,.1f} µs" if seconds < 1e-3 else f"{seconds * 1e3:,.2f} ms"


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--tumble", default="target/release/tumble")
    ap.add_argument("--rounds", type=int, default=2)
    ap.add_argument("--scenes", default=",".join(SCENES))
    args = ap.parse_args()
    import heyoka as hy

    tols = [10.0 ** (-k / 2) for k in range(12, 33)]  # 1e-6 ... 1e-16
    print(f"heyoka {hy.__version__}, tumble {args.tumble}, {args.rounds} rounds alternating")
    print("| scene | error | heyoka | tumble (method) | tumble / heyoka |")
    print("|---|---|---|---|---|")
    for scene in args.scenes.split(","):
        ref = heyoka_reference(hy, scene)
        gap = tumble_reference_gap(args.tumble, scene, ref)
        hey = {t: [] for t in TARGETS}
        tum = {t: [] for t in TARGETS}
        for _ in range(args.rounds):
            ladders = tumble_ladders(args.tumble, scene, SCENES[scene][1])
            for t in TARGETS:
                tum[t].append(min(((time_at(p, t), m) for m, p in ladders.items()), key=lambda x: x[0]))
            rows = heyoka_ladder(hy, scene, ref, tols)
            for t in TARGETS:
                hey[t].append(time_at([(e, s) for _, e, s in rows], t))
        for t in TARGETS:
            h = statistics.median(hey[t])
            ts = sorted(tum[t], key=lambda x: x[0])
            tb, method = ts[len(ts) // 2]
            ratio = tb / h if math.isfinite(tb) and math.isfinite(h) else math.nan
            print(f"| {scene} | {t:.0e} | {fmt(h)} | {fmt(tb)} ({method}) | {ratio:.2f} |")
        method, flag, value = REFERENCE[scene]
        print(f"<!-- {scene}: tumble's reference, {method} {flag.lstrip('-')} {value}, ends {gap:.1e} from heyoka's extended-precision reference -->")


if __name__ == "__main__":
    main()
