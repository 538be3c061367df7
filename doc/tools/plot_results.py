#!/usr/bin/env python3
"""Pictures of a Tribos contact solve, from its Exodus result and its JSON summary.

Usage:
  python3 doc/tools/plot_results.py RESULT.exo SUMMARY.json OUTDIR [--slave SIDE_SET] [--scale S]
                                    [--profile X0,Y0,Z0:X1,Y1,Z1 [--profile-samples N]] [--dpi N]
                                    [--step K] [--history NODE_SET[:COMPONENT]]

  RESULT.exo    written by `tribos --output RESULT.exo`; of a load history (Load Steps) one
                time step per load step, the maps, profile and deformed shape drawn at the
                last one unless --step says otherwise
  SUMMARY.json  written by `tribos --summary SUMMARY.json` (its "history" and "interfaces",
                and with --step its "steps")
  OUTDIR        created if missing; receives
    contact_stress.png  normal and tangential contact stress on the slave surface, over its two
                        in-plane coordinates, with the contact zone and the stick zone outlined
                        (the paper's Figs. 2-3), when the scene has one contact interface
    contact_stress_<NAME>.png
                        the same map for each interface when the summary lists several; NAME is
                        the interface's Contact/<NAME> sublist (its slave side set when unnamed).
                        Each map's title gives the interface, its normal force and the summary's
                        counts of no-contact, stick and slip nodes
    convergence.png     ||g^P||, ||G mu|| and the slip-bound change per SMALSE-M outer
                        iteration, and the PFP applications and inner iterations
    deformed.png        the boundary of the bodies warped by the displacements (magnified)
    profile.csv, profile.png
                        with --profile: the contact stresses along a straight segment (below)
    history.csv, history.png
                        with --history: the force-displacement history of a load history (below)

  --slave NAME  draw contact_stress.png of this side set only, whatever the summary's
                interfaces. Without it the slave side sets are the summary's "interfaces"
                (the part of "SLAVE -> MASTER" before the arrow); a summary without
                "interfaces" falls back to the smallest side set holding every node with a
                contact force, e.g. contact_aluminium in input/two_bricks.xml
  --scale S     displacement magnification of deformed.png (default: the largest displacement
                drawn as 8 % of the model's size)
  --profile X0,Y0,Z0:X1,Y1,Z1
                sample the segment from (X0,Y0,Z0) to (X1,Y1,Z1) at --profile-samples evenly
                spaced points (default 200, both ends included). Each point takes the nearest
                triangle of the slave surfaces drawn (the closest point on the triangle, so a
                point above a flat surface takes the triangle below it along the normal) and
                interpolates the nodal normal and tangential stress linearly (barycentric) at
                that closest point. profile.csv has the header
                s,x,y,z,interface,pressure,tangential_stress with s the distance from the first
                point and x,y,z the sample point on the segment; a point farther from every
                slave triangle than 5 % of the segment's length keeps its row with the last
                three columns empty (a gap in profile.png), so that rows stay evenly spaced
                in s. profile.png draws both stresses against s.
  --dpi N       resolution of the PNGs (default 100)
  --step K      draw the contact stress maps, the profile and deformed.png at time step K
                (1-based, 1 to the result's number of steps; default the last). The maps'
                titles then take the counts and normal force of the summary's steps[K-1], and
                the pictures of a result of several steps name the step and its time (those
                of a one-step result are unchanged)
  --history NODE_SET[:COMPONENT]
                the load history seen from a node set (e.g. the loaded face's, block_top in
                input/block_on_plate.xml); COMPONENT x, y or z, default the one along which the
                node set's mean displacement changes most (from the unloaded state over the
                steps). history.csv has one row per time step with the header
                  time,step,converged,displ_x,displ_y,displ_z,reaction_x,reaction_y,reaction_z,
                  <I>_force_x,<I>_force_y,<I>_force_z,<I>_dissipated_energy (each interface I),
                  dissipated_energy
                step 1-based, converged 1 or 0 (the global variable converged), displ_* the mean
                displacement of the node set's nodes, reaction_* the sum of reaction_x/y/z over
                them (empty cells when none of its nodes is prescribed, i.e. every reaction is
                zero at every step), <I>_force_* the resultant contact force of interface I on
                its master body (global variables <I>_force_x/y/z; I is the Contact/<I> sublist's
                name, "contact" for a flat Contact list), <I>_dissipated_energy and
                dissipated_energy the frictional dissipation so far (of I, and in all).
                history.png: (a) each interface's force along COMPONENT and, when not zero, the
                node set's reaction sum along COMPONENT against its mean displacement along
                COMPONENT, the steps joined in order from the unloaded state (0, 0) and
                numbered (every step up to 12 steps, sparser beyond; unconverged steps always),
                unconverged steps drawn as hollow red markers: a hysteresis loop under a
                reversed friction load; (b) the dissipated energy against time

Normal stress: the nodal variable contact_pressure (normal force per tributary area);
tangential stress: |(contact_t1, contact_t2)| per tributary area (a third of the slave faces
around the node). Every number drawn or written is in the scene's units (its mesh's lengths,
its loads' forces: mm, N and N mm = mJ for the MPa scenes). Zones from contact_status (0 none, 1 stick, 2 slip):
the lines are where the indicator of "in contact" and of "stick", interpolated linearly on the
surface, crosses 1/2, i.e. half-way between nodes of different status.

Needs python3-matplotlib (numpy comes with it) and python3-netcdf4 or ncdump (netcdf-bin) on Debian.
Exit status: 0 written, 2 bad input (missing file, variable, side set or node set, bad
--profile, --step or --history),
77 matplotlib missing, or both netCDF4 and ncdump (the CTest reports a skip).
"""
import argparse
import io
import json
import math
import os
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import exodus_read  # noqa: E402  (the shared ncdump reader next to this script)

