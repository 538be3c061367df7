#!/usr/bin/env python3
"""The tangential load cycle of a Cattaneo-Mindlin sphere history against Mindlin-Deresiewicz.

Usage:
  python3 doc/tools/mindlin_loop.py SUMMARY.json [--scene input/cattaneo_sphere.xml] [--json]

SUMMARY.json is written by `tribos --summary` for input/cattaneo_sphere.xml (a half model by
y = 0, the top face displacement-driven) with a Load Steps history of this shape: step 1 the
normal approach alone ("top shear" factor 0), then the shear factor raised to its largest value
A, lowered to -A and raised to A again. For example, with 4 steps up and 8 per reversal:
  {0, A/4, A/2, 3A/4, A, A/2, 0, ..., -A, ..., A}.

Two identical elastic bodies (K. L. Johnson, Contact Mechanics, 1985, Sec. 7.2-7.3; the
compliances of both bodies summed):
  - first loading, for the relative displacement of remote points:
      delta(Q) = K [1 - (1 - x)^(2/3)],  x = Q/(mu P),  K = 3 mu P (2 - nu) / (8 G a);
  - the unloading and reloading branches follow from it by Masing's rule (Mindlin and
    Deresiewicz), and the energy one cycle Q* -> -Q* -> Q* dissipates is
      W = 9 mu^2 P^2 (2 - nu) / (5 G a) [1 - (1 - x*)^(5/3) - (5 x*/6) (1 + (1 - x*)^(2/3))],
    about (2 - nu) Q*^3 / (18 G a mu P) for small x*.
    (This closed form was checked here against a numerical integration of the Masing branches
    of delta(Q): they agree to 1e-10.)
The model's top face is R away from the contact, so its prescribed displacement adds the
bodies' linear (elastic) compliance to delta: the first-loading steps are fitted by
delta = alpha x + K g(x), g(x) = 1 - (1 - x)^(2/3) - 2x/3 (the part beyond the initial slope),
and the fitted K is compared with Johnson's. The linear part dissipates nothing, so the cycle's
energy compares directly, measured two ways: the dissipated energy the solver accumulates (the
step's end force times its slip increment at the slipping nodes), and the area of the loop of
Q against the prescribed displacement (trapezoids).
P and Q are twice the interface's normal force and contact force along x (the half model); the
analytic a and K use the measured P; mu, E and nu are the scene's (--friction, --E, --nu, --R).
Exit status 0, or 2 for a summary without such a history.
"""
import argparse
import json
import math
import sys
import xml.etree.ElementTree as ElementTree


def top_shear_displacement(scene):
    """The x value of Boundary/top shear/Displacement in the scene file."""
    for plist in ElementTree.parse(scene).getroot().iter("ParameterList"):
        if plist.get("name") == "top shear":
            for p in plist.iter("Parameter"):
                if p.get("name") == "Displacement":
                    return float(p.get("value").strip("{} ").split(",")[0])
    raise KeyError("no Boundary/top shear/Displacement in " + scene)


def masing_energy(mu, P, G, nu, a, x):
    return 9 * mu**2 * P**2 * (2 - nu) / (5 * G * a) * (1 - (1 - x) ** (5 / 3) - 5 * x / 6 * (1 + (1 - x) ** (2 / 3)))


def fit_compliance(xs, ds):
    """Least squares of ds = alpha x + K g(x) over the loading steps: (alpha, K)."""
    g = [1 - (1 - x) ** (2 / 3) - 2 * x / 3 for x in xs]
    s11 = sum(x * x for x in xs)
    s12 = sum(x * gx for x, gx in zip(xs, g))
    s22 = sum(gx * gx for gx in g)
    b1 = sum(x * d for x, d in zip(xs, ds))
    b2 = sum(gx * d for gx, d in zip(g, ds))
    det = s11 * s22 - s12 * s12
    return (b1 * s22 - b2 * s12) / det, (s11 * b2 - s12 * b1) / det


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("summary")
    ap.add_argument("--scene", default="input/cattaneo_sphere.xml", help="the scene file (its top shear)")
    ap.add_argument("--friction", type=float, default=0.3)
    ap.add_argument("--E", type=float, default=210000.0)
    ap.add_argument("--nu", type=float, default=0.3)
    ap.add_argument("--R", type=float, default=10.0)
    ap.add_argument("--interface", type=int, default=0, help="index into the summary's interfaces")
    ap.add_argument("--json", action="store_true", help="print one JSON object")
    args = ap.parse_args()
    with open(args.summary) as f:
        steps = json.load(f).get("steps", [])
    try:
        base = top_shear_displacement(args.scene)
        factors = [k["factors"]["top shear"] for k in steps]
    except (KeyError, OSError, ElementTree.ParseError) as e:
        print("mindlin_loop.py: %s" % e, file=sys.stderr)
        return 2
    top = max(factors) if factors else 0.0
    first = factors.index(top) if factors else 0
    if len(steps) < 4 or factors[0] != 0.0 or factors[-1] != top or min(factors) != -top or first == len(steps) - 1:
        print("mindlin_loop.py: %s: not a history 0 -> A -> -A -> A of Load Steps/top shear/Factors" % args.summary,
              file=sys.stderr)
        return 2
    mu, nu = args.friction, args.nu
    G = args.E / (2 * (1 + nu))
    e_star = args.E / (2 * (1 - nu * nu))
    interface = [k["interfaces"][args.interface] for k in steps]
    P = 2 * interface[0]["normal_force"]
    Q = [2 * i["contact_force"][0] for i in interface]
    d = [base * f for f in factors]
    dissipated = [2 * k["dissipated_energy"] for k in steps]
    a = (3 * P * args.R / (4 * e_star)) ** (1 / 3)
    K = 3 * mu * P * (2 - nu) / (8 * G * a)
    x_star = Q[first] / (mu * P)
    W = masing_energy(mu, P, G, nu, a, x_star)
    alpha, K_fit = fit_compliance([q / (mu * P) for q in Q[1:first + 1]], d[1:first + 1])
    out = {
        "P": P, "Q_star": Q[first], "load_ratio": x_star, "a": a,
        "energy_analytic": W,
        "energy_dissipated": dissipated[-1] - dissipated[first],
        "energy_loop_area": sum(0.5 * (Q[k] + Q[k - 1]) * (d[k] - d[k - 1]) for k in range(first + 1, len(steps))),
        "K_analytic": K, "K_fitted": K_fit, "linear_compliance": alpha,
        "steps": len(steps), "converged": all(k["converged"] for k in steps),
    }
    if args.json:
        print(json.dumps(out, indent=1, sort_keys=True))
        return 0
    rel = lambda v, ref: 100.0 * (v - ref) / ref
    print("P = %.1f N, Q* = %.1f N, Q*/(mu P) = %.4f, a = %.4f mm, %d steps" % (P, Q[first], x_star, a, len(steps)))
    print("energy per cycle: Mindlin-Deresiewicz %.4f N mm; dissipated %.4f (%+.1f %%); loop area %.4f (%+.1f %%)"
          % (W, out["energy_dissipated"], rel(out["energy_dissipated"], W), out["energy_loop_area"],
             rel(out["energy_loop_area"], W)))
    print("first loading: K fitted %.5f mm against Johnson's %.5f (%+.1f %%); linear part %.5f mm"
          % (K_fit, K, rel(K_fit, K), alpha))
    return 0


if __name__ == "__main__":
    sys.exit(main())
