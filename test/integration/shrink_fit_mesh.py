"""Writes the quarter model of a plane-strain shrink fit as meshio writes Exodus meshes (blocks
numbered from 0 without names: block_0 is the shaft, block_1 the hub; node sets only, the
contact surfaces given as node sets). Used by lame_hoop_stress_test.sh and
shrink_fit_friction_test.sh with shrink_fit.xml, and, thicker and in layers, by push_out_test.sh
with push_out.xml (a push-out, not plane strain).

Usage: python3 shrink_fit_mesh.py OUT.exo hex8|tet4|tet10 [--layers L] [--thickness T]
         [--hub-cells RADIAL ANGULAR] [--shaft-cells RADIAL ANGULAR] [--delta DELTA] [--curved]
(needs Debian's python3-meshio). Defaults: one layer, T = 2 mm (the plane-strain slab), the
cells below; push_out_test.sh writes 4 layers, T = 8 mm (and coarser cells for tet10);
--delta 0 writes the nominal geometry (the shaft's surface on the hub's bore: the interference
then given as Contact/Interference, shrink_fit_default_search_test.sh).

Units mm; x >= 0, y >= 0, L layers of cells in 0 <= z <= T. A hollow shaft (inner radius
A = 10, outer B + DELTA) is pressed into a hub (bore B = 20, outer radius C = 40): radial
interference DELTA.
Each body is a structured polar grid with its own nodes, cells 2 mm radially: the hub 10 radial
x 24 angular cells (1.3 mm along the bore), the shaft 5 x 48, so that the meshes do not match
on the interface (two shaft faces on each hub face).

The interface is faceted: the hub's bore is the 24-gon with its vertices on r = B. A shaft
whose outer nodes lay on a circle too would be another polygon, and two polygons with
different vertices differ by up to the sag of a face, B (1 - cos(90 deg / 24 / 2)) = 0.011 mm
here, as much as the interference: a rough contact whose local stresses swamp Lame's (with
nodes on circles, 12 hub and 14 shaft faces: 14 of the 30 slave nodes open, twice Lame's
contact force, hoop stresses off by 100 %). So the shaft's outer surface is the hub's bore
polygon moved out by DELTA along each face's normal (its vertices on the rays of the hub's
vertices lie at r = B + DELTA / cos(half a face's angle), those between them at the faces'
midpoints): non-matching nodes, the same surface, a uniform interference DELTA.

hex8: hexahedra. tet4: each hexahedron cut into 6 tetrahedra (as below, without the mid-edge
nodes). tet10: each hexahedron cut into 6 positively oriented tetrahedra (as in
meshio_two_boxes.py), then a node at the midpoint of each edge (shared; straight edges), in
meshio's "tetra10" order, which is Exodus's TETRA10: vertices 0-3, then edges 01 12 02 03 13 23.
--curved (tet10 only): both surfaces on circles instead, the shaft's at r = B + DELTA and the
hub's bore at r = B (non-matching nodes, a uniform interference), and the node of every edge
whose ends lie on one circle about the z axis moved out onto it: curved faces, as gmsh's
second-order meshes of a cylinder give.
Node sets: shaft_outer, hub_bore (the contact surfaces), hub_outer (r = C), shaft_x0, hub_x0,
shaft_y0, hub_y0 (symmetry planes), all_z0, all_z1 (the slab's faces), shaft_z0, shaft_z1,
hub_z0, hub_z1 (each body's end faces).
"""
import argparse

import meshio
import numpy as np

from meshio_two_boxes import kuhn_tetrahedra  # the same split as the two boxes' mesh

A, B, C, DELTA, T = 10.0, 20.0, 40.0, 0.01, 2.0
HUB_CELLS = (10, 24)  # radial, angular over 90 degrees
SHAFT_CELLS = (5, 48)  # angular: a multiple of the hub's (the shaft's outer surface follows its faces)
assert SHAFT_CELLS[1] % HUB_CELLS[1] == 0


