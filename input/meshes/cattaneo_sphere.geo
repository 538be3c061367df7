// Cattaneo-Mindlin point contact: a sphere on a flat block of the same material, pressed and
// then sheared along x (issue 31). Units mm. Half model by the symmetry plane y = 0 (the
// tangential load is along x, in that plane).
// As hertz_sphere.geo otherwise: each body is meshed on its own (two OpenCASCADE volumes that
// are never fragmented: independent, non-matching meshes on the contact interface, initially
// touching at the origin).
//   sphere: the half y >= 0 of the lower hemisphere of radius R centred at (0, 0, R); curved
//           face = contact, flat face z = R = the displacement-driven top, y = 0 symmetry.
//   block:  x in [-W, W], y in [0, W], z in [-H, 0]; z = 0 contact, z = -H clamped, y = 0
//           symmetry.
// Element size hc (sphere) and ratio*hc (block) within dmin of the contact point, growing
// linearly to hmax at dmax (Threshold fields on the distance to the origin, each restricted to
// its own body, so that the meshes do not match by coincidence). The top face is driven by
// prescribed displacements, so its faceted area does not matter (no hrim refinement).
// Regenerate (from input/meshes):
//   gmsh -3 -format msh41 -setnumber hc 0.15 cattaneo_sphere.geo -o cattaneo_sphere_h0.15.msh
//   ../../build/bin/tribos-msh2exo cattaneo_sphere_h0.15.msh cattaneo_sphere_h0.15.exo
// (no --split-bodies: the bodies already have their own nodes).
SetFactory("OpenCASCADE");

DefineConstant[
  hc = {0.15, Name "Parameters/hc (element size at the contact point, sphere)"},
  hmax = {2.0, Name "Parameters/hmax (element size far away)"},
  ratio = {1.3, Name "Parameters/ratio (block size / sphere size at the contact)"},
  R = {10.0, Name "Parameters/R (sphere radius)"},
  W = {10.0, Name "Parameters/W (block half width in x, width in y)"},
  H = {10.0, Name "Parameters/H (block height)"},
  dmin = {1.3, Name "Parameters/dmin (radius of the uniform hc zone)"},
  dmax = {8.0, Name "Parameters/dmax (distance where hmax is reached)"}
];

// polar angle from -Pi/2 (south pole = contact point) to 0, azimuth 0 .. Pi (y >= 0); its
// plane face y = 0 comes in two pieces (azimuth 0 and Pi)
Sphere(1) = {0, 0, R, R, -Pi/2, 0, Pi};
Box(2) = {-W, 0, -H, 2 * W, W, H};

eps = 1e-6;
sphAll[] = Abs(Boundary{ Volume{1}; });
sphTop[] = Surface In BoundingBox{-R - eps, -eps, R - eps, R + eps, R + eps, R + eps};
sphSymY[] = Surface In BoundingBox{-R - eps, -eps, -eps, R + eps, eps, R + eps};
sphContact[] = sphAll[];
sphContact[] -= {sphTop[], sphSymY[]};
blkContact[] = Surface In BoundingBox{-W - eps, -eps, -eps, W + eps, W + eps, eps};
blkBottom[] = Surface In BoundingBox{-W - eps, -eps, -H - eps, W + eps, W + eps, -H + eps};
blkSymY[] = Surface In BoundingBox{-W - eps, -eps, -H - eps, W + eps, eps, eps};
If (#sphTop[] != 1 || #sphSymY[] != 2 || #sphContact[] != 1 ||
    #blkContact[] != 1 || #blkBottom[] != 1 || #blkSymY[] != 1)
  Error("cattaneo_sphere.geo: face identification failed");
EndIf

// ---- mesh size: the distance to the contact point (the origin) as a formula ----
sphCurves[] = Abs(Boundary{ Surface{sphAll[]}; });
blkAll[] = Abs(Boundary{ Volume{2}; });
blkCurves[] = Abs(Boundary{ Surface{blkAll[]}; });
Field[1] = MathEval;
Field[1].F = "Sqrt(x^2 + y^2 + z^2)";
Field[2] = Threshold;
Field[2].InField = 1;
Field[2].SizeMin = hc;
Field[2].SizeMax = hmax;
Field[2].DistMin = dmin;
Field[2].DistMax = dmax;
Field[3] = Restrict;
Field[3].InField = 2;
Field[3].VolumesList = {1};
Field[3].SurfacesList = {sphAll[]};
Field[3].CurvesList = {sphCurves[]};
Field[12] = Threshold;
Field[12].InField = 1;
Field[12].SizeMin = ratio * hc;
Field[12].SizeMax = hmax;
Field[12].DistMin = dmin;
Field[12].DistMax = dmax;
Field[13] = Restrict;
Field[13].InField = 12;
Field[13].VolumesList = {2};
Field[13].SurfacesList = {blkAll[]};
Field[13].CurvesList = {blkCurves[]};
Field[20] = Min;
Field[20].FieldsList = {3, 13};
Background Field = 20;
Mesh.MeshSizeExtendFromBoundary = 0;
Mesh.MeshSizeFromPoints = 0;
Mesh.MeshSizeFromCurvature = 0;

Physical Volume("sphere", 1) = {1};
Physical Volume("block", 2) = {2};
Physical Surface("sphere_contact", 1) = {sphContact[]};   // the curved face
Physical Surface("sphere_top", 2) = {sphTop[]};           // z = R, displacement-driven
Physical Surface("sphere_sym_y", 4) = {sphSymY[]};        // y = 0
Physical Surface("block_contact", 11) = {blkContact[]};   // z = 0
Physical Surface("block_bottom", 12) = {blkBottom[]};     // z = -H, clamped
Physical Surface("block_sym_y", 14) = {blkSymY[]};        // y = 0
