#!/usr/bin/python3
"""Plot of the Table 2 benchmark: total cut time against input cells, one series per
mesh, with the least-squares line the benchmark reports.

usage: /usr/bin/python3 scripts/plot-table2.py TABLE2.json OUT.png
TABLE2.json is the stdout of `cargo bench --bench table2 -- /work/large`. Needs matplotlib
(Debian's python3-matplotlib, present for /usr/bin/python3 on the project machines).
"""

import json
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def main():
    with open(sys.argv[1]) as f:
        data = json.load(f)
    rows = data["rows"]
    fig, ax = plt.subplots(figsize=(7, 4.5), dpi=110)
    for mesh, marker in (("fandisk", "o"), ("pinion", "s"), ("liver", "^")):
        pts = [(r["input_cells"], r["total_ms"]) for r in rows if r["mesh"] == mesh]
        if pts:
            ax.plot([p[0] for p in pts], [p[1] for p in pts], marker, label=mesh)
    big = data.get("fandisk_1m")
    if big:
        pts = [big] + ([big["same_cells"]] if "same_cells" in big else [])
        ax.plot([p["input_cells"] for p in pts], [p["total_ms"] for p in pts], "x", color="k",
                label="fandisk-1m")
    fitv = data["fit_total_ms_vs_cells"]
    xs = [r["input_cells"] for r in rows]
    if xs:
        x0, x1 = 0, max(xs)
        a, b = fitv["intercept_ms"], fitv["slope_ms_per_cell"]
        ax.plot([x0, x1], [a + b * x0, a + b * x1], "--", color="gray",
                label=f"fit: {a:.1f} ms + {b * 1e3:.2f} µs/cell, r² = {fitv['r2']:.3f}")
    ax.set_xlabel("input cells (tets of all levels replaced)")
    ax.set_ylabel("total cut time (ms, median)")
    ax.set_title("Cutting the MT: time against cells (paper Table 2)")
    ax.grid(True, alpha=0.3)
    ax.legend()
    fig.tight_layout()
    fig.savefig(sys.argv[2])


if __name__ == "__main__":
    main()
