#!/usr/bin/env python3
"""Compares a Tribos Exodus result of a Cattaneo-Mindlin scene with the analytic solution.

Usage:
  python3 doc/tools/cattaneo_compare.py cylinder RESULT.exo [--step K] [options]
  python3 doc/tools/cattaneo_compare.py sphere   RESULT.exo [--step K] [options]

Scenes: input/cattaneo_cylinder.xml (line contact, plane strain slice of thickness t, full
section in x) and input/cattaneo_sphere.xml (point contact, half model by y = 0): two bodies of
the same material pressed by P and then sheared by Q < F P along x (K. L. Johnson, Contact
Mechanics, 1985, Sec. 7.2). For identical materials the normal and tangential problems decouple:
  cylinder: b = sqrt(4 P R / (pi E*)), p0 = 2 P / (pi b), c = b sqrt(1 - Q/(F P));
  sphere:   a = (3 P R / (4 E*))^(1/3), p0 = 3 P / (2 pi a^2), c = a (1 - Q/(F P))^(1/3);
  q(s) = F p0 [sqrt(1 - s^2/b^2) - (c/b) sqrt(1 - s^2/c^2)] for s < c, F p(s) for c <= s < b
  (s = |x| for the cylinder, r = sqrt(x^2 + y^2) for the sphere; b stands for a), with
  1/E* = 2 (1 - nu^2) / E.
P and Q are measured, not given: P = the sum of the nodal normal contact forces
(contact_normal), Q = the sum of the nodal tangential forces along t1 = x (contact_t1), both per
unit length (divided by the slice thickness t) for the cylinder and doubled for the half sphere.
The analytic b, p0 and c are those of the measured P and Q.

Printed (for the time step --step K, 1-based, default the last):
  - P, Q, Q/(F P), and the global contact_force_x of the file as a cross-check of Q;
  - the Hertz b or a, and the computed contact size as hertz_compare.py measures it (last node
    with pressure > 0 and first with 0, the edge interpolated between them; the size from the
    contact area, sum of the tributary areas contact_normal / contact_pressure);
  - the analytic stick size c and the computed one from contact_status (1 stick, 2 slip): the
    largest s of a stick node and the smallest s of a slip node beyond it bracket the stick
    edge; the midpoint is "c computed" (cylinder: also per y-slice of nodes); and the size from
    the stick area (the sum of the stick nodes' tributary areas), robust where the stick
    boundary is ragged (the sphere's unstructured mesh);
  - the rms and the largest error of the nodal tangential traction q = contact_t1 / tributary
    area against the analytic q over the nodes in contact, relative to F p0 (and the same for
    the pressure against Hertz, relative to p0); the rms also over the stick and the slip nodes
    apart (a stick node's tangential force is not set by Coulomb's law and is the noisier).
The slave node set is the one of block_contact / cylinder_contact / sphere_contact (or --slave)
that carries a normal contact force. Positions are the undeformed coordinates.
With --json, one JSON object with these numbers instead (for a test to check bounds).

Reads the netCDF file with `ncdump` (Debian: netcdf-bin) through exodus_read.py and uses the
Hertz helpers of hertz_compare.py; standard library only.
Exit status 0, or 2 for a file without the variables (or without the step).
"""
import argparse
import json
import math
import os
import signal
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import exodus_read  # noqa: E402  (the shared ncdump reader next to this script)
import hertz_compare  # noqa: E402  (Hertz's b / a and p0, the contact-edge estimate)

NODAL = ["contact_normal", "contact_t1", "contact_pressure", "contact_status"]

# ---------------------------------------------------------------- reading the result


def step_values(path, header, step):
    """(step, number of steps, {name: values} of the NODAL variables, {name: value} of the global
    variables) at time step `step` (1-based; None: the last), through exodus_read's every-step
    readers. IndexError for a step the file does not have, KeyError for a missing variable."""
    steps = exodus_read.dimension(header, "time_step") or 0
    k = steps if step is None else step
    if not 1 <= k <= steps:
        raise IndexError("time step %s (the file has %d)" % (step, steps))
    nodal = {name: values[k - 1] for name, values in exodus_read.nodal_steps(path, header, NODAL).items()}
    glo = {name: values[k - 1] for name, values in exodus_read.global_variables(path, header).items()}
    return k, steps, nodal, glo


