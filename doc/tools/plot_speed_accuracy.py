#!/usr/bin/python3
"""Speed against accuracy: one chart from the CSV files of build/bin/tribos_speed_accuracy.

  python3 doc/tools/plot_speed_accuracy.py [--title TEXT] OUT.png LABEL=FILE.csv [LABEL=FILE.csv ...]

Left: displacement error against F applications; right: the largest KKT residual against F
applications; one line per (variant, friction model), one marker per tolerance epsilon. Runs
whose CSV row says converged = 0 (column present in newer CSVs) are crossed out in black.
"""
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def read(path):
    with open(path) as f:
        return list(csv.DictReader(f))


def main():
    if len(sys.argv) < 3:
        sys.exit(__doc__)
    args = sys.argv[1:]
    title = "Table 1 cell 2s = 32, H/h = 3: epsilon = 1e-2 ... 1e-9"
    if args[0] == "--title":
        title, args = args[1], args[2:]
    out = args[0]
    fig, (left, right) = plt.subplots(1, 2, figsize=(11, 4.2))
    crossed = False
    for spec in args[1:]:
        label, path = spec.split("=", 1)
        rows = read(path)
        for model, style in (("None", "o-"), ("Coulomb", "s--")):
            sel = [r for r in rows if r["model"] == model]
            f = [int(r["pfp_applications"]) for r in sel]
            err = [float(r["relative_error"]) for r in sel]
            kkt = [max(float(r["kkt_equilibrium"]), float(r["kkt_complementarity"]), float(r["kkt_friction"]))
                   for r in sel]
            name = f"{label}, {'frictionless' if model == 'None' else 'Coulomb'}"
            left.loglog(f, err, style, label=name)
            right.loglog(f, kkt, style, label=name)
            bad = [i for i, r in enumerate(sel) if r.get("converged", "1") == "0"]
            for ax, y in ((left, err), (right, kkt)):
                ax.loglog([f[i] for i in bad], [y[i] for i in bad], "kx", markersize=10,
                          label=None if crossed or ax is right else "not converged")
            crossed = crossed or bool(bad)
    left.set_xlabel("F applications")
    left.set_ylabel("relative displacement error")
    right.set_xlabel("F applications")
    right.set_ylabel("largest KKT residual")
    for ax in (left, right):
        ax.grid(True, which="both", alpha=0.3)
    left.legend(fontsize=8)
    fig.suptitle(title)
    fig.tight_layout()
    fig.savefig(out, dpi=110)
    print("wrote", out)


if __name__ == "__main__":
    main()
