"""The hoop-tilt map with heyoka, side by side with `tumble sweep`, on the same machine.

Computes the default map's `max_tilt` (151 spins x 155 bead angles, t in [0, 10] s, the free
hoop of `crates/studies/src/sweep/tilt-map.sweep.toml`) with heyoka's Taylor method on the
free hoop's Euler-Poisson equations (the same reduction tumble's map runs: Gamma = R^T e_z,
the body angular momentum Pi, the bead angle alpha and its momentum p_alpha; 8 variables),
in SIMD batches (`heyoka.taylor_adaptive_batch`, the CPU's recommended batch size), on
`--processes` worker processes. The largest tilt is located as heyoka locates maxima: a
non-terminal event where d(Gamma_z)/dt = Gamma_x w_y - Gamma_y w_x vanishes, the state at the
event from the step's Taylor polynomial (`update_d_output`), and the start and end of the run.

It times heyoka and `tumble sweep` (`--threads` = `--processes`, its points/s from the
manifest) alternately, `--rounds` times each, JIT compilation excluded (each worker compiles
once before the clock starts), and prints points/s and each side's worst point against a
reference map (`--reference`, the `results.csv` of a tight tumble map, e.g.
`tumble sweep -o out/map-ref --set run.integrator=vern9 --set run.tol=1e-15 --check off`).

Not run by CI; needs heyoka (`python3 -m venv /tmp/hy && /tmp/hy/bin/pip install heyoka`):

    /tmp/hy/bin/python tools/heyoka_map.py --tumble target/release/tumble \\
        --reference out/map-ref/results.csv --rounds 3

Sources: heyoka (F. Biscani, D. Izzo, "Revisiting high-order Taylor methods for astrodynamics
and celestial mechanics", MNRAS 504, 2021), its batch mode and event detection as its
documentation describes them.
"""

import argparse
import csv
import json
import math
import multiprocessing as mp
import os
import subprocess
import sys
import tempfile
import time

import numpy as np

# The default map (tilt-map.sweep.toml).
HOOP_M, BEAD_M, RADIUS, GRAVITY = 1.0, 0.1, 1.0, 9.81
THETA0, ALPHA_DOT0, T_END = 1.5707963267948966, 0.0, 10.0
OMEGA0 = (0.5, 8.0, 151)
ALPHA0 = (0.04, 3.12, 155)


def grid():
    """(omega0, alpha0) in the map's index order: the last axis fastest."""
    w = np.linspace(*OMEGA0)
    a = np.linspace(*ALPHA0)
    return [(wi, ai) for wi in w for ai in a]


JD = 0.5 * HOOP_M * RADIUS**2
JN = HOOP_M * RADIUS**2
MU = BEAD_M * RADIUS**2
K = BEAD_M * GRAVITY * RADIUS


def initial_state(omega0, alpha0):
    """Gamma, Pi, alpha, p_alpha of the hoop at ZYZ angles (0, theta0, 0) spinning at omega0
    about the vertical, the bead at alpha0 moving at ALPHA_DOT0."""
    st, ct = math.sin(THETA0), math.cos(THETA0)
    gamma = np.array([-st, 0.0, ct])  # third row of R_y(theta0)
    w = omega0 * gamma  # body angular velocity of a spin about the lab vertical
    s, c = math.sin(alpha0), math.cos(alpha0)
    j = np.array(
        [[JD + MU * s * s, -MU * c * s, 0.0], [-MU * c * s, JD + MU * c * c, 0.0], [0.0, 0.0, JN + MU]]
    )
    pi = j @ w + np.array([0.0, 0.0, MU]) * ALPHA_DOT0
    p = MU * w[2] + MU * ALPHA_DOT0
    return np.concatenate([gamma, pi, [alpha0, p]])


def equations(hy):
    gx, gy, gz, px, py, pz, al, pa = hy.make_vars("gx", "gy", "gz", "px", "py", "pz", "al", "pa")
    s, c = hy.sin(al), hy.cos(al)
    inv = 1.0 / (JD * (JD + MU))
    wx = inv * ((JD + MU * c * c) * px + MU * c * s * py)
    wy = inv * (MU * c * s * px + (JD + MU * s * s) * py)
    wz = (pz - pa) / JN
    adot = pa / MU - wz
    sys_ = [
        (gx, gy * wz - gz * wy),
        (gy, gz * wx - gx * wz),
        (gz, gx * wy - gy * wx),
        (px, py * wz - pz * wy - K * gz * s),
        (py, pz * wx - px * wz + K * gz * c),
        (pz, px * wy - py * wx + K * (gx * s - gy * c)),
        (al, adot),
        (pa, MU * (s * c * (wx * wx - wy * wy) - (c * c - s * s) * wx * wy) - K * (gy * c - gx * s)),
    ]
    return sys_, gx * wy - gy * wx


_worker = {}


def _tilt(g):
    return abs(g[2]) / math.sqrt(g[0] * g[0] + g[1] * g[1] + g[2] * g[2])


