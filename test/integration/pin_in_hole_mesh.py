"""Writes the half model of a pin in a clearance hole, plane strain, as meshio writes Exodus
meshes (block_0 the pin, block_1 the plate; node sets only). Used by pin_in_hole_test.sh with
pin_in_hole.xml (issue 41: a pin pushed across its clearance must bear on the hole's wall,
whatever the Search Distance).

Usage: python3 pin_in_hole_mesh.py OUT.exo [--clearance C] [--offset X] [--pin-cells RADIAL ANGULAR]
         [--plate-cells RADIAL ANGULAR]
(needs Debian's python3-meshio). Units mm; y >= 0 (symmetry plane y = 0), one layer of
hexahedra in 0 <= z <= 2 (the plane-strain slab). A hollow pin (r = 10 .. 20 - C) sits centred
in the hole (r = 20) of a plate ring (r = 20 .. 40). Both are structured polar grids over
0 <= theta <= 180 degrees with their own nodes, the pin's nodes on its circle, the hole's on
its own: the meshes do not match (default 40 pin and 48 plate cells around). The faceted
surfaces differ from circles by at most 20 (1 - cos(1.875 deg)) = 0.011 mm, far below the
clearance (default 0.25 mm).
Node sets: pin_outer, plate_hole (the contact surfaces), pin_inner (r = 10: the push),
plate_outer (r = 40: held), pin_y0, plate_y0 (symmetry), all_z0, all_z1 (the slab's faces).
"""
import argparse

import meshio
import numpy as np

A, B, C, T = 10.0, 20.0, 40.0, 2.0
PIN_CELLS = (4, 40)    # radial, angular over 180 degrees
PLATE_CELLS = (8, 48)


def half_ring(inner, outer, cells):
    """Nodes (radial i, angular j, layer k) of a half ring inner <= r <= outer, 0 <= z <= T, and
    its hexahedra in Exodus HEX8 order (radially out, then round, seen from +z; then the top)."""
    nr, nt = cells
    points, index = [], {}
    for k in range(2):
        for j in range(nt + 1):
            theta = np.pi * j / nt
            for i in range(nr + 1):
                r = inner + (outer - inner) * i / nr
                index[i, j, k] = len(points)
                points.append([r * np.cos(theta), r * np.sin(theta), T * k])
    hexes = [[index[i, j, 0], index[i + 1, j, 0], index[i + 1, j + 1, 0], index[i, j + 1, 0],
              index[i, j, 1], index[i + 1, j, 1], index[i + 1, j + 1, 1], index[i, j + 1, 1]]
             for j in range(nt) for i in range(nr)]
    return np.array(points), np.array(hexes)


def main(path, clearance, pin_cells, plate_cells, shift=0.0):
    pin_points, pin_cells_ = half_ring(A, B - clearance, pin_cells)
    pin_points[:, 0] += shift
    plate_points, plate_cells_ = half_ring(B, C, plate_cells)
    offset = len(pin_points)
    points = np.vstack([pin_points, plate_points])
    pin, plate = np.arange(offset), np.arange(offset, len(points))
    r = np.hypot(points[:, 0], points[:, 1])
    r[pin] = np.hypot(points[pin, 0] - shift, points[pin, 1])  # the pin's own radii
    eps = 1e-9

    def where(nodes, test):
        return nodes[test(points[nodes], r[nodes])]

    sets = {
        "pin_outer": where(pin, lambda x, rr: np.abs(rr - (B - clearance)) < eps),
        "pin_inner": where(pin, lambda x, rr: np.abs(rr - A) < eps),
        "plate_hole": where(plate, lambda x, rr: np.abs(rr - B) < eps),
        "plate_outer": where(plate, lambda x, rr: np.abs(rr - C) < eps),
        "pin_y0": where(pin, lambda x, rr: np.abs(x[:, 1]) < eps),
        "plate_y0": where(plate, lambda x, rr: np.abs(x[:, 1]) < eps),
        "all_z0": np.nonzero(np.abs(points[:, 2]) < eps)[0],
        "all_z1": np.nonzero(np.abs(points[:, 2] - T) < eps)[0],
    }
    mesh = meshio.Mesh(points, [("hexahedron", pin_cells_), ("hexahedron", plate_cells_ + offset)], point_sets=sets)
    meshio.write(path, mesh, file_format="exodus")


if __name__ == "__main__":
    parser = argparse.ArgumentParser(description="The half model of a pin in a clearance hole (Exodus, via meshio).")
    parser.add_argument("path", help="the Exodus file to write")
    parser.add_argument("--clearance", type=float, default=0.25, help="radial clearance [mm] (default 0.25)")
    parser.add_argument("--offset", type=float, default=0.0,
                        help="the pin moved along x [mm] (default 0: centred; the clearance: touching at theta = 0)")
    parser.add_argument("--pin-cells", type=int, nargs=2, default=PIN_CELLS, metavar=("RADIAL", "ANGULAR"))
    parser.add_argument("--plate-cells", type=int, nargs=2, default=PLATE_CELLS, metavar=("RADIAL", "ANGULAR"))
    args = parser.parse_args()
    if not 0 <= args.clearance < B - A or min(list(args.pin_cells) + list(args.plate_cells)) < 1:
        parser.error("--clearance must lie in [0, 10) and the cells be >= 1")
    main(args.path, args.clearance, tuple(args.pin_cells), tuple(args.plate_cells), args.offset)
