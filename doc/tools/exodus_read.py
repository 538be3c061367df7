"""Reads Tribos's Exodus II results: with netCDF4 (Debian: python3-netcdf4) where it is
installed, which reads the file itself, else by parsing the text of `ncdump` (Debian:
netcdf-bin), so that the comparison tools also run where only ncdump is. Used by
hertz_compare.py, cattaneo_compare.py, cantilever_compare.py, mindlin_loop.py and
plot_results.py. Exodus stores the mesh as netCDF variables: coordx/y/z, connect<b> (1-based
node ids per element block), node_ns<s>, elem_ss<s> and side_ss<s> (1-based), names in
name_nod_var, eb_names, ns_names, ss_names, and the nodal results either as
vals_nod_var<i>(time, node) or as one vals_nod_var(time, var, node). Both readers give the
same values: numbers as floats (missing ones NaN), character arrays as one string per row.
"""
import re
import subprocess

try:
    import netCDF4  # the file itself, not ncdump's text
except ImportError:  # ncdump's text then
    netCDF4 = None

# Local vertices (0-based) of the faces of a 4-node tetrahedron, Exodus side = index + 1.
TET_FACES = ((0, 1, 3), (1, 2, 3), (0, 3, 2), (0, 2, 1))
# The corner vertices of the faces of every element type Tribos writes, by nodes per element
# (the vertices come first in each: a 10-node tetrahedron's faces are its corners'), Exodus
# side = index + 1, each ordered so its right-hand normal points out (mesh/ElementTypes.cpp).
FACES_BY_NODE_COUNT = {
    4: TET_FACES,
    10: TET_FACES,
    8: ((0, 1, 5, 4), (1, 2, 6, 5), (2, 3, 7, 6), (0, 4, 7, 3), (0, 3, 2, 1), (4, 5, 6, 7)),
    6: ((0, 1, 4, 3), (1, 2, 5, 4), (0, 3, 5, 2), (0, 2, 1), (3, 4, 5)),
}


def element_faces(element):
    """The faces of one element as tuples of its corner node ids (3 or 4 each), side order."""
    faces = FACES_BY_NODE_COUNT.get(len(element))
    if faces is None:
        raise KeyError("an element of %d nodes (Tribos writes 4-, 10-, 8- and 6-node elements)" % len(element))
    return [tuple(element[v] for v in face) for face in faces]


def triangles_of(face):
    """A face as triangles: itself, or a quadrilateral's two (0, 1, 2), (0, 2, 3)."""
    return [face] if len(face) == 3 else [(face[0], face[1], face[2]), (face[0], face[2], face[3])]


class NetcdfLayout:
    """The dimensions and variable names of a file, as netCDF4 reads them (the header)."""

    def __init__(self, path):
        with netCDF4.Dataset(path) as d:
            self.dimensions = {name: len(dim) for name, dim in d.dimensions.items()}
            self.variables = set(d.variables)


def can_read():
    """Whether a reader is installed: netCDF4, or the ncdump program."""
    import shutil
    return netCDF4 is not None or shutil.which("ncdump") is not None


def ncdump_header(path):
    """The file's header: its layout (netCDF4), or ncdump -h's text."""
    if netCDF4 is not None:
        return NetcdfLayout(path)
    return subprocess.run(["ncdump", "-h", path], check=True, capture_output=True, text=True).stdout


def _netcdf_vars(path, names):
    """ncdump_vars through netCDF4: numbers flattened as floats (fill values NaN), character
    arrays as one string per row."""
    import numpy as np
    out = {}
    with netCDF4.Dataset(path) as d:
        for name in names:
            if name not in d.variables:
                raise KeyError(name)
            v = d.variables[name]
            v.set_auto_chartostring(False)
            data = v[:]
            if v.dtype.kind == "S":
                rows = np.atleast_2d(np.ma.filled(data, b""))
                out[name] = [b"".join(c for c in row if c).decode() for row in rows]
            else:
                out[name] = np.ma.filled(np.ma.asarray(data, dtype=float), np.nan).ravel().tolist()
    return out


def ncdump_vars(path, names):
    """The data of the named variables as {name: list of numbers or strings} (flattened)."""
    if netCDF4 is not None:
        return _netcdf_vars(path, names)
    text = subprocess.run(["ncdump", "-v", ",".join(names), path], check=True, capture_output=True,
                          text=True).stdout
    data = text.split("\ndata:\n", 1)[1]
    out = {}
    for name in names:
        m = re.search(r"^\s*" + re.escape(name) + r"\s*=(.*?);\s*$", data, re.S | re.M)
        if not m:
            raise KeyError(name)
        body = m.group(1)
        if '"' in body:
            out[name] = re.findall(r'"((?:[^"\\]|\\.)*)"', body)
        else:
            vals = []
            for tok in body.replace("\n", " ").split(","):
                tok = tok.strip()
                if not tok:
                    continue
                vals.append(float("nan") if tok == "_" else float(tok))
            out[name] = vals
    return out


def dimension(header, name):
    if isinstance(header, NetcdfLayout):
        return header.dimensions.get(name)
    m = re.search(r"^\s*" + re.escape(name) + r"\s*=\s*(?:UNLIMITED\s*;\s*//\s*\()?(\d+)", header, re.M)
    return int(m.group(1)) if m else None


