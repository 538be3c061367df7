"""Writes two stacked boxes as meshio writes Exodus meshes: blocks numbered from 0 without
names, node sets only (no side sets). Used by the meshio CTests (test_meshio.cpp) to check
that Tribos solves such a mesh; meshio_two_boxes.xml is the scene.

Usage: python3 meshio_two_boxes.py OUT.exo   (needs Debian's python3-meshio)
lower: [0,1] x [0,1] x [0,1], 2 x 2 x 2 cells; upper: [0,1] x [0,1] x [1,2], 3 x 3 x 2 cells,
each cell cut into 6 tetrahedra; the bodies have their own nodes on z = 1.
"""
import sys

import meshio
import numpy as np


def box(origin, cells):
    nx, ny, nz = cells
    points = np.array([[origin[0] + i / nx, origin[1] + j / ny, origin[2] + k / nz]
                       for k in range(nz + 1) for j in range(ny + 1) for i in range(nx + 1)])

    def node(i, j, k):
        return i + (nx + 1) * (j + (ny + 1) * k)

    tets = []
    for k in range(nz):
        for j in range(ny):
            for i in range(nx):
                corner = [node(i + (v & 1), j + ((v >> 1) & 1), k + ((v >> 2) & 1)) for v in range(8)]
                tets += kuhn_tetrahedra(points, corner)
    return points, np.array(tets)


def kuhn_tetrahedra(points, corner):
    """The 6 tetrahedra of a hexahedral cell around its diagonal 0-7, positively oriented;
    corner[v] is the node at the binary position v = (di, dj, dk) of the cell. Shared with
    shrink_fit_mesh.py."""
    tets = []
    for a, b in [(1, 3), (1, 5), (2, 3), (2, 6), (4, 5), (4, 6)]:
        tet = [corner[0], corner[a], corner[b], corner[7]]
        x = points[tet]
        if np.linalg.det(np.array([x[1] - x[0], x[2] - x[0], x[3] - x[0]])) < 0:
            tet[1], tet[2] = tet[2], tet[1]
        tets.append(tet)
    return tets


def main(path):
    lower_points, lower_tets = box((0.0, 0.0, 0.0), (2, 2, 2))
    upper_points, upper_tets = box((0.0, 0.0, 1.0), (3, 3, 2))
    offset = len(lower_points)
    points = np.vstack([lower_points, upper_points])
    lower = np.arange(offset)
    upper = np.arange(offset, len(points))

    def on(nodes, axis, value):
        return nodes[np.isclose(points[nodes, axis], value)]

    sets = {"lower_bottom": on(lower, 2, 0.0), "lower_top": on(lower, 2, 1.0),
            "upper_bottom": on(upper, 2, 1.0), "upper_top": on(upper, 2, 2.0),
            "upper_x0": on(upper, 0, 0.0), "upper_y0": on(upper, 1, 0.0)}
    mesh = meshio.Mesh(points, [("tetra", lower_tets), ("tetra", upper_tets + offset)], point_sets=sets)
    meshio.write(path, mesh, file_format="exodus")


if __name__ == "__main__":
    main(sys.argv[1])