try:
    import matplotlib
    matplotlib.use("Agg")  # files only, no display needed
    import matplotlib.pyplot as plt
    import matplotlib.tri as mtri
    import numpy as np
    from matplotlib.collections import PolyCollection
    from matplotlib.lines import Line2D
    from matplotlib.ticker import MaxNLocator
    from mpl_toolkits.mplot3d.art3d import Poly3DCollection
    from PIL import Image  # comes with matplotlib
except ImportError as missing:
    print("plot_results.py: needs matplotlib and numpy (apt-get install python3-matplotlib): %s" % missing,
          file=sys.stderr)
    sys.exit(77)

AXES = "xyz"
STATUS_NAMES = ("no contact", "stick", "slip")

# ---------------------------------------------------------------- data


def save(fig, out, dpi):
    """A PNG with a 256-colour palette: a third of the size of a true-colour one (pictures
    committed under doc/figures stay small), no visible loss on these flat-shaded plots."""
    buffer = io.BytesIO()
    fig.savefig(buffer, format="png", dpi=dpi)
    plt.close(fig)
    Image.open(buffer).convert("RGB").quantize(colors=256).save(out, optimize=True)


CONTACT_FIELDS = ("contact_normal", "contact_t1", "contact_t2", "contact_status", "contact_pressure")


def read_result(path, step):
    """Header, mesh, coordinates, the nodal fields of time step `step` (1-based, 0: the last;
    the contact ones only if present), the step drawn (1-based) and the number of steps."""
    header = exodus_read.ncdump_header(path)
    mesh = exodus_read.read_mesh(path, header)
    names = ["displ_x", "displ_y", "displ_z"]
    if set(CONTACT_FIELDS) <= set(exodus_read.nodal_variable_names(path, header)):
        names += CONTACT_FIELDS
    steps = exodus_read.nodal_steps(path, header, names)
    count = len(steps["displ_x"])
    if count == 0:
        raise ValueError("%s: no time step written" % path)
    if not 0 <= step <= count:
        raise ValueError("--step %d: the result has %d time step%s (1 to %d)" % (step, count, "s" * (count > 1),
                                                                                  count))
    step = step or count
    coords = np.column_stack([mesh["x"], mesh["y"], mesh["z"]])
    return header, mesh, coords, {k: np.asarray(v[step - 1]) for k, v in steps.items()}, step, count


def step_summary(summary, step, count):
    """The summary with "interfaces" of time step `step` (its steps[step - 1]) when that is not
    the last step; the summary itself for the last (its own "interfaces" describe it)."""
    steps = summary.get("steps") or []
    if step == count or len(steps) != count:
        return summary
    return dict(summary, interfaces=steps[step - 1].get("interfaces") or [])


def step_label(step, count, times):
    """"step K of N, time t" for a result of several steps, "" for one step (titles unchanged)."""
    if count <= 1:
        return ""
    return "step %d of %d, time %.4g" % (step, count, times[step - 1]) if len(times) == count else \
        "step %d of %d" % (step, count)


def slave_side_set(mesh, fields, requested):
    """The named side set, or the smallest one that holds every node with a contact force."""
    if requested:
        if requested not in mesh["side_sets"]:
            raise KeyError("side set " + requested + " (the file has: " + ", ".join(mesh["side_sets"]) + ")")
        return requested
    loaded = set(np.nonzero((np.abs(fields["contact_normal"]) > 0) | (fields["contact_status"] > 0))[0])
    candidates = []
    for name in mesh["side_sets"]:
        nodes = {n for tri in exodus_read.side_set_triangles(mesh, name) for n in tri}
        if loaded and loaded <= nodes:
            candidates.append((len(nodes), name))
    if not candidates:
        raise KeyError("no side set holds the contact nodes (no contact force anywhere?); name it with --slave")
    return min(candidates)[1]