def has_variable(header, name):
    if isinstance(header, NetcdfLayout):
        return name in header.variables
    return re.search(r"\s" + re.escape(name) + r"\(", header) is not None


def _names(path, header, variable):
    return [s.strip() for s in ncdump_vars(path, [variable])[variable]] if has_variable(header, variable) else []


def nodal_variable_names(path, header):
    return _names(path, header, "name_nod_var")


def last_step_nodal(path, header, wanted):
    """{name: values} of the named nodal variables at the last time step (absent names: KeyError)."""
    return {v: (steps[-1] if steps else []) for v, steps in nodal_steps(path, header, wanted).items()}


def read_mesh(path, header=None):
    """Coordinates, element blocks, node sets and side sets, 0-based:
    {"x", "y", "z": lists; "blocks": [(name, [[n0, n1, n2, n3], ...])];
     "node_sets": {name: [node]}; "side_sets": {name: [(element, side 0..3)]}}.
    Elements are numbered over the blocks in file order (Exodus's implicit numbering)."""
    header = header or ncdump_header(path)
    nblocks = dimension(header, "num_el_blk") or 0
    nns = dimension(header, "num_node_sets") or 0
    nss = dimension(header, "num_side_sets") or 0
    fields = ["coordx", "coordy", "coordz"] + ["connect%d" % (b + 1) for b in range(nblocks)]
    fields += ["node_ns%d" % (s + 1) for s in range(nns) if has_variable(header, "node_ns%d" % (s + 1))]
    for s in range(nss):
        if has_variable(header, "elem_ss%d" % (s + 1)):
            fields += ["elem_ss%d" % (s + 1), "side_ss%d" % (s + 1)]
    d = ncdump_vars(path, fields)
    block_names = _names(path, header, "eb_names") or ["block_%d" % (b + 1) for b in range(nblocks)]
    ns_names = _names(path, header, "ns_names") or ["nodeset_%d" % (s + 1) for s in range(nns)]
    ss_names = _names(path, header, "ss_names") or ["sideset_%d" % (s + 1) for s in range(nss)]
    mesh = {"x": d["coordx"], "y": d["coordy"], "z": d["coordz"], "blocks": [], "node_sets": {}, "side_sets": {}}
    for b in range(nblocks):
        nodes_per = dimension(header, "num_nod_per_el%d" % (b + 1))
        conn = [int(v) - 1 for v in d["connect%d" % (b + 1)]]
        mesh["blocks"].append((block_names[b], [conn[i:i + nodes_per] for i in range(0, len(conn), nodes_per)]))
    for s in range(nns):
        mesh["node_sets"][ns_names[s]] = [int(v) - 1 for v in d.get("node_ns%d" % (s + 1), [])]
    for s in range(nss):
        elems = d.get("elem_ss%d" % (s + 1), [])
        sides = d.get("side_ss%d" % (s + 1), [])
        mesh["side_sets"][ss_names[s]] = [(int(e) - 1, int(k) - 1) for e, k in zip(elems, sides)]
    return mesh


def element_nodes(mesh):
    """Connectivity of every element, over the blocks in order (the side sets' numbering)."""
    return [element for _, elements in mesh["blocks"] for element in elements]


def side_set_triangles(mesh, name):
    """The faces of side set `name` as node triples (0-based; a quadrilateral as two triangles)."""
    elements = element_nodes(mesh)
    return [tri for e, side in mesh["side_sets"][name] for tri in triangles_of(element_faces(elements[e])[side])]


# ---- every time step (load histories: tribos writes each load step as a time step)


def time_values(path, header):
    """The time of every step (time_whole), [] when the file has none."""
    return ncdump_vars(path, ["time_whole"])["time_whole"] if has_variable(header, "time_whole") else []


def global_variables(path, header):
    """{name: [value at step 1, step 2, ...]} of the global variables ({} when none), in file order."""
    names = _names(path, header, "name_glo_var")
    if not names or not has_variable(header, "vals_glo_var"):
        return {}
    vals = ncdump_vars(path, ["vals_glo_var"])["vals_glo_var"]  # (time_step, num_glo_var), row-major
    return {name: vals[i::len(names)] for i, name in enumerate(names)}


def nodal_steps(path, header, wanted):
    """{name: [[values at step 1], [values at step 2], ...]} of the named nodal variables
    (absent names: KeyError)."""
    var_names = nodal_variable_names(path, header)
    for v in wanted:
        if v not in var_names:
            raise KeyError(v + " (the file has: " + ", ".join(var_names) + ")")
    n = dimension(header, "num_nodes")
    separate = has_variable(header, "vals_nod_var1")  # else one vals_nod_var(time, var, node)
    fields = ["vals_nod_var%d" % (var_names.index(v) + 1) for v in wanted] if separate else ["vals_nod_var"]
    d = ncdump_vars(path, fields) if wanted else {}
    out = {}
    for v in wanted:
        i = var_names.index(v) + 1
        if separate:
            vals = d["vals_nod_var%d" % i]
            out[v] = [vals[s * n:(s + 1) * n] for s in range(len(vals) // n)]
        else:
            vals = d["vals_nod_var"]
            steps = len(vals) // (len(var_names) * n)
            out[v] = [vals[((s * len(var_names)) + i - 1) * n:((s * len(var_names)) + i) * n] for s in range(steps)]
    return out
