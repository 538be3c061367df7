"""Tip deflection of the slender cantilever (input/cantilever_*.xml, issue 32) against
Timoshenko's beam theory.

Beam L x H x H (x along the beam), clamped at x = 0 (every component of the node set "clamped"),
a uniform traction of total P in -z on the face x = L (side set "tip"). Reference:
    delta = P L^3 / (3 E I) + P L / (k G A),  I = H^4 / 12, A = H^2, G = E / (2 (1 + nu)),
    k = 10 (1 + nu) / (12 + 11 nu)            (Cowper's shear coefficient of a rectangle)
Two measures of the computed tip deflection:
    tip mean  -(mean u_z over the nodes of the node set "tip") from the Exodus result, and
    2U/P      twice the strain energy of the summary JSON over P (the load's work conjugate:
              the area-weighted mean deflection of the loaded face).
Errors are relative to delta, (computed - delta) / delta (negative: too stiff).

Usage: python3 cantilever_compare.py RESULT.exo SUMMARY.json [--E 2.1e5] [--nu 0.3] [--L 10]
       [--H 1] [--P 1] [--json]
Reads the Exodus file with ncdump (exodus_read.py).
"""
import argparse
import json
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import exodus_read  # noqa: E402


def timoshenko(E, nu, L, H, P):
    """(delta, Euler-Bernoulli part, shear part, k)."""
    inertia = H ** 4 / 12.0
    area = H * H
    G = E / (2.0 * (1.0 + nu))
    k = 10.0 * (1.0 + nu) / (12.0 + 11.0 * nu)
    bending = P * L ** 3 / (3.0 * E * inertia)
    shear = P * L / (k * G * area)
    return bending + shear, bending, shear, k


def compare(result, summary, E=2.1e5, nu=0.3, L=10.0, H=1.0, P=1.0):
    header = exodus_read.ncdump_header(result)
    mesh = exodus_read.read_mesh(result, header)
    uz = exodus_read.last_step_nodal(result, header, ["displ_z"])["displ_z"]
    tip = mesh["node_sets"]["tip"]
    tip_mean = -sum(uz[n] for n in tip) / len(tip)
    with open(summary) as f:
        s = json.load(f)
    energy_deflection = 2.0 * s["strain_energy"] / P
    delta, bending, shear, k = timoshenko(E, nu, L, H, P)
    nodes_per_element = sorted({len(e) for _, elements in mesh["blocks"] for e in elements})
    return {
        "result": result,
        "nodes_per_element": nodes_per_element,
        "n_nodes": s["n_nodes"],
        "n_elements": s["n_elements"],
        "n_primal": s["n_primal"],
        "n_dofs": 3 * s["n_nodes"],
        "n_subdomains": s["n_subdomains"],
        "f_applications": s["pfp_applications"],
        "factor_nonzeros": s.get("factor_nonzeros"),
        "converged": s["converged"],
        "timoshenko": delta,
        "euler_bernoulli": bending,
        "shear_part": shear,
        "shear_coefficient": k,
        "tip_mean": tip_mean,
        "tip_nodes": len(tip),
        "energy_deflection": energy_deflection,
        "error_tip_mean": (tip_mean - delta) / delta,
        "error_energy": (energy_deflection - delta) / delta,
    }


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("result")
    parser.add_argument("summary")
    parser.add_argument("--E", type=float, default=2.1e5)
    parser.add_argument("--nu", type=float, default=0.3)
    parser.add_argument("--L", type=float, default=10.0)
    parser.add_argument("--H", type=float, default=1.0)
    parser.add_argument("--P", type=float, default=1.0)
    parser.add_argument("--json", action="store_true", help="print the comparison as JSON")
    a = parser.parse_args()
    r = compare(a.result, a.summary, a.E, a.nu, a.L, a.H, a.P)
    if a.json:
        print(json.dumps(r, indent=2, sort_keys=True))
        return
    print("Timoshenko %.6f (Euler-Bernoulli %.6f + shear %.6f, k = %.4f)"
          % (r["timoshenko"], r["euler_bernoulli"], r["shear_part"], r["shear_coefficient"]))
    print("%s: %d nodes, %d elements (%s nodes each): tip mean %.6f (%+.2f %%), 2U/P %.6f (%+.2f %%)"
          % (a.result, r["n_nodes"], r["n_elements"], "/".join(str(n) for n in r["nodes_per_element"]),
             r["tip_mean"], 100 * r["error_tip_mean"], r["energy_deflection"], 100 * r["error_energy"]))


if __name__ == "__main__":
    main()