def interface_surfaces(summary, mesh, fields, requested):
    """The slave surfaces to draw, as dicts {label, slave, entry, png}: one per entry of the
    summary's "interfaces" (a multi-interface scene has one slave side set per interface, and a
    single map of one of them would hide the others), or the --slave side set, or the default
    guess when the summary predates "interfaces". entry is the summary's interface object or
    None."""
    interfaces = summary.get("interfaces") or []
    if requested:
        slave = slave_side_set(mesh, fields, requested)
        entry = next((e for e in interfaces if slave_of(e) == slave), None)
        return [dict(label=slave, slave=slave, entry=entry, png="contact_stress.png")]
    if not interfaces:
        slave = slave_side_set(mesh, fields, "")
        return [dict(label=slave, slave=slave, entry=None, png="contact_stress.png")]
    surfaces = []
    for entry in interfaces:
        slave = slave_side_set(mesh, fields, slave_of(entry))
        label = entry.get("name") or slave
        png = "contact_stress.png" if len(interfaces) == 1 else "contact_stress_%s.png" % label
        surfaces.append(dict(label=label, slave=slave, entry=entry, png=png))
    return surfaces


def slave_of(entry):
    """The slave side set of a summary interface, whose "interface" reads "SLAVE -> MASTER"."""
    return entry["interface"].split(" -> ")[0].strip()


def in_plane_axes(points):
    """The two coordinate axes of largest extent (the surface's or the model's plane)."""
    extent = points.max(axis=0) - points.min(axis=0)
    return sorted(np.argsort(extent)[1:])


def tributary_area(coords, triangles):
    area = np.zeros(len(coords))
    for tri in triangles:
        a, b, c = coords[list(tri)]
        share = 0.5 * np.linalg.norm(np.cross(b - a, c - a)) / 3.0
        area[list(tri)] += share
    return area

def tangential_stress(coords, fields, triangles):
    """|(contact_t1, contact_t2)| per tributary area at every node (zero off the triangles):
    the solver writes tangential forces, the maps and profiles compare them with pressures."""
    area = tributary_area(coords, triangles)
    force = np.hypot(fields["contact_t1"], fields["contact_t2"])
    return np.where(area > 0, force / np.where(area > 0, area, 1.0), 0.0)

# ---------------------------------------------------------------- contact stress maps


def outline_zones(ax, triangulation, status):
    """Contact zone (solid) and stick zone (dashed) boundaries; returns legend handles."""
    handles = []
    for indicator, style, label in ((status > 0.5, "-", "contact zone"), (np.abs(status - 1.0) < 0.5, "--",
                                                                           "stick zone")):
        values = indicator.astype(float)
        if values.min() < 0.5 < values.max():  # the zone exists and is not everything
            ax.tricontour(triangulation, values, levels=[0.5], colors="k", linestyles=style, linewidths=1.4)
            handles.append(Line2D([], [], color="k", linestyle=style, label=label + " boundary"))
    return handles


def zoom_to_contact(ax, u, v, status):
    """Frame a small contact zone (less than half the surface each way, as in Hertz contact)
    with a margin, so that it fills the picture."""
    inside = status > 0.5
    if not inside.any():
        return
    lo = np.array([u[inside].min(), v[inside].min()])
    hi = np.array([u[inside].max(), v[inside].max()])
    if np.any(hi - lo > 0.5 * np.array([np.ptp(u), np.ptp(v)])):
        return
    margin = 0.4 * max((hi - lo).max(), 1e-12)
    ax.set_xlim(max(lo[0] - margin, u.min()), min(hi[0] + margin, u.max()))
    ax.set_ylim(max(lo[1] - margin, v.min()), min(hi[1] + margin, v.max()))


def map_title(surface, counts):
    """The interface, its normal force and its node counts: from the summary when it lists the
    interface (the counts of the nodes the solver paired), else counted from contact_status
    over the whole side set."""
    entry = surface["entry"]
    if entry is None:
        return "slave surface %s: %d no contact, %d stick, %d slip nodes" % (surface["slave"], *counts)
    name = surface["label"] + " (%s)" % entry["interface"] if entry.get("name") else entry["interface"]
    return "interface %s: normal force %.4g; %d no contact, %d stick, %d slip nodes" % (
        name, entry["normal_force"], entry["no_contact"], entry["stick"], entry["slip"])


def plot_contact(mesh, coords, fields, surface, out, dpi, label=""):
    triangles = exodus_read.side_set_triangles(mesh, surface["slave"])
    nodes = sorted({n for tri in triangles for n in tri})
    local = {n: i for i, n in enumerate(nodes)}
    i, j = in_plane_axes(coords[nodes])
    triangulation = mtri.Triangulation(coords[nodes, i], coords[nodes, j],
                                       [[local[n] for n in tri] for tri in triangles])
    status = fields["contact_status"][nodes]
    normal = fields["contact_pressure"][nodes]
    tangential = tangential_stress(coords, fields, triangles)[nodes]
    counts = [int(np.sum(np.rint(status) == s)) for s in range(3)]

    fig, axes = plt.subplots(1, 2, figsize=(11, 4.2), constrained_layout=True)
    for ax, values, title in ((axes[0], normal, "normal contact stress"),
                              (axes[1], tangential, "tangential contact stress |t|")):
        top = values.max() if values.max() > 0 else 1.0
        levels = MaxNLocator(nbins=20).tick_values(0.0, top)
        filled = ax.tricontourf(triangulation, values, levels=levels, cmap="viridis")
        fig.colorbar(filled, ax=ax, shrink=0.9, label="force / area")
        handles = outline_zones(ax, triangulation, status)
        ax.set_aspect("equal")
        zoom_to_contact(ax, triangulation.x, triangulation.y, status)
        ax.set_xlabel(AXES[i])
        ax.set_ylabel(AXES[j])
        ax.set_title("%s (max %.4g)" % (title, values.max()))
    if handles:
        axes[1].legend(handles=handles, loc="upper right", fontsize=8, framealpha=0.8)
    fig.suptitle(map_title(surface, counts) + ("\n" + label if label else ""))
    save(fig, out, dpi)

