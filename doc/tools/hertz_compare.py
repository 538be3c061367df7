#!/usr/bin/env python3
"""Compares a Tribos Exodus result of a Hertz scene with the analytic solution.

Usage:
  python3 doc/tools/hertz_compare.py cylinder RESULT.exo [options]
  python3 doc/tools/hertz_compare.py sphere   RESULT.exo [options]

Scenes: input/hertz_cylinder.xml (line contact, plane strain, half model by x = 0) and
input/hertz_sphere.xml (point contact, quarter model by x = 0 and y = 0); formulas in
/work/shared/VALIDATION.md. Reads, from the last time step, the nodal variables
contact_pressure (normal force / tributary area, on slave nodes) and contact_normal (nodal
normal force), the coordinates and the slave node set (default "block_contact", the scenes' slave), and prints:
  - the peak nodal pressure and its position against p0;
  - the contact half-width b (cylinder: per y-slice of nodes, the nodes sorted by x) or radius
    a (sphere: r = sqrt(x^2 + y^2)): the last node with positive pressure and the first with
    zero pressure bracket the edge; "edge" interpolates inside that bracket by the Hertz
    shape p^2 = c (b^2 - x^2) through the last two positive nodes (clamped to the bracket);
    "area" is the contact area (sum of the tributary areas, contact_normal / contact_pressure,
    of the nodes in contact) as a width / radius (it overshoots by about half an element);
  - a least-squares fit p0 sqrt(1 - x^2/b^2) to the nodal pressures within 2 b (Hertz);
  - the total normal contact force against the load the model carries;
  - with --profile, the nodal pressures against Hertz.
Positions are the undeformed coordinates (the contact surface of the slave body; Hertz's
small-strain theory measures b and a in the undeformed configuration as well).

Reads the netCDF file with `ncdump` (Debian: apt-get install netcdf-bin) through exodus_read.py;
standard library only.
Exit status 0, or 2 for a file without the variables.
"""
import argparse
import math
import os
import signal
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import exodus_read  # noqa: E402  (the shared ncdump reader next to this script)

# ---------------------------------------------------------------- reading the result


def read_result(path, slave):
    """Coordinates, the last step's nodal contact variables and the slave node ids (0-based)."""
    header = exodus_read.ncdump_header(path)
    for needed in ("name_nod_var", "ns_names"):
        if not exodus_read.has_variable(header, needed):
            raise KeyError("no %s in the file (not a tribos result, or no node sets)" % needed)
    mesh = exodus_read.read_mesh(path, header)
    if slave not in mesh["node_sets"]:
        raise KeyError("node set " + slave + " (the file has: " + ", ".join(mesh["node_sets"]) + ")")
    res = {"x": mesh["x"], "y": mesh["y"], "z": mesh["z"], "slave": sorted(mesh["node_sets"][slave])}
    res.update(exodus_read.last_step_nodal(path, header, ["contact_pressure", "contact_normal"]))
    res["steps"] = exodus_read.dimension(header, "time_step")
    return res

# ---------------------------------------------------------------- Hertz


def effective_modulus(E1, nu1, E2, nu2):
    return 1.0 / ((1.0 - nu1 ** 2) / E1 + (1.0 - nu2 ** 2) / E2)


def hertz(kind, P, R, Es):
    """(half-width b or radius a, peak p0)."""
    if kind == "cylinder":
        b = math.sqrt(4.0 * P * R / (math.pi * Es))
        return b, 2.0 * P / (math.pi * b)
    a = (3.0 * P * R / (4.0 * Es)) ** (1.0 / 3.0)
    return a, 3.0 * P / (2.0 * math.pi * a * a)


def hertz_p(p0, b, s):
    return p0 * math.sqrt(1.0 - (s / b) ** 2) if abs(s) < b else 0.0


