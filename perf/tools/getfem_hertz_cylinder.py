#!/usr/bin/python3
"""GetFEM reference solve of input/hertz_cylinder.xml (Hertz line contact, plane-strain slice).

Reads the same Exodus mesh Tribos reads (element blocks "cylinder" and "block", side sets named
cylinder_contact, cylinder_top, cylinder_sym, cylinder_ends, block_contact, block_bottom, block_sym,
block_ends) and solves the discrete problem the scene describes with GetFEM (python3-getfem):

  * small-strain isotropic linear elasticity, cylinder steel E = 2.1e5 nu = 0.3, block aluminium
    E = 7e4 nu = 0.33, P1 tetrahedra or Q1 hexahedra as in the file (each body its own GetFEM mesh);
  * traction {0, 0, -200} MPa on cylinder_top (source term brick);
  * block_bottom clamped, u_x = 0 on *_sym, u_y = 0 on *_ends (all by Lagrange multipliers on the
    side-set faces; GetFEM filters the redundant multiplier dofs where the sets share nodes);
  * contact: GetFEM's nodal contact brick between non-matching meshes (slave block_contact on the
    block, master cylinder_contact on the cylinder), nodal multipliers, non-symmetric Alart-Curnier
    augmented Lagrangian (r = 7e4 by default) solved by GetFEM's Newton (md.solve, 'basic' line
    search: the default one cycles without converging with Coulomb friction); --friction None
    (frictionless) or Coulomb (coefficient 0.2, one static step: slip measured from the reference
    configuration). The normal multipliers start at -(applied load / slave nodes) each: with 0 the
    cylinder, held in z only by contact across the 1e-5 gap, gives a singular first tangent matrix.
    GetFEM 5.4's interface itself prints "ok here" on stdout when the contact brick is added.

Prints one line:
  getfem mesh=... friction=... nodes=... contact_nodes=... normal_force=... (expected ...)
  reaction_z=... newton=... converged=... setup_solve_s=... total_s=...
setup_solve_s is time.perf_counter() around GetFEM model set-up (mesh_fem, integration, bricks) and
md.solve; total_s adds reading the Exodus file and building the GetFEM meshes.
Exit status 77 when `import getfem` fails, 1 when the normal force is off the expected one by > 1 %.
"""
import argparse
import os
import sys
import time

T_START = time.perf_counter()
try:
    import getfem as gf
except Exception as exc:  # noqa: BLE001 - any import failure means "not available"
    print(f"getfem_hertz_cylinder: python3-getfem not available ({exc}); skipped", file=sys.stderr)
    sys.exit(77)
import numpy as np

# Exodus local side -> local nodes (0-based), Exodus II manual
EXO_SIDES = {
    4: [[0, 1, 3], [1, 2, 3], [0, 2, 3], [0, 1, 2]],                       # TETRA4
    8: [[0, 1, 5, 4], [1, 2, 6, 5], [2, 3, 7, 6], [0, 4, 7, 3], [0, 3, 2, 1], [4, 5, 6, 7]],  # HEX8
}
# GetFEM local vertex k = Exodus local node PERM[k] (GetFEM's Q1 cube numbers vertices
# lexicographically, Exodus HEX8 counter-clockwise); PERM is its own inverse.
PERM = {4: [0, 1, 2, 3], 8: [0, 1, 3, 2, 4, 5, 7, 6]}
GEOTRANS = {4: 'GT_PK(3,1)', 8: 'GT_QK(3,1)'}
FEM = {4: 'FEM_PK(3,1)', 8: 'FEM_QK(3,1)'}
IM = {4: 'IM_TETRAHEDRON(2)', 8: 'IM_GAUSS_PARALLELEPIPED(3,2)'}

MATERIALS = {'cylinder': (2.1e5, 0.3), 'block': (7.0e4, 0.33)}
TRACTION = [0.0, 0.0, -200.0]
FRICTION_COEFF = 0.2