# ---------------------------------------------------------------- pressure profile


def parse_segment(text):
    """"X0,Y0,Z0:X1,Y1,Z1" as two points; ValueError (exit 2) for anything else."""
    ends = text.split(":")
    points = [np.array([float(v) for v in end.split(",")]) for end in ends]
    if len(points) != 2 or any(len(p) != 3 for p in points):
        raise ValueError("--profile %s: expected X0,Y0,Z0:X1,Y1,Z1" % text)
    if np.linalg.norm(points[1] - points[0]) == 0:
        raise ValueError("--profile %s: the two points coincide" % text)
    return points


def closest_on_triangles(p, a, b, c):
    """Distance from p to each triangle (a[k], b[k], c[k]) and the barycentric coordinates of
    the closest point: inside the face it is p's projection along the normal, else the closest
    point of an edge; taking the smaller of the two covers every case, degenerate faces too."""
    normal = np.cross(b - a, c - a)
    nn = np.einsum("ij,ij->i", normal, normal)
    safe = np.where(nn > 0, nn, 1.0)
    q = p - (np.einsum("ij,ij->i", p - a, normal) / safe)[:, None] * normal
    # barycentric coordinates of the projection q (w_b, w_c from the normal equations)
    w_b = np.einsum("ij,ij->i", np.cross(q - a, c - a), normal) / safe
    w_c = np.einsum("ij,ij->i", np.cross(b - a, q - a), normal) / safe
    w_a = 1.0 - w_b - w_c
    inside = (nn > 0) & (w_a >= 0) & (w_b >= 0) & (w_c >= 0)
    best = np.where(inside, np.linalg.norm(p - q, axis=1), np.inf)
    bary = np.column_stack([w_a, w_b, w_c])
    for first, second, start, end in ((0, 1, a, b), (1, 2, b, c), (2, 0, c, a)):
        edge = end - start
        length2 = np.einsum("ij,ij->i", edge, edge)
        t = np.clip(np.einsum("ij,ij->i", p - start, edge) / np.where(length2 > 0, length2, 1.0), 0.0, 1.0)
        distance = np.linalg.norm(p - (start + t[:, None] * edge), axis=1)
        closer = distance < best
        best = np.where(closer, distance, best)
        on_edge = np.zeros_like(bary)
        on_edge[:, first] = 1.0 - t
        on_edge[:, second] = t
        bary = np.where(closer[:, None], on_edge, bary)
    return best, bary


def sample_profile(coords, fields, mesh, surfaces, segment, samples):
    """Rows (s, point, interface label or None, pressure, tangential stress) along the segment,
    interpolated on the nearest slave triangle of all the surfaces drawn; None values where no
    triangle lies within 5 % of the segment's length (the line left the slave surfaces)."""
    start, end = segment
    length = np.linalg.norm(end - start)
    tris, owner, tangential = [], [], np.zeros(len(coords))
    for k, surface in enumerate(surfaces):
        triangles = exodus_read.side_set_triangles(mesh, surface["slave"])
        tris += triangles
        owner += [k] * len(triangles)
        # each slave node belongs to one interface: its own surface's tributary area
        tangential = np.where(tangential > 0, tangential, tangential_stress(coords, fields, triangles))
    tris = np.array(tris)
    a, b, c = coords[tris[:, 0]], coords[tris[:, 1]], coords[tris[:, 2]]
    rows = []
    for s in np.linspace(0.0, length, samples):
        point = start + (s / length) * (end - start)
        distance, bary = closest_on_triangles(point, a, b, c)
        k = int(np.argmin(distance))
        if distance[k] > 0.05 * length:
            rows.append((s, point, None, None, None))
            continue
        nodes = tris[k]
        rows.append((s, point, surfaces[owner[k]]["label"], float(bary[k] @ fields["contact_pressure"][nodes]),
                     float(bary[k] @ tangential[nodes])))
    return rows


def write_profile_csv(rows, out):
    """profile.csv: empty interface and stress cells where the segment is off the surfaces."""
    with open(out, "w") as f:
        f.write("s,x,y,z,interface,pressure,tangential_stress\n")
        for s, point, label, pressure, tangential in rows:
            values = ("", "", "") if label is None else (label, "%.9g" % pressure, "%.9g" % tangential)
            f.write("%.9g,%.9g,%.9g,%.9g,%s,%s,%s\n" % (s, *point, *values))