def read_result(path, step, slave):
    header = exodus_read.ncdump_header(path)
    for needed in ("name_nod_var", "ns_names"):
        if not exodus_read.has_variable(header, needed):
            raise KeyError("no %s in the file (not a tribos result, or no node sets)" % needed)
    mesh = exodus_read.read_mesh(path, header)
    k, steps, nodal, glo = step_values(path, header, step)
    candidates = [slave] if slave else ["block_contact", "cylinder_contact", "sphere_contact"]
    chosen = None
    for name in candidates:
        if name in mesh["node_sets"] and any(nodal["contact_normal"][m] != 0.0 for m in mesh["node_sets"][name]):
            chosen = name
            break
    if chosen is None:
        if slave and slave not in mesh["node_sets"]:
            raise KeyError("node set " + slave + " (the file has: " + ", ".join(mesh["node_sets"]) + ")")
        raise KeyError("a slave node set with contact forces among " + ", ".join(candidates))
    res = {"x": mesh["x"], "y": mesh["y"], "z": mesh["z"], "slave": sorted(set(mesh["node_sets"][chosen])),
           "slave_name": chosen, "step": k, "steps": steps, "global": glo, "mesh": mesh}
    res.update(nodal)
    return res


def slave_element_size(mesh, slave_nodes, near):
    """sqrt(2 x the mean area) of the slave-surface triangles with a vertex in `near` (the contact
    zone): the leg of a right isosceles triangle of that area (the cylinder's extruded faces are
    such halves of rectangles)."""
    nodes = set(slave_nodes)
    near = set(near)
    elements = exodus_read.element_nodes(mesh)
    x, y, z = mesh["x"], mesh["y"], mesh["z"]
    areas = []
    for name, sides in mesh["side_sets"].items():
        tris = [t for e, s in sides for t in exodus_read.triangles_of(exodus_read.element_faces(elements[e])[s])]
        if not tris or not all(all(v in nodes for v in t) for t in tris):
            continue
        for a, b, c in tris:
            if not (a in near or b in near or c in near):
                continue
            u = (x[b] - x[a], y[b] - y[a], z[b] - z[a])
            v = (x[c] - x[a], y[c] - y[a], z[c] - z[a])
            w = (u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0])
            areas.append(0.5 * math.sqrt(w[0] ** 2 + w[1] ** 2 + w[2] ** 2))
        break
    return math.sqrt(2.0 * sum(areas) / len(areas)) if areas else float("nan")

# ---------------------------------------------------------------- Cattaneo-Mindlin


def stick_size(kind, b, ratio):
    """Analytic stick half-width / radius for Q/(F P) = ratio (0 <= ratio < 1)."""
    ratio = min(max(ratio, 0.0), 1.0)
    return b * math.sqrt(1.0 - ratio) if kind == "cylinder" else b * (1.0 - ratio) ** (1.0 / 3.0)


def traction(F, p0, b, c, s):
    """Cattaneo-Mindlin tangential traction at s (same formula for the strip and the circle)."""
    if s >= b:
        return 0.0
    q = F * p0 * math.sqrt(1.0 - (s / b) ** 2)
    if s < c:
        q -= F * p0 * (c / b) * math.sqrt(1.0 - (s / c) ** 2)
    return q


def stick_bracket(points):
    """points: (s, status). (largest s of a stick node, smallest s > it of a slip node)."""
    sticks = [s for s, st in points if st == 1]
    if not sticks:
        return None, min((s for s, st in points if st == 2), default=None)
    lo = max(sticks)
    hi = min((s for s, st in points if st == 2 and s > lo * (1.0 + 1e-9)), default=None)
    return lo, hi


def midpoint(lo, hi):
    if lo is None and hi is None:
        return None
    if lo is None:
        return 0.0
    if hi is None:
        return lo
    return 0.5 * (lo + hi)

# ---------------------------------------------------------------- main


