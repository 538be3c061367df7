"""Writes a bar cut in two bodies, the mesh of the pretension tests (issue 43; pretension_test.sh,
split_bar.xml), as meshio writes Exodus meshes (block_0 the left half, block_1 the right; node
sets only).

Usage: python3 split_bar_mesh.py OUT.exo [--left-cells NX NYZ] [--right-cells NX NYZ]
(needs Debian's python3-meshio). Units mm: the bar is 0 <= x <= 100, 0 <= y, z <= 10, cut at
x = 50; each half a structured grid of hexahedra with its own nodes (the halves match on the
cut by default; other cell counts make them non-matching).
Node sets: left_end (x = 0), right_end (x = 100), cut_left and cut_right (x = 50 of each half),
y0 and z0 (the faces y = 0 and z = 0 of both halves: symmetry planes).
"""
import argparse

import meshio
import numpy as np

L, A = 100.0, 10.0


def half(x0, x1, nx, nyz, first):
    """Nodes and HEX8 cells of the box x0 <= x <= x1, numbered from `first`."""
    xs, ys = np.linspace(x0, x1, nx + 1), np.linspace(0.0, A, nyz + 1)
    index = lambda i, j, k: first + (k * (nyz + 1) + j) * (nx + 1) + i
    points = [(x, y, z) for z in ys for y in ys for x in xs]
    cells = [[index(i, j, k), index(i + 1, j, k), index(i + 1, j + 1, k), index(i, j + 1, k),
              index(i, j, k + 1), index(i + 1, j, k + 1), index(i + 1, j + 1, k + 1), index(i, j + 1, k + 1)]
             for k in range(nyz) for j in range(nyz) for i in range(nx)]
    return np.array(points), np.array(cells)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("path")
    parser.add_argument("--left-cells", type=int, nargs=2, default=(10, 2))
    parser.add_argument("--right-cells", type=int, nargs=2, default=(10, 2))
    args = parser.parse_args()
    left, left_cells = half(0.0, L / 2, *args.left_cells, 0)
    right, right_cells = half(L / 2, L, *args.right_cells, len(left))
    points = np.vstack([left, right])
    n = len(left)
    at = lambda mask: np.flatnonzero(mask)
    sets = {
        "left_end": at(np.isclose(points[:, 0], 0.0)),
        "right_end": at(np.isclose(points[:, 0], L)),
        "cut_left": at(np.isclose(points[:, 0], L / 2) & (np.arange(len(points)) < n)),
        "cut_right": at(np.isclose(points[:, 0], L / 2) & (np.arange(len(points)) >= n)),
        "y0": at(np.isclose(points[:, 1], 0.0)),
        "z0": at(np.isclose(points[:, 2], 0.0)),
    }
    mesh = meshio.Mesh(points, [("hexahedron", left_cells), ("hexahedron", right_cells)], point_sets=sets)
    meshio.write(args.path, mesh, file_format="exodus")


if __name__ == "__main__":
    main()