def names(ds, var):
    from netCDF4 import chartostring
    if var not in ds.variables:
        return []
    return [str(s).strip() for s in chartostring(ds.variables[var][:])]


def read_exodus(path):
    import netCDF4
    ds = netCDF4.Dataset(path)
    ds.set_auto_mask(False)
    xyz = np.vstack([ds.variables['coord' + c][:] for c in 'xyz']).astype(float)  # 3 x nn
    blocks = {}
    first = 0
    for i, name in enumerate(names(ds, 'eb_names'), start=1):
        conn = np.asarray(ds.variables[f'connect{i}'][:], dtype=np.int64) - 1
        blocks[name] = (first, conn)
        first += conn.shape[0]
    side_sets = {}
    for i, name in enumerate(names(ds, 'ss_names'), start=1):
        side_sets[name] = (np.asarray(ds.variables[f'elem_ss{i}'][:], dtype=np.int64) - 1,
                           np.asarray(ds.variables[f'side_ss{i}'][:], dtype=np.int64) - 1)
    ds.close()
    return xyz, blocks, side_sets


class Body:
    """One element block as its own GetFEM mesh, with its side sets as face regions."""

    def __init__(self, name, xyz, first, conn):
        self.name = name
        self.first, self.nelem = first, conn.shape[0]
        self.nv = conn.shape[1]
        if self.nv not in GEOTRANS:
            raise SystemExit(f"block {name}: {self.nv}-node elements not supported (TETRA4, HEX8)")
        self.mesh = gf.Mesh('empty', 3)
        pts = np.asfortranarray(xyz[:, conn[:, PERM[self.nv]].T])  # 3 x nv x ne
        cvids = np.asarray(self.mesh.add_convex(gf.GeoTrans(GEOTRANS[self.nv]), pts)).ravel()
        if cvids.size != self.nelem or np.any(np.diff(cvids) != 1):
            raise SystemExit("unexpected GetFEM convex numbering")
        self.cv0 = int(cvids[0])
        self.exo_nodes = np.unique(conn)
        if self.mesh.nbpts() != self.exo_nodes.size:
            raise SystemExit(f"block {name}: GetFEM merged points ({self.mesh.nbpts()} vs "
                             f"{self.exo_nodes.size} Exodus nodes)")
        # GetFEM face f of a convex -> set of local vertices (same for every convex of the block)
        pid, idx = self.mesh.pid_from_cvid(self.cv0)
        local = {int(p): k for k, p in enumerate(np.asarray(pid).ravel())}
        nfaces = 4 if self.nv == 4 else 6
        face_of = {}
        for f in range(nfaces):
            fp = np.asarray(self.mesh.pid_in_faces(np.array([[self.cv0], [f]]))).ravel()
            face_of[frozenset(local[int(p)] for p in fp)] = f
        self.exo_side_to_face = [face_of[frozenset(PERM[self.nv][j] for j in side)]
                                 for side in EXO_SIDES[self.nv]]
        self.regions = {}

    def add_region(self, name, elems, sides, rid):
        mine = (elems >= self.first) & (elems < self.first + self.nelem)
        if not np.any(mine):
            return False
        if not np.all(mine):
            raise SystemExit(f"side set {name} spans two element blocks")
        cv = elems - self.first + self.cv0
        faces = np.array([self.exo_side_to_face[s] for s in sides])
        self.mesh.set_region(rid, np.vstack([cv, faces]))
        self.regions[name] = rid
        return True