def plot_profile(rows, segment, out, dpi, label=""):
    s = np.array([r[0] for r in rows])
    pressure = np.array([np.nan if r[3] is None else r[3] for r in rows])
    tangential = np.array([np.nan if r[4] is None else r[4] for r in rows])
    fig, ax = plt.subplots(figsize=(8, 4.2), constrained_layout=True)
    ax.plot(s, pressure, "-", label="normal contact stress (pressure)")
    ax.plot(s, tangential, "--", label="tangential contact stress |t|")
    ax.axhline(0.0, color="gray", linewidth=0.6)
    ax.set_xlabel("s, distance from (%s)" % ", ".join("%g" % v for v in segment[0]))
    ax.set_ylabel("force / area")
    ax.set_title("contact stresses from (%s) to (%s)" % tuple(", ".join("%g" % v for v in p) for p in segment)
                 + (", " + label if label else ""))
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=8)
    save(fig, out, dpi)

# ---------------------------------------------------------------- convergence history


def plot_convergence(summary, out, dpi):
    history = summary.get("history") or []
    if not history:
        return False
    outer = [h["outer"] for h in history]
    fig, (left, right) = plt.subplots(1, 2, figsize=(11, 4.2), constrained_layout=True)
    series = (("projected_gradient", "||g^P|| / ||Ph||", "o-"), ("equality_residual", "||G mu|| / ||Ph||", "s-"),
              ("slip_bound_change", "slip-bound change", "^-"))
    for key, label, style in series:
        # null: not finite (the first slip-bound update, from g = 0, is an infinite change)
        values = [float("nan") if h[key] is None else h[key] for h in history]
        if any(v > 0 for v in values):
            left.semilogy(outer, [v if v > 0 else float("nan") for v in values], style, label=label, ms=4)
    if "tolerance" in summary:
        left.axhline(summary["tolerance"], color="gray", linestyle=":", label="tolerance epsilon")
    left.set_xlabel("SMALSE-M outer iteration")
    left.set_title("residuals")
    left.legend(fontsize=8)
    left.grid(True, which="both", alpha=0.3)
    right.bar(outer, [h["inner"] for h in history], color="tab:blue", alpha=0.5, label="MPGP iterations")
    right.set_xlabel("SMALSE-M outer iteration")
    right.set_ylabel("MPGP iterations of the outer iteration")
    twin = right.twinx()
    twin.plot(outer, [h["pfp_applications"] for h in history], "k.-", label="PFP applications (cumulative)")
    twin.set_ylabel("PFP applications so far")
    right.set_title("cost (%.3g s in all)" % history[-1]["elapsed_s"])
    lines = right.get_legend_handles_labels()
    more = twin.get_legend_handles_labels()
    right.legend(lines[0] + more[0], lines[1] + more[1], fontsize=8, loc="upper left")
    state = "converged" if summary.get("converged") else "NOT converged"
    fig.suptitle("%s: %d outer iterations, %s" % (os.path.basename(str(summary.get("input", ""))), len(history),
                                                  state))
    save(fig, out, dpi)
    return True

# ---------------------------------------------------------------- load history


def parse_history(text, mesh):
    """"NODE_SET[:COMPONENT]" as (node set, axis index or None for the default)."""
    name, _, component = text.partition(":")
    if name not in mesh["node_sets"]:
        raise KeyError("--history %s: no node set %s (the file has: %s)" % (text, name, ", ".join(mesh["node_sets"])))
    if not mesh["node_sets"][name]:
        raise ValueError("--history %s: node set %s is empty" % (text, name))
    if component and component not in AXES:
        raise ValueError("--history %s: COMPONENT is x, y or z" % text)
    return name, (AXES.index(component) if component else None)


def read_history(path, header, mesh, node_set):
    """Per time step: the node set's mean displacement and reaction sum (None when none of its
    nodes is prescribed), each interface's contact force and dissipated energy (from the
    global variables <I>_force_x/y/z and <I>_dissipated_energy), the total dissipated energy,
    converged and the time."""
    nodes = mesh["node_sets"][node_set]
    names = ["displ_x", "displ_y", "displ_z"]
    with_reactions = {"reaction_x", "reaction_y", "reaction_z"} <= set(exodus_read.nodal_variable_names(path, header))
    if with_reactions:
        names += ["reaction_x", "reaction_y", "reaction_z"]
    steps = exodus_read.nodal_steps(path, header, names)
    count = len(steps["displ_x"])
    displacement = np.array([[np.mean(np.asarray(steps["displ_" + c][k])[nodes]) for c in AXES] for k in range(count)])
    reaction = None
    if with_reactions:
        nodal = np.array([[np.asarray(steps["reaction_" + c][k])[nodes] for c in AXES] for k in range(count)])
        if np.any(nodal != 0):  # the solver writes zero reactions at free components
            reaction = nodal.sum(axis=2)
    globals_ = exodus_read.global_variables(path, header)
    interfaces = [n[:-len("_force_x")] for n in globals_ if n.endswith("_force_x")
                  and n[:-len("x")] + "y" in globals_ and n[:-len("x")] + "z" in globals_]
    nan = [float("nan")] * count

    def series(name):
        values = globals_.get(name)
        return np.array(values if values is not None and len(values) == count else nan, dtype=float)

    times = exodus_read.time_values(path, header)
    return dict(node_set=node_set, count=count, displacement=displacement, reaction=reaction,
                times=np.array(times if len(times) == count else range(1, count + 1), dtype=float),
                converged=series("converged"), dissipated=series("dissipated_energy"),
                interfaces=[dict(name=i, force=np.column_stack([series(i + "_force_" + c) for c in AXES]),
                                 dissipated=series(i + "_dissipated_energy")) for i in interfaces])