def polar_grid(inner, outer_radius, cells, layers=1, thickness=T):
    """Nodes (radial i, angular j, layer k) of a quarter ring from r = inner to outer_radius(theta),
    z from 0 to thickness in `layers` cells, and its hexahedra. Radial spacing uniform along
    each ray."""
    nr, nt = cells
    points, index = [], {}
    for k in range(layers + 1):
        for j in range(nt + 1):
            theta = 0.5 * np.pi * j / nt
            outer = outer_radius(theta)
            for i in range(nr + 1):
                r = inner + (outer - inner) * i / nr
                index[i, j, k] = len(points)
                points.append([r * np.cos(theta), r * np.sin(theta), thickness * k / layers])
    points = np.array(points)
    # Exodus HEX8 order: the bottom face counter-clockwise seen from +z (radially out, then
    # round), then the top face.
    hexes = [[index[i, j, k], index[i + 1, j, k], index[i + 1, j + 1, k], index[i, j + 1, k],
              index[i, j, k + 1], index[i + 1, j, k + 1], index[i + 1, j + 1, k + 1], index[i, j + 1, k + 1]]
             for k in range(layers) for j in range(nt) for i in range(nr)]
    return points, np.array(hexes)


def hub_bore_radius(theta, offset, hub_angular=HUB_CELLS[1]):
    """Radius at angle theta of the hub's bore polygon (vertices on r = B) moved out by offset
    along each face's normal."""
    step = 0.5 * np.pi / hub_angular
    face = min(int(np.floor(theta / step + 1e-12)), hub_angular - 1)
    middle = (face + 0.5) * step
    return (B * np.cos(0.5 * step) + offset) / np.cos(theta - middle)


def tetrahedra(points, hexes):
    """Each hexahedron cut into 6 tetrahedra around its diagonal 0-6 (Exodus numbering; corner
    7 of meshio_two_boxes.py's binary numbering), positively oriented."""
    # Binary corner v = (di, dj, dk) -> Exodus HEX8 local node.
    binary_to_hex = [0, 1, 3, 2, 4, 5, 7, 6]
    tets = []
    for h in hexes:
        tets += kuhn_tetrahedra(points, [h[binary_to_hex[v]] for v in range(8)])
    return np.array(tets)


def quadratic(points, tets, curved=False):
    """Adds a node at the midpoint of every edge (one per edge); returns the points and the
    10-node tetrahedra. curved: the node of an edge whose ends lie on one circle about the z
    axis is moved out onto that circle (curved faces, as gmsh's second-order meshes give)."""
    points = list(points)
    middle = {}

    def node(p, q):
        key = (min(p, q), max(p, q))
        if key not in middle:
            middle[key] = len(points)
            mid = 0.5 * (points[p] + points[q])
            rp, rq = np.hypot(*points[p][:2]), np.hypot(*points[q][:2])
            if curved and abs(rp - rq) < 1e-9:
                mid[:2] *= rp / np.hypot(*mid[:2])
            points.append(mid)
        return middle[key]

    tet10 = [list(t) + [node(t[0], t[1]), node(t[1], t[2]), node(t[0], t[2]), node(t[0], t[3]),
                        node(t[1], t[3]), node(t[2], t[3])] for t in tets]
    return np.array(points), np.array(tet10)