def main():
    ap = argparse.ArgumentParser(description=__doc__.split('\n')[0])
    ap.add_argument('mesh', help='Exodus file (absolute, relative to cwd, or relative to input/)')
    ap.add_argument('--friction', choices=['None', 'Coulomb'], default='None')
    ap.add_argument('--r', type=float, default=None,
                    help='augmentation parameter of the contact brick (default: E of the block)')
    ap.add_argument('--max-res', type=float, default=None,
                    help='Newton residual target (default 1e-8 x applied force)')
    ap.add_argument('--lambda0', type=float, default=-1.0,
                    help='initial normal multipliers = lambda0 x applied force / slave nodes')
    ap.add_argument('--lsolver', default='auto', help="GetFEM linear solver ('auto', 'mumps', 'superlu')")
    ap.add_argument('--lsearch', default='basic',
                    help="GetFEM line search ('simplest', 'systematic', 'quadratic', 'basic')")
    ap.add_argument('--max-iter', type=int, default=100)
    ap.add_argument('--verbose', action='store_true')
    args = ap.parse_args()

    path = args.mesh
    if not os.path.exists(path):
        here = os.path.dirname(os.path.abspath(__file__))
        alt = os.path.join(here, '..', '..', 'input', path)
        if os.path.exists(alt):
            path = alt
        else:
            raise SystemExit(f"mesh not found: {args.mesh}")

    xyz, blocks, side_sets = read_exodus(path)
    bodies = {}
    for name in ('cylinder', 'block'):
        if name not in blocks:
            raise SystemExit(f"element block {name!r} missing in {path}")
        bodies[name] = Body(name, xyz, *blocks[name])
    for rid, (ssname, (elems, sides)) in enumerate(sorted(side_sets.items()), start=1):
        owner = 'cylinder' if ssname.startswith('cylinder') else 'block'
        bodies[owner].add_region(ssname, elems, sides, rid)
    for need in ('cylinder_contact', 'cylinder_top', 'cylinder_sym', 'cylinder_ends'):
        assert need in bodies['cylinder'].regions, need
    for need in ('block_contact', 'block_bottom', 'block_sym', 'block_ends'):
        assert need in bodies['block'].regions, need
    thickness = float(xyz[1].max() - xyz[1].min())
    applied = -TRACTION[2] * 10.0 * thickness  # traction x (R = 10 mm) x t = 2000 N/mm x t

    # ---------------------------------------------------------------- GetFEM model set-up + solve
    t0 = time.perf_counter()
    gf.util_trace_level(0)
    md = gf.Model('real')
    var = {'cylinder': 'uc', 'block': 'ub'}
    mims = {}
    for name, b in bodies.items():
        mf = gf.MeshFem(b.mesh, 3)
        mf.set_fem(gf.Fem(FEM[b.nv]))
        mim = gf.MeshIm(b.mesh, gf.Integ(IM[b.nv]))
        mims[name] = mim
        b.mf = mf
        u = var[name]
        md.add_fem_variable(u, mf)
        E, nu = MATERIALS[name]
        lam, mu = E * nu / ((1 + nu) * (1 - 2 * nu)), E / (2 * (1 + nu))
        md.add_initialized_data(f'lambda_{name}', [lam])
        md.add_initialized_data(f'mu_{name}', [mu])
        md.add_isotropic_linearized_elasticity_brick(mim, u, f'lambda_{name}', f'mu_{name}')
        # multiplier space: scalar P1/Q1 on the faces (normal conditions), vector for the clamp
        b.mf_m1 = gf.MeshFem(b.mesh, 1)
        b.mf_m1.set_fem(gf.Fem(FEM[b.nv]))
        # symmetry plane x = 0 and end faces y = 0 / y = t are planes with normals +-e_x / +-e_y:
        # a normal Dirichlet condition there is exactly u_x = 0 / u_y = 0.
        md.add_normal_Dirichlet_condition_with_multipliers(mim, u, b.mf_m1, b.regions[f'{name}_sym'])
        md.add_normal_Dirichlet_condition_with_multipliers(mim, u, b.mf_m1, b.regions[f'{name}_ends'])

    cyl, blk = bodies['cylinder'], bodies['block']
    md.add_initialized_data('traction', TRACTION)
    md.add_source_term_brick(mims['cylinder'], 'uc', 'traction', cyl.regions['cylinder_top'])
    # clamp block_bottom: vector multiplier, named so the reaction can be integrated
    mf_bot = gf.MeshFem(blk.mesh, 3)
    mf_bot.set_fem(gf.Fem(FEM[blk.nv]))
    md.add_multiplier('mult_bottom', mf_bot, 'ub', mims['block'], blk.regions['block_bottom'])
    md.add_Dirichlet_condition_with_multipliers(mims['block'], 'ub', 'mult_bottom',
                                                blk.regions['block_bottom'])

    # contact: the brick adds the multipliers itself, one normal (and two tangential) nodal
    # forces per slave node of block_contact
    n_slave = len(np.asarray(blk.mesh.pid_in_regions(blk.regions['block_contact'])).ravel())
    r = args.r if args.r is not None else MATERIALS['block'][0]
    md.add_initialized_data('r', [r])
    if args.friction == 'None':
        md.add_nodal_contact_between_nonmatching_meshes_brick(
            mims['block'], mims['cylinder'], 'ub', 'uc', 'lambda_n', 'r',
            blk.regions['block_contact'], cyl.regions['cylinder_contact'], 1, 0, 1)
    else:
        md.add_initialized_data('friction_coeff', [FRICTION_COEFF])
        # GetFEM 5.4's interface parser of this command reads, with friction, one string more
        # than documented: after multname_t it discards the next string and takes the two
        # following ones as dataname_r and dataname_fr (gf_model_set.cc pops dataname_r again).
        # Pass 'r' twice so that the call is right with both readings; the argument count
        # (at most 13) then leaves no room for augmented_version, whose default is 1 anyway.
        md.add_nodal_contact_between_nonmatching_meshes_brick(
            mims['block'], mims['cylinder'], 'ub', 'uc', 'lambda_n', 'lambda_t', 'r', 'r',
            'friction_coeff', blk.regions['block_contact'], cyl.regions['cylinder_contact'],
            1, 0)

    # The cylinder is held in z only by the contact (initial gap 1e-5): with lambda_n = 0 every
    # slave node starts inactive and the first tangent matrix is singular. Start with every slave
    # node pressed (the applied load spread evenly); Newton then releases the ones that separate.
    n_mult = np.asarray(md.variable('lambda_n')).size
    md.set_variable('lambda_n', np.full(n_mult, args.lambda0 * applied / n_mult))
    max_res = args.max_res if args.max_res is not None else 1e-8 * applied
    opts = ['max_res', max_res, 'max_iter', args.max_iter, 'lsolver', args.lsolver]
    if args.lsearch:
        opts += ['lsearch', args.lsearch]
    if args.verbose:
        opts.append('noisy')
    out = md.solve(*opts)
    t1 = time.perf_counter()
    nbit, converged = (out[0], out[1]) if isinstance(out, (tuple, list)) else (out, -1)

    lam_n = np.asarray(md.variable('lambda_n')).ravel()
    normal_force = abs(float(lam_n.sum()))
    reaction_z = float(gf.asm_generic(mims['block'], 0, 'mult_bottom(3)', blk.regions['block_bottom'], md))
    nodes = cyl.mesh.nbpts() + blk.mesh.nbpts()
    dev = abs(normal_force - applied) / applied
    print(f"getfem mesh={os.path.basename(path)} friction={args.friction} nodes={nodes} "
          f"slave_nodes={n_slave} active={int(np.count_nonzero(np.abs(lam_n) > 1e-12 * applied))} "
          f"normal_force={normal_force:.4f} expected={applied:.1f} reaction_z={abs(reaction_z):.4f} "
          f"newton={nbit} converged={converged} setup_solve_s={t1 - t0:.3f} "
          f"total_s={time.perf_counter() - T_START:.3f}")
    if dev > 0.01:
        print(f"getfem_hertz_cylinder: normal force off by {100 * dev:.2f} % (> 1 %)", file=sys.stderr)
        return 1
    return 0


if __name__ == '__main__':
    sys.exit(main())