def fit_hertz(points, b_guess):
    """Least-squares p0 sqrt(1 - s^2/b^2) through (s, p): golden-section search on b, p0 linear."""
    def residual(b):
        w = [math.sqrt(1.0 - (s / b) ** 2) if s < b else 0.0 for s, _ in points]
        ww = sum(x * x for x in w)
        p0 = sum(x * p for x, (_, p) in zip(w, points)) / ww if ww > 0 else 0.0
        return sum((p - p0 * x) ** 2 for x, (_, p) in zip(w, points)), p0
    lo, hi = 0.2 * b_guess, 2.0 * b_guess
    g = (math.sqrt(5.0) - 1.0) / 2.0
    # coarse scan first (the residual is not unimodal between nodes), then golden section
    grid = [lo + (hi - lo) * k / 200.0 for k in range(201)]
    best = min(grid, key=lambda b: residual(b)[0])
    lo, hi = max(lo, best - (hi - lo) / 200.0), min(hi, best + (hi - lo) / 200.0)
    c, d = hi - g * (hi - lo), lo + g * (hi - lo)
    for _ in range(60):
        if residual(c)[0] < residual(d)[0]:
            hi = d
        else:
            lo = c
        c, d = hi - g * (hi - lo), lo + g * (hi - lo)
    b = 0.5 * (lo + hi)
    res, p0 = residual(b)
    return b, p0, math.sqrt(res / len(points))


# Nodal pressures below this are the iterative solver's round-off, not contact (a node out
# of contact carries a multiplier of the order of the solver tolerance times the forces).
NOISE = 0.0


def edge_estimate(profile):
    """profile: (s, p) sorted by s >= 0. Returns (last positive s, first zero s after it, edge)."""
    pos = [i for i, (_, p) in enumerate(profile) if p > NOISE]
    if not pos:
        return None, None, None
    i = pos[-1]
    s_in, p_in = profile[i]
    s_out = next((s for s, p in profile[i + 1:] if p <= 0.0), None)
    edge = None
    if i > 0 and profile[i - 1][1] > p_in:
        s_prev, p_prev = profile[i - 1]
        den = p_prev ** 2 - p_in ** 2
        b2 = (p_prev ** 2 * s_in ** 2 - p_in ** 2 * s_prev ** 2) / den
        edge = math.sqrt(b2) if b2 > 0 else s_in
    if edge is None:
        edge = s_in if s_out is None else 0.5 * (s_in + s_out)
    edge = max(edge, s_in)
    if s_out is not None:
        edge = min(edge, s_out)
    return s_in, s_out, edge


def rel(v, ref):
    return "%+.1f %%" % (100.0 * (v - ref) / ref) if ref else ""