def main(path, kind, layers=1, thickness=T, hub_grid=HUB_CELLS, shaft_grid=SHAFT_CELLS, delta=DELTA,
         curved=False):
    nt = hub_grid[1]
    # The shaft's outer surface: the moved hub polygon, or (curved) the circle r = B + delta.
    shaft_surface = (lambda theta: B + delta) if curved else (lambda theta: hub_bore_radius(theta, delta, nt))
    hub_surface = (lambda theta: B) if curved else (lambda theta: hub_bore_radius(theta, 0.0, nt))
    shaft_points, shaft_cells = polar_grid(A, shaft_surface, shaft_grid, layers, thickness)
    # The hub's nodes lie on its rays at the polygon's vertices: r = B on the bore, r = C outside.
    hub_points, hub_cells = polar_grid(B, lambda theta: C, hub_grid, layers, thickness)
    if kind == "tet4":
        shaft_cells, hub_cells = tetrahedra(shaft_points, shaft_cells), tetrahedra(hub_points, hub_cells)
    if kind == "tet10":
        shaft_points, shaft_cells = quadratic(shaft_points, tetrahedra(shaft_points, shaft_cells), curved)
        hub_points, hub_cells = quadratic(hub_points, tetrahedra(hub_points, hub_cells), curved)
    offset = len(shaft_points)
    points = np.vstack([shaft_points, hub_points])
    shaft = np.arange(offset)
    hub = np.arange(offset, len(points))
    r = np.hypot(points[:, 0], points[:, 1])

    def where(nodes, test):
        return nodes[test(points[nodes], r[nodes])]

    eps = 1e-9
    # The shaft's outer surface: its outer nodes (the last radial layer of the grid; tet10: and
    # the midpoints between them), i.e. the nodes on the moved hub polygon (curved: on r = B + delta).
    on_shaft_outer = np.array([abs(shaft_surface(np.arctan2(y, x)) - rr) < 1e-9
                               for (x, y, _), rr in zip(points[shaft], r[shaft])])
    sets = {
        "shaft_outer": shaft[on_shaft_outer],
        "hub_bore": where(hub, lambda x, rr: np.abs(
            np.array([hub_surface(np.arctan2(p[1], p[0])) for p in x]) - rr) < 1e-9),
        "shaft_x0": where(shaft, lambda x, rr: np.abs(x[:, 0]) < eps),
        "shaft_y0": where(shaft, lambda x, rr: np.abs(x[:, 1]) < eps),
        "hub_outer": where(hub, lambda x, rr: rr > C * np.cos(0.25 * np.pi / nt) - 1e-9),
        "hub_x0": where(hub, lambda x, rr: np.abs(x[:, 0]) < eps),
        "hub_y0": where(hub, lambda x, rr: np.abs(x[:, 1]) < eps),
        "all_z0": np.nonzero(np.abs(points[:, 2]) < eps)[0],
        "all_z1": np.nonzero(np.abs(points[:, 2] - thickness) < eps)[0],
        "shaft_z0": where(shaft, lambda x, rr: np.abs(x[:, 2]) < eps),
        "shaft_z1": where(shaft, lambda x, rr: np.abs(x[:, 2] - thickness) < eps),
        "hub_z0": where(hub, lambda x, rr: np.abs(x[:, 2]) < eps),
        "hub_z1": where(hub, lambda x, rr: np.abs(x[:, 2] - thickness) < eps),
    }
    cell_type = {"hex8": "hexahedron", "tet4": "tetra", "tet10": "tetra10"}[kind]
    mesh = meshio.Mesh(points, [(cell_type, shaft_cells), (cell_type, hub_cells + offset)], point_sets=sets)
    meshio.write(path, mesh, file_format="exodus")


if __name__ == "__main__":
    parser = argparse.ArgumentParser(description="The quarter model of a shrink fit (Exodus, via meshio).")
    parser.add_argument("path", help="the Exodus file to write")
    parser.add_argument("kind", choices=("hex8", "tet4", "tet10"), help="element type")
    parser.add_argument("--layers", type=int, default=1, help="cells along z (default 1)")
    parser.add_argument("--thickness", type=float, default=T, help="slab thickness along z [mm] (default %g)" % T)
    parser.add_argument("--hub-cells", type=int, nargs=2, default=HUB_CELLS, metavar=("RADIAL", "ANGULAR"),
                        help="the hub's cells (default %d %d)" % HUB_CELLS)
    parser.add_argument("--shaft-cells", type=int, nargs=2, default=SHAFT_CELLS, metavar=("RADIAL", "ANGULAR"),
                        help="the shaft's cells, angular a multiple of the hub's (default %d %d)" % SHAFT_CELLS)
    parser.add_argument("--delta", type=float, default=DELTA,
                        help="the shaft's radial interference [mm] (default %g; 0: nominal geometry)" % DELTA)
    parser.add_argument("--curved", action="store_true",
                        help="tet10: the surfaces on circles, r = B + DELTA (shaft) and B (hub), the mid-edge "
                             "nodes of edges along a circle on it (curved faces, as gmsh's second-order meshes)")
    args = parser.parse_args()
    if args.curved and args.kind != "tet10":
        parser.error("--curved is for tet10 (mid-edge nodes on the circles)")
    if args.layers < 1 or not args.thickness > 0:
        parser.error("--layers must be >= 1 and --thickness > 0")
    if min(list(args.hub_cells) + list(args.shaft_cells)) < 1 or args.shaft_cells[1] % args.hub_cells[1]:
        parser.error("cells must be >= 1, the shaft's angular ones a multiple of the hub's")
    if args.delta < 0:
        parser.error("--delta must be >= 0")
    main(args.path, args.kind, args.layers, args.thickness, tuple(args.hub_cells), tuple(args.shaft_cells), args.delta,
         args.curved)