def default_component(history):
    """The axis along which the node set's mean displacement changes most, the unloaded state
    (zero) included, so that a one-step result takes its largest displacement."""
    u = np.vstack([np.zeros(3), history["displacement"]])
    return int(np.argmax(np.ptp(u, axis=0)))


def write_history_csv(history, out):
    """history.csv: one row per step; empty reaction cells when the node set has no prescribed
    node, empty cells for a global variable the result lacks."""
    cell = lambda v: "" if v is None or not np.isfinite(v) else "%.12g" % v  # noqa: E731
    header = ["time", "step", "converged"] + ["displ_" + c for c in AXES] + ["reaction_" + c for c in AXES]
    for interface in history["interfaces"]:
        header += [interface["name"] + "_force_" + c for c in AXES] + [interface["name"] + "_dissipated_energy"]
    header.append("dissipated_energy")
    with open(out, "w") as f:
        f.write(",".join(header) + "\n")
        for k in range(history["count"]):
            converged = history["converged"][k]
            row = [cell(history["times"][k]), "%d" % (k + 1), "" if not np.isfinite(converged) else "%d" % converged]
            row += [cell(v) for v in history["displacement"][k]]
            row += ["", "", ""] if history["reaction"] is None else [cell(v) for v in history["reaction"][k]]
            for interface in history["interfaces"]:
                row += [cell(v) for v in interface["force"][k]] + [cell(interface["dissipated"][k])]
            row.append(cell(history["dissipated"][k]))
            f.write(",".join(row) + "\n")


def annotated_steps(count, unconverged):
    """The steps numbered on the force-displacement curve: all up to 12, else about 10 evenly
    spaced ones, the first and the last, and every unconverged step."""
    every = 1 if count <= 12 else int(math.ceil(count / 10.0))
    return sorted({k for k in range(count) if k % every == every - 1 or k in (0, count - 1)} | set(unconverged))


def plot_history_curve(ax, u, force, label, style, annotate, unconverged):
    """One force-displacement series: from the unloaded state (0, 0), dotted, then the steps in
    order, unconverged ones hollow and red."""
    line, = ax.plot(u, force, style, ms=5, label=label)
    ax.plot([0.0, u[0]], [0.0, force[0]], ":", color=line.get_color(), linewidth=1)
    if unconverged:
        ax.plot(u[unconverged], force[unconverged], "o", ms=9, markerfacecolor="none", markeredgecolor="red",
                markeredgewidth=1.5)
    for k in annotate:  # odd steps above right, even ones below left: a return to a point stays legible
        ax.annotate("%d" % (k + 1), (u[k], force[k]), textcoords="offset points",
                    xytext=(4, 4) if k % 2 == 0 else (-10, -12), fontsize=7,
                    color="red" if k in unconverged else line.get_color())


def plot_history(history, axis, out, dpi, title=""):
    c = AXES[axis]
    u = history["displacement"][:, axis]
    count = history["count"]
    unconverged = [k for k in range(count) if history["converged"][k] == 0]
    annotate = annotated_steps(count, unconverged)
    fig, (left, right) = plt.subplots(1, 2, figsize=(11, 4.6), constrained_layout=True)
    styles = ("o-", "s-", "^-", "D-", "v-", "P-")
    for n, interface in enumerate(history["interfaces"]):
        plot_history_curve(left, u, interface["force"][:, axis], "%s_force_%s (contact force on its master)"
                           % (interface["name"], c), styles[n % len(styles)], annotate, unconverged)
    reaction = history["reaction"]
    if reaction is not None and np.any(reaction[:, axis] != 0):
        plot_history_curve(left, u, reaction[:, axis], "reaction_%s summed over %s" % (c, history["node_set"]),
                           "k.--", annotate, unconverged)
    left.axhline(0.0, color="gray", linewidth=0.6)
    left.axvline(0.0, color="gray", linewidth=0.6)
    left.set_xlabel("mean displ_%s of node set %s" % (c, history["node_set"]))
    left.set_ylabel("force along %s" % c)
    left.set_title("(a) force against displacement, steps numbered")
    left.grid(True, alpha=0.3)
    handles, labels = left.get_legend_handles_labels()
    if unconverged:
        handles.append(Line2D([], [], marker="o", linestyle="none", markerfacecolor="none", markeredgecolor="red"))
        labels.append("not converged")
    if handles:
        left.legend(handles, labels, fontsize=8)

    times = history["times"]
    right.plot(times, history["dissipated"], "ko-", ms=4, label="dissipated_energy (all interfaces)")
    if len(history["interfaces"]) > 1:
        for n, interface in enumerate(history["interfaces"]):
            right.plot(times, interface["dissipated"], styles[n % len(styles)][0] + "--", ms=4,
                       label=interface["name"] + "_dissipated_energy")
    if unconverged:
        right.plot(times[unconverged], history["dissipated"][unconverged], "o", ms=9, markerfacecolor="none",
                   markeredgecolor="red", markeredgewidth=1.5, label="not converged")
    right.set_xlabel("time")
    right.set_ylabel("frictional dissipation so far (force x length)")
    right.set_title("(b) dissipated energy")
    right.grid(True, alpha=0.3)
    right.legend(fontsize=8)
    fig.suptitle(title or "load history: %d steps, %d not converged" % (count, len(unconverged)))
    save(fig, out, dpi)


