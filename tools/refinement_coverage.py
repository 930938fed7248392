#!/usr/bin/env python3
"""How much of a uniform map's fine structure a refined sweep of the same grid resolved.

Usage: tools/refinement_coverage.py UNIFORM_DIR REFINED_DIR [--metric max_tilt] [--spread 0.05]

Both folders are finished `tumble sweep` outputs of the same two-axis grid (the refined one run
with `--refine L`). A cell of the uniform grid (four neighbouring points) is *steep* when the
metric's values at its corners spread by more than `--spread`; the script prints how many
steep cells the refined sweep computed at all four corners (resolved at the grid's own
resolution), the refined sweep's share of the grid's points, and the steepest cells it missed.
Only the standard library is used.
"""
import argparse
import csv
import sys


def load(folder, metric):
    with open(f"{folder}/results.csv", newline="") as f:
        rows = list(csv.DictReader(f))
    axes = [c for c in rows[0].keys() if c not in ("index", "level", "status", "reason")]
    values = {}
    for r in rows:
        if r["status"] == "ok" and r[metric] != "":
            values[int(r["index"])] = float(r[metric])
    return rows, axes, values


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("uniform")
    p.add_argument("refined")
    p.add_argument("--metric", default="max_tilt")
    p.add_argument("--spread", type=float, default=0.05)
    a = p.parse_args()
    urows, axes, uni = load(a.uniform, a.metric)
    rrows, _, ref = load(a.refined, a.metric)
    have = {int(r["index"]) for r in rrows}
    x_name, y_name = axes[0], axes[1]
    xs = sorted({float(r[x_name]) for r in urows})
    ys = sorted({float(r[y_name]) for r in urows})
    nx, ny = len(xs), len(ys)
    if nx * ny != len(urows):
        sys.exit("the uniform folder does not hold a whole two-axis grid")
    steep, resolved, missed = 0, 0, []
    for i in range(nx - 1):
        for j in range(ny - 1):
            corners = [i * ny + j, (i + 1) * ny + j, i * ny + j + 1, (i + 1) * ny + j + 1]
            if any(c not in uni for c in corners):
                continue
            v = [uni[c] for c in corners]
            spread = max(v) - min(v)
            if spread > a.spread:
                steep += 1
                if all(c in have for c in corners):
                    resolved += 1
                else:
                    missed.append((spread, xs[i], ys[j]))
    print(f"refined sweep: {len(have)} of {nx * ny} points ({100 * len(have) / (nx * ny):.1f} %)")
    print(f"steep cells ({a.metric} spread > {a.spread}): {steep}, resolved: {resolved} "
          f"({100 * resolved / max(steep, 1):.1f} %)")
    for spread, x, y in sorted(missed, reverse=True)[:5]:
        print(f"  missed: {x_name} = {x:g}, {y_name} = {y:g}, spread {spread:.3f}")


if __name__ == "__main__":
    main()
