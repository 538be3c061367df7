"""Writes a single-lap bolted joint of hexahedra, the mesh of input/bolted_joint.xml (issue 43), as
meshio writes Exodus meshes (node sets only; each body its own nodes; the bodies' grids do not
match, so every interface has mortar rows).

Usage: python3 bolted_joint_mesh.py OUT.exo [--refine N]   (bolted_joint.exo: the default)
(needs Debian's python3-meshio). Units mm. Two plates 20 wide (-10 <= y <= 10) and 5 thick overlap
over -20 <= x <= 20: the lower plate (block_0, -40 <= x <= 20, -5 <= z <= 0) and the upper plate
(block_1, -20 <= x <= 40, 0 <= z <= 5), each with a square hole |x|, |y| < 4.25. A square bolt,
shank |x|, |y| <= 4 (a clearance of 0.25 all round), is cut at z = 0 into two bodies for its
pretension section: the upper part (block_2: the shank 0 <= z <= 5 and the head |x|, |y| <= 8,
5 <= z <= 8) and the lower part (block_3: the shank -5 <= z <= 0 and the nut, -8 <= z <= -5).
--refine N splits every cell N times in each direction (default 1).
Node sets: lower_end (x = -40), upper_end (x = 40), lower_top, lower_bottom, upper_top,
upper_bottom (the plates' faces z = 0, -5, 5, 0), lower_hole, upper_hole (the holes' walls),
head_bottom (z = 5), nut_top (z = -5), shank_upper, shank_lower (the shank's sides), cut_upper,
cut_lower (z = 0 of the two bolt parts), sym_y (y = -10 of both plates: held in y).
"""
import argparse

import meshio
import numpy as np

HOLE, SHANK, HEAD = 4.25, 4.0, 8.0


def refined(lines, n):
    """The grid lines with every interval split into n."""
    out = [lines[0]]
    for a, b in zip(lines[:-1], lines[1:]):
        out += list(np.linspace(a, b, n + 1)[1:])
    return np.array(out)


def body(xs, ys, zs, inside):
    """Nodes and HEX8 cells of the cells of the grid xs x ys x zs whose centre is `inside`."""
    index, points, cells = {}, [], []
    def node(i, j, k):
        if (i, j, k) not in index:
            index[(i, j, k)] = len(points)
            points.append((xs[i], ys[j], zs[k]))
        return index[(i, j, k)]
    for k in range(len(zs) - 1):
        for j in range(len(ys) - 1):
            for i in range(len(xs) - 1):
                c = ((xs[i] + xs[i + 1]) / 2, (ys[j] + ys[j + 1]) / 2, (zs[k] + zs[k + 1]) / 2)
                if not inside(*c):
                    continue
                cells.append([node(i, j, k), node(i + 1, j, k), node(i + 1, j + 1, k), node(i, j + 1, k),
                              node(i, j, k + 1), node(i + 1, j, k + 1), node(i + 1, j + 1, k + 1),
                              node(i, j + 1, k + 1)])
    return np.array(points), np.array(cells)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("path")
    parser.add_argument("--refine", type=int, default=1)
    args = parser.parse_args()
    n = args.refine
    plate_y = refined([-10, -7, -HOLE, -2, 0, 2, HOLE, 7, 10], n)
    outside_hole = lambda x, y: max(abs(x), abs(y)) > HOLE
    bolt_xy = refined([-HEAD, -6, -SHANK, -2, 0, 2, SHANK, 6, HEAD], n)
    in_shank = lambda x, y: max(abs(x), abs(y)) < SHANK
    bodies = [
        body(refined([-40, -32, -24, -16, -10, -7, -HOLE, -2, 0, 2, HOLE, 7, 10, 15, 20], n), plate_y,
             refined([-5, -2.5, 0], n), lambda x, y, z: outside_hole(x, y)),
        body(refined([-20, -15, -10, -7, -HOLE, -2, 0, 2, HOLE, 7, 10, 16, 24, 32, 40], n), plate_y,
             refined([0, 2.5, 5], n), lambda x, y, z: outside_hole(x, y)),
        body(bolt_xy, bolt_xy, refined([0, 1.25, 2.5, 3.75, 5, 6.5, 8], n),
             lambda x, y, z: in_shank(x, y) or z > 5),
        body(bolt_xy, bolt_xy, refined([-8, -6.5, -5, -3.75, -2.5, -1.25, 0], n),
             lambda x, y, z: in_shank(x, y) or z < -5),
    ]
    first = np.cumsum([0] + [len(p) for p, _ in bodies])
    points = np.vstack([p for p, _ in bodies])
    owner = np.concatenate([np.full(len(p), b) for b, (p, _) in enumerate(bodies)])
    x, y, z = points.T
    at = lambda mask: np.flatnonzero(mask)
    wall = lambda r: np.isclose(np.maximum(abs(x), abs(y)), r)
    sets = {
        "lower_end": at((owner == 0) & np.isclose(x, -40)),
        "upper_end": at((owner == 1) & np.isclose(x, 40)),
        "lower_top": at((owner == 0) & np.isclose(z, 0)),
        "lower_bottom": at((owner == 0) & np.isclose(z, -5)),
        "upper_top": at((owner == 1) & np.isclose(z, 5)),
        "upper_bottom": at((owner == 1) & np.isclose(z, 0)),
        "lower_hole": at((owner == 0) & wall(HOLE)),
        "upper_hole": at((owner == 1) & wall(HOLE)),
        "head_bottom": at((owner == 2) & np.isclose(z, 5)),
        "nut_top": at((owner == 3) & np.isclose(z, -5)),
        "shank_upper": at((owner == 2) & wall(SHANK) & (z <= 5 + 1e-9)),
        "shank_lower": at((owner == 3) & wall(SHANK) & (z >= -5 - 1e-9)),
        "cut_upper": at((owner == 2) & np.isclose(z, 0)),
        "cut_lower": at((owner == 3) & np.isclose(z, 0)),
        "sym_y": at((owner <= 1) & np.isclose(y, -10)),
    }
    cells = [("hexahedron", c + first[b]) for b, (_, c) in enumerate(bodies)]
    meshio.write(args.path, meshio.Mesh(points, cells, point_sets=sets), file_format="exodus")


if __name__ == "__main__":
    main()