# ---------------------------------------------------------------- deformed shape


def boundary_faces(mesh):
    """(face node triple, block index) of every element face that belongs to one element (any
    element type; a quadrilateral face as its two triangles)."""
    seen = {}
    for b, (_, elements) in enumerate(mesh["blocks"]):
        for element in elements:
            for face in exodus_read.element_faces(element):
                key = tuple(sorted(face))
                seen[key] = None if key in seen else (face, b)
    return [(tri, b) for face, b in (v for v in seen.values() if v is not None) for tri in exodus_read.triangles_of(face)]


def magnification(coords, displacement, requested):
    if requested:
        return requested
    largest = np.linalg.norm(displacement, axis=1).max()
    if largest == 0:
        return 1.0
    raw = 0.08 * np.linalg.norm(coords.max(axis=0) - coords.min(axis=0)) / largest
    step = 10 ** math.floor(math.log10(raw))
    return max(m * step for m in (1, 2, 5) if m * step <= raw)  # a round number


def plot_deformed(mesh, coords, fields, requested_scale, out, dpi, label=""):
    displacement = np.column_stack([fields["displ_x"], fields["displ_y"], fields["displ_z"]])
    scale = magnification(coords, displacement, requested_scale)
    warped = coords + scale * displacement
    faces = boundary_faces(mesh)
    tris = np.array([f for f, _ in faces])
    magnitude = np.linalg.norm(displacement, axis=1)
    face_value = magnitude[tris].mean(axis=1)
    norm = plt.Normalize(0.0, magnitude.max() if magnitude.max() > 0 else 1.0)
    cmap = plt.get_cmap("viridis")

    fig = plt.figure(figsize=(11, 4.6), constrained_layout=True)
    ax3 = fig.add_subplot(1, 2, 1, projection="3d")
    ax3.add_collection3d(Poly3DCollection(warped[tris], facecolors=cmap(norm(face_value)), edgecolors="k",
                                          linewidths=0.1))
    low, high = warped.min(axis=0), warped.max(axis=0)
    ax3.set_xlim(low[0], high[0])
    ax3.set_ylim(low[1], high[1])
    ax3.set_zlim(low[2], high[2])
    ax3.set_box_aspect(np.maximum(high - low, 1e-12 * np.ptp(coords)))
    ax3.view_init(elev=22, azim=-60)
    ax3.set_xlabel("x")
    ax3.set_ylabel("y")
    ax3.set_zlabel("z")
    ax3.set_title("deformed boundary, displacements x %g" % scale + ("\n" + label if label else ""))

    # Side view along the axis of smallest extent: undeformed silhouette in grey, the faces
    # that look at the viewer drawn far to near (painter's order).
    ax2 = fig.add_subplot(1, 2, 2)
    i, j = in_plane_axes(coords)
    depth = 3 - i - j
    normals = np.cross(warped[tris[:, 1]] - warped[tris[:, 0]], warped[tris[:, 2]] - warped[tris[:, 0]])
    front = normals[:, depth] < 0  # the viewer looks along +depth from below its minimum
    order = np.argsort(-warped[tris, depth].mean(axis=1))
    ax2.add_collection(PolyCollection(coords[tris][:, :, [i, j]], facecolors="0.85", edgecolors="none"))
    shown = [k for k in order if front[k]]
    ax2.add_collection(PolyCollection(warped[tris[shown]][:, :, [i, j]], facecolors=cmap(norm(face_value[shown])),
                                      edgecolors="k", linewidths=0.15))
    both = np.vstack([coords, warped])
    pad = 0.03 * np.ptp(both[:, [i, j]], axis=0)
    ax2.set_xlim(both[:, i].min() - pad[0], both[:, i].max() + pad[0])
    ax2.set_ylim(both[:, j].min() - pad[1], both[:, j].max() + pad[1])
    ax2.set_aspect("equal")
    ax2.set_xlabel(AXES[i])
    ax2.set_ylabel(AXES[j])
    ax2.set_title("seen along %s (grey: undeformed)" % AXES[depth])
    fig.colorbar(plt.cm.ScalarMappable(norm=norm, cmap=cmap), ax=ax2, shrink=0.9, label="|u| (unscaled)")
    save(fig, out, dpi)