def fmt(v, f="%.4f"):
    return "-" if v is None else f % v


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("kind", choices=["cylinder", "sphere"])
    ap.add_argument("result", help="Exodus file written by tribos --output")
    ap.add_argument("--step", type=int, default=None, help="time step, 1-based (default: the last)")
    ap.add_argument("--friction", type=float, default=0.3, help="Coulomb coefficient F")
    ap.add_argument("--E", type=float, default=210000.0, help="Young modulus of both bodies")
    ap.add_argument("--nu", type=float, default=0.3, help="Poisson ratio of both bodies")
    ap.add_argument("--R", type=float, default=10.0, help="radius of the curved body")
    ap.add_argument("--slave", default=None,
                    help="slave node set (default: the one of block_contact, cylinder_contact, sphere_contact with contact forces)")
    ap.add_argument("--profile", action="store_true", help="print the nodal tractions against the analytic ones")
    ap.add_argument("--json", action="store_true", help="print one JSON object instead of the text")
    args = ap.parse_args()

    kind, F = args.kind, args.friction
    try:
        r = read_result(args.result, args.step, args.slave)
    except (KeyError, IndexError, subprocess.CalledProcessError) as e:
        print("cattaneo_compare: %s: cannot read %s" % (args.result, e), file=sys.stderr)
        return 2
    x, y = r["x"], r["y"]
    fn, ft, pr, st = r["contact_normal"], r["contact_t1"], r["contact_pressure"], r["contact_status"]
    nodes = r["slave"]
    Es = hertz_compare.effective_modulus(args.E, args.nu, args.E, args.nu)

    # loads on the full body: per unit length (cylinder) or x2 (half sphere)
    if kind == "cylinder":
        ys = [y[n] for n in nodes]
        t = max(ys) - min(ys)
        scale = 1.0 / t
    else:
        t = None
        scale = 2.0
    P = scale * sum(fn[n] for n in nodes)
    Qs = scale * sum(ft[n] for n in nodes)
    Q = abs(Qs)
    sign = 1.0 if Qs >= 0.0 else -1.0
    Qx = scale * r["global"]["contact_force_x"] if "contact_force_x" in r["global"] else None
    if P <= 0.0:
        print("cattaneo_compare: %s: no normal contact force at step %d" % (args.result, r["step"]), file=sys.stderr)
        return 2
    b, p0 = hertz_compare.hertz(kind, P, args.R, Es)
    ratio = Q / (F * P)
    c = stick_size(kind, b, ratio)
    hertz_compare.NOISE = 1e-6 * p0

    def pos(n):
        return abs(x[n]) if kind == "cylinder" else math.hypot(x[n], y[n])

    contact = [n for n in nodes if pr[n] > hertz_compare.NOISE]
    # computed contact size (as hertz_compare.py)
    area = sum(fn[n] / pr[n] for n in contact)
    prof = sorted((pos(n), pr[n]) for n in nodes)
    s_in = max((pos(n) for n in contact), default=None)
    s_out = min((s for s, p in prof if p <= hertz_compare.NOISE and (s_in is None or s > s_in)), default=None)
    if kind == "cylinder":
        size_area = area / t / 2.0          # full width 2 b: area = 2 b t
        edges = []
        slices = {}
        for n in nodes:
            slices.setdefault(round(y[n] / 1e-6), []).append(n)
        for key in sorted(slices):
            for side in (1.0, -1.0):       # both sides of x = 0 (the full section)
                pr_side = sorted((abs(x[n]), pr[n]) for n in slices[key] if x[n] * side >= 0.0)
                e = hertz_compare.edge_estimate(pr_side)[2]
                if e is not None:
                    edges.append(e)
        size_edge = sum(edges) / len(edges) if edges else None
    else:
        size_area = math.sqrt(2.0 * area / math.pi)   # half circle: area = pi a^2 / 2
        size_edge = None

    # computed stick size
    lo, hi = stick_bracket([(pos(n), int(round(st[n]))) for n in contact])
    c_num = midpoint(lo, hi)
    per_slice = []
    if kind == "cylinder":
        for key in sorted(slices):
            sl = [n for n in slices[key] if pr[n] > hertz_compare.NOISE]
            slo, shi = stick_bracket([(pos(n), int(round(st[n]))) for n in sl])
            per_slice.append({"y": y[slices[key][0]], "stick_max": slo, "slip_min": shi, "c": midpoint(slo, shi),
                              "stick": sum(1 for n in sl if int(round(st[n])) == 1),
                              "slip": sum(1 for n in sl if int(round(st[n])) == 2)})
    h_slave = slave_element_size(r["mesh"], nodes, contact)
    # the stick size from the stick area (sum of the stick nodes' tributary areas), as the
    # contact size from the contact area: robust on an unstructured mesh, where the stick
    # boundary is ragged (it overshoots by about half an element, as the contact area does)
    stick_area = sum(fn[n] / pr[n] for n in contact if int(round(st[n])) == 1)
    c_area = stick_area / t / 2.0 if kind == "cylinder" else math.sqrt(2.0 * stick_area / math.pi)

    # traction errors over the nodes in contact
    rows = []
    for n in contact:
        s = pos(n)
        a_n = fn[n] / pr[n]
        q = sign * ft[n] / a_n
        rows.append((s, y[n], x[n], q, traction(F, p0, b, c, s), pr[n], hertz_compare.hertz_p(p0, b, s), int(round(st[n]))))
    dq = [(q - qa) / (F * p0) for _, _, _, q, qa, _, _, _ in rows]
    dp = [(p - pa) / p0 for _, _, _, _, _, p, pa, _ in rows]
    q_rms = math.sqrt(sum(d * d for d in dq) / len(dq)) if dq else None
    q_max = max((abs(d) for d in dq), default=None)
    p_rms = math.sqrt(sum(d * d for d in dp) / len(dp)) if dp else None

    def rms_of(status):
        d = [e for e, row in zip(dq, rows) if row[7] == status]
        return math.sqrt(sum(v * v for v in d) / len(d)) if d else None
    q_rms_stick, q_rms_slip = rms_of(1), rms_of(2)

    wname = "b" if kind == "cylinder" else "a"
    out = {
        "kind": kind, "file": args.result, "step": r["step"], "steps": r["steps"], "slave": r["slave_name"],
        "friction": F, "E_star": Es, "R": args.R, "slice_thickness": t,
        "P": P, "Q": Q, "Q_signed": Qs, "Q_global_x": Qx, "load_ratio": ratio,
        "hertz_size": b, "p0": p0,
        "contact_size_edge": size_edge, "contact_size_area": size_area,
        "contact_last_positive": s_in, "contact_first_zero": s_out,
        "c_analytic": c, "c_computed": c_num, "c_bracket": [lo, hi], "c_area": c_area,
        "slave_element_size": h_slave,
        "nodes_in_contact": len(contact),
        "stick_nodes": sum(1 for n in contact if int(round(st[n])) == 1),
        "slip_nodes": sum(1 for n in contact if int(round(st[n])) == 2),
        "q_rms": q_rms, "q_max": q_max, "q_rms_stick": q_rms_stick, "q_rms_slip": q_rms_slip, "p_rms": p_rms,
    }
    if per_slice:
        out["slices"] = per_slice
    if args.json:
        print(json.dumps(out, indent=1, sort_keys=True))
        return 0

    unit = "N/mm" if kind == "cylinder" else "N"
    print("%s: step %d of %d, %d slave nodes (%s), %d in contact (%d stick, %d slip)"
          % (args.result, r["step"], r["steps"], len(nodes), r["slave_name"], len(contact),
             out["stick_nodes"], out["slip_nodes"]))
    print("loads %s: P = %.2f %s, Q = %.2f %s (sum of contact_t1; global contact_force_x: %s), Q/(F P) = %.4f (F = %g)"
          % ("per unit length (slice t = %g)" % t if kind == "cylinder" else "on the full sphere (half model x 2)",
             P, unit, Qs, unit, fmt(Qx, "%.2f"), ratio, F))
    print("Hertz: E* = %.1f, R = %g -> %s = %.4f, p0 = %.1f" % (Es, args.R, wname, b, p0))
    if kind == "cylinder":
        print("contact half-width: edge %s (%s), from the area %.4f (%s); last p > 0 at |x| = %s, first p = 0 at %s"
              % (fmt(size_edge), hertz_compare.rel(size_edge, b) if size_edge else "", size_area,
                 hertz_compare.rel(size_area, b), fmt(s_in), fmt(s_out)))
    else:
        print("contact radius: from the area %.4f (%s); last p > 0 at r = %s, first p = 0 at %s"
              % (size_area, hertz_compare.rel(size_area, b), fmt(s_in), fmt(s_out)))
    print("stick %s: analytic c = %.4f (c/%s = %.3f); computed %s, bracket [%s, %s] (last stick, first slip beyond); "
          "slave element size %.4f"
          % ("half-width" if kind == "cylinder" else "radius", c, wname, c / b, fmt(c_num), fmt(lo), fmt(hi), h_slave))
    print("  from the stick area (sum of the stick nodes' tributary areas): %.4f (%s)" % (c_area, hertz_compare.rel(c_area, c)))
    if per_slice:
        print("%-10s %6s %6s %10s %10s %10s" % ("slice y", "stick", "slip", "last stick", "first slip", "c"))
        for s in per_slice:
            print("%-10.4g %6d %6d %10s %10s %10s" % (s["y"], s["stick"], s["slip"], fmt(s["stick_max"]),
                                                    fmt(s["slip_min"]), fmt(s["c"])))
    print("tangential traction q = contact_t1 / tributary area against Cattaneo-Mindlin over %d nodes: "
          "rms %s, max %s of F p0 = %.1f"
          % (len(rows), fmt(q_rms, "%.4f"), fmt(q_max, "%.4f"), F * p0))
    print("  rms over the stick nodes %s, over the slip nodes %s" % (fmt(q_rms_stick), fmt(q_rms_slip)))
    print("pressure against Hertz over the same nodes: rms %s of p0" % fmt(p_rms, "%.4f"))
    if args.profile:
        print("%9s %9s %9s %10s %10s %10s %10s %6s" % ("|x|" if kind == "cylinder" else "r", "y", "x", "q", "q CM",
                                                    "p", "p Hertz", "status"))
        for s, yy, xx, q, qa, p, pa, stt in sorted(rows, key=lambda v: (round(v[1], 6), v[0]) if kind == "cylinder" else v[0]):
            print("%9.4f %9.4f %9.4f %10.1f %10.1f %10.1f %10.1f %6d" % (s, yy, xx, q, qa, p, pa, stt))
    return 0


if __name__ == "__main__":
    signal.signal(signal.SIGPIPE, signal.SIG_DFL)  # quiet when piped into head
    sys.exit(main())
