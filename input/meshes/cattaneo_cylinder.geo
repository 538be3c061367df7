// Cattaneo-Mindlin line contact (plane strain): a cylinder on a flat block of the same
// material, pressed and then sheared along x (issue 31). Units mm. Full section in x (no
// symmetry plane: the tangential load is along x).
// As hertz_cylinder.geo otherwise: each body is meshed on its own (two OpenCASCADE volumes that
// share no entity: independent, non-matching meshes on the contact interface), the xz section
// is meshed in 2D and extruded along y over the slice thickness t = 2 hc with 2 element layers
// (the same mesh in every y-slice; contact nodes at y = 0, t/2, t).
//   cylinder: the lower half disc x in [-R, R], z in [0, R] of a cylinder of radius R (axis
//             along y, centre (0, y, R)); curved face = contact (the scene's slave), flat face z = R =
//             the displacement-driven top.
//   block:    x in [-W, W], z in [-H, 0]; z = 0 = contact (the scene's master), z = -H clamped.
// Element size hc on the cylinder and ratio*hc on the block within dmin of the contact line
// (x = 0, z = 0), growing linearly to hmax at dmax (Distance + Threshold fields, each
// restricted to its own body's section, so that the meshes do not match by coincidence; the
// slave, the cylinder, is the finer side).
// The cylinder is lifted by a tiny initial gap (default 1e-5 mm): gmsh 4.8 looks the nodes of
// all extruded volumes up by position when it splits the prisms into tetrahedra, and coincident
// nodes of the two bodies on the contact line would be mixed up (see hertz_cylinder.geo). Under
// a prescribed top displacement the gap only takes 1e-5 mm off the approach.
// Regenerate (from input/meshes):
//   gmsh -3 -format msh41 -setnumber hc 0.1 cattaneo_cylinder.geo -o cattaneo_cylinder_h0.1.msh
//   ../../build/bin/tribos-msh2exo cattaneo_cylinder_h0.1.msh cattaneo_cylinder_h0.1.exo
// (no --split-bodies: the bodies already have their own nodes).
SetFactory("OpenCASCADE");

DefineConstant[
  hc = {0.1, Name "Parameters/hc (element size at the contact line, cylinder)"},
  hmax = {2.0, Name "Parameters/hmax (element size far away)"},
  R = {10.0, Name "Parameters/R (cylinder radius)"},
  W = {10.0, Name "Parameters/W (block half width)"},
  H = {10.0, Name "Parameters/H (block height)"},
  dmin = {1.5, Name "Parameters/dmin (radius of the uniform hc zone)"},
  dmax = {10.0, Name "Parameters/dmax (distance where hmax is reached)"},
  ratio = {1.3, Name "Parameters/ratio (block size / cylinder size at the contact)"},
  gap = {1e-5, Name "Parameters/gap (initial gap, see above)"}
];
t = 2 * hc;        // slice thickness along y
nlayers = 2;       // element layers through t

// ---- cylinder (section in the plane y = 0): two quarter arcs (a circle arc must be < Pi) ----
Point(1) = {0, 0, gap};           // contact line
Point(2) = {R, 0, R + gap};       // right end of the arc on the top face
Point(3) = {0, 0, R + gap};       // centre (on the top face)
Point(4) = {-R, 0, R + gap};      // left end of the arc
Circle(1) = {4, 3, 1};    // contact arc, left
Circle(2) = {1, 3, 2};    // contact arc, right
Line(3) = {2, 4};         // top (z = R)
Curve Loop(1) = {1, 2, 3};
Plane Surface(1) = {1};

// ---- block ----
Point(11) = {-W, 0, 0};
Point(12) = {W, 0, 0};
Point(13) = {W, 0, -H};
Point(14) = {-W, 0, -H};
Line(11) = {11, 12};      // contact (z = 0)
Line(12) = {12, 13};      // x = W (free)
Line(13) = {13, 14};      // bottom (z = -H)
Line(14) = {14, 11};      // x = -W (free)
Curve Loop(11) = {11, 12, 13, 14};
Plane Surface(11) = {11};

// ---- mesh size: the distance to the contact line (x = 0, z = 0) as a formula (the block has
// no point there) ----
Field[1] = MathEval;
Field[1].F = "Sqrt(x^2 + z^2)";
Field[2] = Threshold;
Field[2].InField = 1;
Field[2].SizeMin = hc;
Field[2].SizeMax = hmax;
Field[2].DistMin = dmin;
Field[2].DistMax = dmax;
Field[3] = Restrict;
Field[3].InField = 2;
Field[3].SurfacesList = {1};
Field[3].CurvesList = {1, 2, 3};
Field[12] = Threshold;
Field[12].InField = 1;
Field[12].SizeMin = ratio * hc;
Field[12].SizeMax = hmax;
Field[12].DistMin = dmin;
Field[12].DistMax = dmax;
Field[13] = Restrict;
Field[13].InField = 12;
Field[13].SurfacesList = {11};
Field[13].CurvesList = {11, 12, 13, 14};
Field[20] = Min;
Field[20].FieldsList = {3, 13};
Background Field = 20;
Mesh.MeshSizeExtendFromBoundary = 0;
Mesh.MeshSizeFromPoints = 0;
Mesh.MeshSizeFromCurvature = 0;

// ---- structured extrusion along y: out[0] = face y = t, out[1] = volume ----
cyl[] = Extrude {0, t, 0} { Surface{1}; Layers{nlayers}; };
blk[] = Extrude {0, t, 0} { Surface{11}; Layers{nlayers}; };

// faces by position (eps: far below any element size)
eps = 1e-6;
cylAll[] = Boundary{ Volume{cyl[1]}; };
cylTop[] = Surface In BoundingBox{-R - eps, -eps, R + gap - eps, R + eps, t + eps, R + gap + eps};
cylEnds[] = {1, cyl[0]};
cylContact[] = cylAll[];
cylContact[] -= {cylTop[], cylEnds[]};
blkContact[] = Surface In BoundingBox{-W - eps, -eps, -eps, W + eps, t + eps, eps};
blkBottom[] = Surface In BoundingBox{-W - eps, -eps, -H - eps, W + eps, t + eps, -H + eps};
blkEnds[] = {11, blk[0]};
If (#cylTop[] != 1 || #cylContact[] != 2 || #blkContact[] != 1 || #blkBottom[] != 1)
  Error("cattaneo_cylinder.geo: face identification failed");
EndIf

Physical Volume("cylinder", 1) = {cyl[1]};
Physical Volume("block", 2) = {blk[1]};
Physical Surface("cylinder_contact", 1) = {cylContact[]};  // the curved face (two quarter arcs)
Physical Surface("cylinder_top", 2) = {cylTop[]};          // z = R, displacement-driven
Physical Surface("cylinder_ends", 4) = {cylEnds[]};        // y = 0 and y = t
Physical Surface("block_contact", 11) = {blkContact[]};    // z = 0
Physical Surface("block_bottom", 12) = {blkBottom[]};      // z = -H, clamped
Physical Surface("block_ends", 14) = {blkEnds[]};          // y = 0 and y = t
