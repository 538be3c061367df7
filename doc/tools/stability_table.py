"""Markdown tables of the stability sweeps (doc/tools/stability_sweeps.sh writes the manifest).

Manifest lines: section, label, exit status, base path (base.json summary, base.log console,
base.exo results). Per run: exit status, behaviour, counts, the largest relative KKT residual,
contact status counts, the solver's message. The "scaling" section also compares the
displacements with the unit load's: max |u(s f) / s - u(f)| / max |u(f)| (doc/stability.md).
"""
import json
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import exodus_read  # noqa: E402

# The relative KKT residuals of the discrete problem (all must be <= kkt.tolerance).
KKT = ("equilibrium", "gluing_dirichlet", "non_penetration", "complementarity", "normal_sign",
       "friction_admissibility", "slip_rule", "stick_rule")


def behaviour(status, summary, message):
    if status == 124:
        return "no end (killed at 120 s)"
    if status == 2:
        return "refused (input error)"
    if summary is None:
        return "failed (exit %d)" % status
    if summary.get("converged"):
        return "converges"
    if "diverge" in message:
        return "diverges"
    if "Max Outer Iterations" in message:
        return "stagnates (outer cap)"
    if "KKT residual" in message:
        return "inaccurate (KKT)"
    return "not converged"


def fmt(x):
    if x is None:
        return "NaN"
    if isinstance(x, float) and math.isinf(x):
        return "inf"
    return "%.1e" % x if isinstance(x, float) else str(x)


def last_message(log):
    """The error line of a refused run (exit 2) or the last line of the console."""
    lines = [l.strip() for l in open(log, errors="replace").read().splitlines() if l.strip()]
    for l in lines:
        if "error:" in l:
            return l
    return lines[-1] if lines else ""


def displacements(exo):
    header = exodus_read.ncdump_header(exo)
    u = exodus_read.last_step_nodal(exo, header, ["displ_x", "displ_y", "displ_z"])
    return [c for xyz in zip(u["displ_x"], u["displ_y"], u["displ_z"]) for c in xyz]


def longest_growth(summary):
    """The most consecutive updates in which the slip-bound change grew (the divergence test
    of the inexact fixed point fires at 8, after 3 updates)."""
    changes = [h.get("slip_bound_change") for h in summary.get("history", [])]
    run = longest = 0
    for a, b in zip(changes, changes[1:]):
        run = run + 1 if a is not None and b is not None and b > a else 0
        longest = max(longest, run)
    return longest


def scale_of(label):
    return float(label.rsplit("x", 1)[1])


def main(manifest):
    rows = [l.rstrip("\n").split("\t") for l in open(manifest) if l.strip()]
    sections = []
    for section, label, status, base in rows:
        if section not in sections:
            sections.append(section)
    for section in sections:
        print("\n#### %s\n" % section)
        head = "| case | exit | behaviour | outer | PFP | g updates | last dg | dg growths in a row | max KKT | no contact/stick/slip |"
        if section == "scaling":
            head += " u deviation |"
        print(head + " message |")
        print("|" + "---|" * (head.count("|") - 1 + 1))
        reference = {}
        for sec, label, status, base in rows:
            if sec != section:
                continue
            status = int(status)
            summary = None
            if status != 2 and os.path.exists(base + ".json"):
                summary = json.load(open(base + ".json"))
            message = summary.get("message", "") if summary else last_message(base + ".log")
            cells = [label, str(status), behaviour(status, summary, message)]
            if summary:
                kkt = summary.get("kkt", {})
                values = [kkt.get(k) for k in KKT if k in kkt]
                worst = float("nan") if any(v is None for v in values) else max(values, default=0.0)
                nodes = summary.get("contact_nodes", {})
                cells += [str(summary.get("outer_iterations", "")), str(summary.get("pfp_applications", "")),
                          str(summary.get("fixed_point_iterations", "")), fmt(summary.get("fixed_point_change")),
                          str(longest_growth(summary)), fmt(worst), "%s/%s/%s" % (nodes.get("no_contact"), nodes.get("stick"), nodes.get("slip"))]
            else:
                cells += [""] * 7
            if section == "scaling":
                deviation = ""
                if summary and os.path.exists(base + ".exo"):
                    model = label.split(",")[0]
                    u = displacements(base + ".exo")
                    s = scale_of(label)
                    if s == 1.0:
                        reference[model] = u
                    ref = reference.get(model)
                    if ref is not None:
                        top = max(abs(x) for x in ref)
                        deviation = fmt(max(abs(a / s - b) for a, b in zip(u, ref)) / top)
                cells.append(deviation)
            cells.append(message.replace("||", "‖").replace("|", "/")[:200])
            print("| " + " | ".join(cells) + " |")


if __name__ == "__main__":
    main(sys.argv[1])