def init_worker(tol):
    import heyoka as hy

    sys_, dgz = equations(hy)
    bs = hy.recommended_simd_size()
    best = np.zeros(bs)

    def on_extremum(ta, t, d_sgn, b):
        ta.update_d_output(t)
        best[b] = max(best[b], _tilt(ta.d_output[:3, b]))

    ev = hy.nt_event_batch(dgz, on_extremum)
    y0 = np.tile(initial_state(1.0, 1.0)[:, None], (1, bs))
    ta = hy.taylor_adaptive_batch(sys_, y0, tol=tol, nt_events=[ev])
    _worker.update(ta=ta, bs=bs, best=best)
    run_chunk([(1.0, 1.0)] * bs)  # warm up


def run_chunk(points):
    ta, bs, best = _worker["ta"], _worker["bs"], _worker["best"]
    out = []
    for k in range(0, len(points), bs):
        batch = points[k : k + bs]
        lanes = batch + [batch[-1]] * (bs - len(batch))
        ta.set_time(0.0)
        ta.state[:] = np.stack([initial_state(w, a) for (w, a) in lanes], axis=1)
        ta.reset_cooldowns()
        for b in range(bs):
            best[b] = _tilt(ta.state[:3, b])
        ta.propagate_until(T_END)
        for b in range(len(batch)):
            m = max(best[b], _tilt(ta.state[:3, b]))
            out.append(math.asin(min(1.0, m)))
    return out


def heyoka_map(points, tol, processes, chunk=256):
    chunks = [points[k : k + chunk] for k in range(0, len(points), chunk)]
    with mp.get_context("fork").Pool(processes, initializer=init_worker, initargs=(tol,)) as pool:
        # Every worker compiled and warmed up before the clock starts.
        pool.map(time.sleep, [0.2] * processes, chunksize=1)
        start = time.perf_counter()
        parts = pool.map(run_chunk, chunks, chunksize=1)
        elapsed = time.perf_counter() - start
    return [v for part in parts for v in part], elapsed


def tumble_map(exe, threads, sets):
    with tempfile.TemporaryDirectory() as d:
        out = os.path.join(d, "map")
        cmd = [exe, "sweep", "-o", out, "--threads", str(threads), "--check", "off"]
        for s in sets:
            cmd += ["--set", s]
        subprocess.run(cmd, check=True, stderr=subprocess.DEVNULL)
        with open(os.path.join(out, "manifest.json")) as f:
            manifest = json.load(f)
        values = read_max_tilt(os.path.join(out, "results.csv"))
    return values, manifest["points"] / manifest["wall_time_s"], manifest


def read_max_tilt(path):
    with open(path) as f:
        return [float(r["max_tilt"]) for r in csv.DictReader(f)]


def worst(values, reference):
    if reference is None:
        return float("nan")
    return max(abs(a - b) for a, b in zip(values, reference))


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--tumble", default="target/release/tumble")
    ap.add_argument("--reference", help="results.csv of a tight tumble map")
    ap.add_argument("--rounds", type=int, default=3)
    ap.add_argument("--processes", type=int, default=2)
    ap.add_argument("--heyoka-tol", type=float, action="append", help="repeatable; default 1e-12")
    ap.add_argument("--set", action="append", default=[], help="--set for tumble sweep")
    args = ap.parse_args()
    tols = args.heyoka_tol or [1e-12]
    reference = read_max_tilt(args.reference) if args.reference else None
    points = grid()
    import heyoka as hy

    print(
        f"{len(points)} points, heyoka {hy.__version__} (batch {hy.recommended_simd_size()}), "
        f"{args.processes} processes/threads, {os.cpu_count()} CPUs, {args.rounds} rounds alternating",
        file=sys.stderr,
    )
    runs = {}
    for r in range(args.rounds):
        sides = ["tumble"] + [f"heyoka tol {t:g}" for t in tols]
        if r % 2:
            sides.reverse()
        for side in sides:
            if side == "tumble":
                values, rate, manifest = tumble_map(args.tumble, args.processes, args.set)
                label = f"tumble ({manifest['integrator']}, tol {manifest['tol']:g}, {manifest['model']['name']})"
            else:
                tol = float(side.split()[-1])
                values, elapsed = heyoka_map(points, tol, args.processes)
                rate = len(points) / elapsed
                label = f"heyoka (taylor, tol {tol:g}, euler-poisson, batch {hy.recommended_simd_size()})"
            print(f"round {r + 1}: {label}: {rate:,.0f} points/s", file=sys.stderr)
            entry = runs.setdefault(label, {"rates": [], "values": values})
            entry["rates"].append(rate)
    base = next(v for k, v in runs.items() if k.startswith("tumble"))
    base_rate = float(np.median(base["rates"]))
    print("| run | points/s (median; all rounds) | worst point against the reference | × tumble |")
    print("|---|---|---|---|")
    for label, e in runs.items():
        med = float(np.median(e["rates"]))
        rates = ", ".join(f"{x:,.0f}" for x in e["rates"])
        print(f"| {label} | {med:,.0f} ({rates}) | {worst(e['values'], reference):.1e} | {med / base_rate:.2f} |")


if __name__ == "__main__":
    main()