# ---------------------------------------------------------------- main


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("kind", choices=["cylinder", "sphere"])
    ap.add_argument("result", help="Exodus file written by tribos --output")
    ap.add_argument("--E1", type=float, default=210000.0, help="curved body's Young modulus (steel)")
    ap.add_argument("--nu1", type=float, default=0.3)
    ap.add_argument("--E2", type=float, default=70000.0, help="flat body's Young modulus (aluminium)")
    ap.add_argument("--nu2", type=float, default=0.33)
    ap.add_argument("--R", type=float, default=10.0, help="radius of the curved body")
    ap.add_argument("--load", type=float, default=None,
                    help="full-body load: cylinder N per unit length (default 4000), sphere N (default 7814.03)")
    ap.add_argument("--slave", default=None, help="slave node set (default block_contact)")
    ap.add_argument("--profile", action="store_true", help="print the nodal pressures against Hertz")
    args = ap.parse_args()

    kind = args.kind
    P = args.load if args.load is not None else (4000.0 if kind == "cylinder" else 7814.03)
    slave = args.slave or "block_contact"
    try:
        r = read_result(args.result, slave)
    except (KeyError, IndexError, subprocess.CalledProcessError) as e:
        print("hertz_compare: %s: cannot read %s" % (args.result, e), file=sys.stderr)
        return 2
    Es = effective_modulus(args.E1, args.nu1, args.E2, args.nu2)
    b, p0 = hertz(kind, P, args.R, Es)
    x, y, z = r["x"], r["y"], r["z"]
    pr, fn = r["contact_pressure"], r["contact_normal"]
    nodes = r["slave"]
    wname = "b" if kind == "cylinder" else "a"

    print("%s: %d nodes, %d slave nodes (%s), time steps %s" % (args.result, len(x), len(nodes), slave, r["steps"]))
    print("Hertz: E* = %.1f, R = %g, load %g %s -> %s = %.4f, p0 = %.1f"
          % (Es, args.R, P, "N per unit length" if kind == "cylinder" else "N", wname, b, p0))

    # total normal force against the load the model carries
    total = sum(fn[n] for n in nodes)
    if kind == "cylinder":
        ys = [y[n] for n in nodes]
        t = max(ys) - min(ys)
        carried = 0.5 * P * t
        print("total normal force %.2f, half model carries P/2 * t = %.2f (t = %g): %s"
              % (total, carried, t, rel(abs(total), carried)))
    else:
        carried = 0.25 * P
        print("total normal force %.2f, quarter model carries P/4 = %.2f: %s" % (total, carried, rel(abs(total), carried)))

    global NOISE
    NOISE = 1e-6 * p0
    in_contact = [n for n in nodes if pr[n] > NOISE]
    if not in_contact:
        print("no slave node with positive contact_pressure")
        return 0
    peak = max(in_contact, key=lambda n: pr[n])
    print("peak nodal pressure %.1f at (%.4f, %.4f, %.4f): %s against p0 = %.1f"
          % (pr[peak], x[peak], y[peak], z[peak], rel(pr[peak], p0), p0))
    area = sum(fn[n] / pr[n] for n in in_contact)
    print("nodes in contact: %d" % len(in_contact))

    if kind == "cylinder":
        # one profile per y-slice of nodes (the extruded mesh is the same in every slice)
        tol = 1e-6 * max(1.0, args.R)
        slices = {}
        for n in nodes:
            key = round(y[n] / tol)
            slices.setdefault(key, []).append(n)
        print("%-10s %6s %10s %10s %10s %10s %10s" % ("slice y", "nodes", "peak p", "last p>0", "first 0", "edge", "vs b"))
        for key in sorted(slices):
            prof = sorted((abs(x[n]), pr[n]) for n in slices[key])
            s_in, s_out, edge = edge_estimate(prof)
            pk = max(p for _, p in prof)
            print("%-10.4g %6d %10.1f %10s %10s %10s %10s"
                  % (y[slices[key][0]], len(prof), pk, "%.4f" % s_in if s_in is not None else "-",
                     "%.4f" % s_out if s_out is not None else "-", "%.4f" % edge if edge is not None else "-",
                     rel(edge, b) if edge is not None else ""))
        ys = [y[n] for n in nodes]
        t = max(ys) - min(ys)
        b_area = area / t if t > 0 else float("nan")
        print("contact width from the area (sum of tributary areas / t): b = %.4f (%s)" % (b_area, rel(b_area, b)))
        pts = [(abs(x[n]), pr[n], y[n]) for n in nodes if abs(x[n]) < 2.0 * b]
    else:
        prof = sorted((math.hypot(x[n], y[n]), pr[n]) for n in nodes)
        r_pos = max(math.hypot(x[n], y[n]) for n in in_contact)
        r_zero = min((s for s, p in prof if p <= 0.0), default=None)
        print("largest r with p > 0: %.4f, smallest r with p = 0: %s (a = %.4f)"
              % (r_pos, "%.4f" % r_zero if r_zero is not None else "-", b))
        # radial edge per bracket: the interpolation through the two outermost positive nodes
        # of the sorted profile is noisy on an unstructured mesh; bracket and area are printed
        a_area = math.sqrt(4.0 * area / math.pi)
        print("contact radius from the area (quarter: sum of tributary areas = pi a^2 / 4): a = %.4f (%s)"
              % (a_area, rel(a_area, b)))
        pts = [(math.hypot(x[n], y[n]), pr[n], None) for n in nodes if math.hypot(x[n], y[n]) < 2.0 * b]
    bf, p0f, rms = fit_hertz([(s, p) for s, p, _ in pts], b)
    print("least-squares Hertz fit over %d nodes within 2 %s: %s = %.4f (%s), p0 = %.1f (%s), rms residual %.1f (%.1f %% of p0)"
          % (len(pts), wname, wname, bf, rel(bf, b), p0f, rel(p0f, p0), rms, 100.0 * rms / p0))
    if args.profile:
        print("%10s %10s %10s %10s %10s" % ("|x|" if kind == "cylinder" else "r", "y" if kind == "cylinder" else "",
                                             "p", "Hertz", "diff/p0"))
        for s, p, yy in sorted(pts, key=lambda q: (q[2] or 0.0, q[0])):
            h = hertz_p(p0, b, s)
            print("%10.4f %10s %10.1f %10.1f %+10.3f" % (s, "%.4f" % yy if yy is not None else "", p, h, (p - h) / p0))
    return 0


if __name__ == "__main__":
    signal.signal(signal.SIGPIPE, signal.SIG_DFL)  # quiet when piped into head
    sys.exit(main())