def attach_profile_value(argv):
    """argv with "--profile -5,0,10:..." written "--profile=-5,0,10:...": argparse takes a value
    that starts with "-" (a negative first coordinate) for an option and would refuse it."""
    out = list(argv)
    for k in range(len(out) - 1):
        if out[k] == "--profile" and out[k + 1].startswith("-"):
            out[k:k + 2] = ["--profile=" + out[k + 1]]
            break
    return out


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[1])
    parser.add_argument("result")
    parser.add_argument("summary")
    parser.add_argument("outdir")
    parser.add_argument("--slave", default="")
    parser.add_argument("--scale", type=float, default=0.0)
    parser.add_argument("--profile", default="")
    parser.add_argument("--profile-samples", type=int, default=200)
    parser.add_argument("--dpi", type=int, default=100)
    parser.add_argument("--step", type=int, default=None)
    parser.add_argument("--history", default="")
    args = parser.parse_args(attach_profile_value(sys.argv[1:]))
    if not exodus_read.can_read():
        print("plot_results.py: needs python3-netcdf4 or ncdump to read Exodus (apt-get install python3-netcdf4 "
              "or netcdf-bin)", file=sys.stderr)
        return 77
    try:
        segment = parse_segment(args.profile) if args.profile else None
        if segment is not None and args.profile_samples < 2:
            raise ValueError("--profile-samples %d: at least 2 (the two ends)" % args.profile_samples)
        if args.step is not None and args.step < 1:
            raise ValueError("--step %d: time steps count from 1" % args.step)
        if not os.path.isfile(args.result):
            raise OSError("%s: no such file (write it with tribos --output)" % args.result)
        with open(args.summary) as f:
            summary = json.load(f)
        header, mesh, coords, fields, step, count = read_result(args.result, args.step or 0)
        label = step_label(step, count, exodus_read.time_values(args.result, header) if count > 1 else [])
        contact = "contact_status" in fields
        surfaces = interface_surfaces(step_summary(summary, step, count), mesh, fields, args.slave) if contact else []
        if args.history:
            node_set, axis = parse_history(args.history, mesh)
            history = read_history(args.result, header, mesh, node_set)
    except (OSError, KeyError, ValueError, IndexError, subprocess.CalledProcessError) as e:
        print("plot_results.py: %s" % e, file=sys.stderr)
        return 2
    os.makedirs(args.outdir, exist_ok=True)
    path = lambda name: os.path.join(args.outdir, name)  # noqa: E731
    if contact:
        for surface in surfaces:
            plot_contact(mesh, coords, fields, surface, path(surface["png"]), args.dpi, label)
            print("wrote", path(surface["png"]))
    else:
        print("plot_results.py: no contact fields (a scene without contact): contact_stress.png%s not written"
              % (" and the profile" if segment is not None else ""), file=sys.stderr)
    if contact and segment is not None:
        rows = sample_profile(coords, fields, mesh, surfaces, segment, args.profile_samples)
        write_profile_csv(rows, path("profile.csv"))
        plot_profile(rows, segment, path("profile.png"), args.dpi, label)
        print("wrote", path("profile.csv"), "and", path("profile.png"),
              "(%d of %d points on a slave surface)" % (sum(r[2] is not None for r in rows), len(rows)))
    if plot_convergence(summary, path("convergence.png"), args.dpi):
        print("wrote", path("convergence.png"))
    else:
        print("plot_results.py: no \"history\" in %s (not a contact solve): convergence.png not written"
              % args.summary, file=sys.stderr)
    plot_deformed(mesh, coords, fields, args.scale, path("deformed.png"), args.dpi, label)
    print("wrote", path("deformed.png"))
    if args.history:
        axis = default_component(history) if axis is None else axis
        write_history_csv(history, path("history.csv"))
        plot_history(history, axis, path("history.png"), args.dpi,
                     "%s: load history of %d step%s seen from node set %s along %s"
                     % (os.path.basename(str(summary.get("input", ""))) or os.path.basename(args.result),
                        history["count"], "s" * (history["count"] > 1), node_set, AXES[axis]))
        if not history["interfaces"]:
            print("plot_results.py: no <interface>_force_x/y/z global variables in %s: history.png has no contact"
                  " force" % args.result, file=sys.stderr)
        print("wrote", path("history.csv"), "and", path("history.png"),
              "(%d step%s, %s along %s)" % (history["count"], "s" * (history["count"] > 1), node_set, AXES[axis]))
    return 0


if __name__ == "__main__":
    sys.exit(main())
