// Hertz point contact, quarter model by the symmetry planes x = 0 and y = 0. Units mm.
// A steel sphere (radius R, centre (0, 0, R)) on an aluminium block; each body is meshed on
// its own (two OpenCASCADE volumes that are never fragmented: independent, non-matching
// meshes on the contact interface, initially touching at the point (0, 0, 0)).
//   sphere: the quarter of the lower hemisphere x >= 0, y >= 0, z <= R (curved face = contact,
//           z = R face loaded, x = 0 and y = 0 faces symmetry planes).
//   block:  x, y in [0, W], z in [-H, 0].
// Element size hc (sphere) and ratio*hc (block, the master, coarser so that the meshes do not
// match) within dmin of the contact point, growing linearly to hmax at dmax (Distance +
// Threshold fields, each restricted to its own body). The rim of the loaded face z = R gets
// the size hrim (0.5: 32 segments on the quarter circle), so that the faceted loaded face has
// the area pi R^2 / 4 to 0.04 % (with hmax = 2 it would be 0.64 % short, and so the load).
// Regenerate (from input/meshes):
//   gmsh -3 -format msh41 -setnumber hc 0.15 hertz_sphere.geo -o hertz_sphere_h0.15.msh
//   ../../build/bin/tribos-msh2exo hertz_sphere_h0.15.msh hertz_sphere_h0.15.exo
// (a hexahedral block: -setnumber HexBlock 1 ... -o hertz_sphere_hexblock_h0.15.msh)
// (no --split-bodies: the bodies already have their own nodes).
SetFactory("OpenCASCADE");

DefineConstant[
  hc = {0.15, Name "Parameters/hc (element size at the contact point)"},
  hmax = {2.0, Name "Parameters/hmax (element size far away)"},
  ratio = {1.3, Name "Parameters/ratio (block size / sphere size at the contact)"},
  R = {10.0, Name "Parameters/R (sphere radius)"},
  W = {10.0, Name "Parameters/W (block width)"},
  H = {10.0, Name "Parameters/H (block height)"},
  dmin = {1.3, Name "Parameters/dmin (radius of the uniform hc zone)"},
  dmax = {8.0, Name "Parameters/dmax (distance where hmax is reached)"},
  hrim = {0.5, Name "Parameters/hrim (element size on the rim of the loaded face)"},
  HexBlock = {0, Name "Parameters/HexBlock (1: the block in 8-node hexahedra, graded to the contact corner)"},
  nblock = {20, Name "Parameters/nblock (HexBlock: cells per block edge)"},
  growth = {1.088, Name "Parameters/growth (HexBlock: size ratio of neighbouring cells from the corner)"}
];

// polar angle from -Pi/2 (south pole = contact point) to 0, azimuth 0 .. Pi/2 (x, y >= 0)
Sphere(1) = {0, 0, R, R, -Pi/2, 0, Pi/2};
Box(2) = {0, 0, -H, W, W, H};

eps = 1e-6;
sphAll[] = Abs(Boundary{ Volume{1}; });
sphTop[] = Surface In BoundingBox{-eps, -eps, R - eps, R + eps, R + eps, R + eps};
sphSymX[] = Surface In BoundingBox{-eps, -eps, -eps, eps, R + eps, R + eps};
sphSymY[] = Surface In BoundingBox{-eps, -eps, -eps, R + eps, eps, R + eps};
sphContact[] = sphAll[];
sphContact[] -= {sphTop[], sphSymX[], sphSymY[]};
blkContact[] = Surface In BoundingBox{-eps, -eps, -eps, W + eps, W + eps, eps};
blkBottom[] = Surface In BoundingBox{-eps, -eps, -H - eps, W + eps, W + eps, -H + eps};
blkSymX[] = Surface In BoundingBox{-eps, -eps, -H - eps, eps, W + eps, eps};
blkSymY[] = Surface In BoundingBox{-eps, -eps, -H - eps, W + eps, eps, eps};
If (#sphTop[] != 1 || #sphSymX[] != 1 || #sphSymY[] != 1 || #sphContact[] != 1 ||
    #blkContact[] != 1 || #blkBottom[] != 1 || #blkSymX[] != 1 || #blkSymY[] != 1)
  Error("hertz_sphere.geo: face identification failed");
EndIf
sphPole[] = Point In BoundingBox{-eps, -eps, -eps, eps, eps, eps};   // both bodies' points at 0

// ---- mesh size ----
sphCurves[] = Abs(Boundary{ Surface{sphAll[]}; });
blkAll[] = Abs(Boundary{ Volume{2}; });
blkCurves[] = Abs(Boundary{ Surface{blkAll[]}; });
Field[1] = Distance;
Field[1].PointsList = {sphPole[]};
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
sphRim[] = Abs(Boundary{ Surface{sphTop[]}; });
sphRim[] -= {Curve In BoundingBox{-eps, -eps, -eps, eps, R + eps, R + eps}};   // x = 0 edge
sphRim[] -= {Curve In BoundingBox{-eps, -eps, -eps, R + eps, eps, R + eps}};   // y = 0 edge
If (#sphRim[] != 1)
  Error("hertz_sphere.geo: rim identification failed");
EndIf
Field[4] = Distance;
Field[4].CurvesList = {sphRim[]};
Field[4].NumPointsPerCurve = 200;
Field[5] = Threshold;
Field[5].InField = 4;
Field[5].SizeMin = hrim;
Field[5].SizeMax = hmax;
Field[5].DistMin = 0;
Field[5].DistMax = 4 * (hmax - hrim);
Field[6] = Restrict;
Field[6].InField = 5;
Field[6].VolumesList = {1};
Field[6].SurfacesList = {sphAll[]};
Field[6].CurvesList = {sphCurves[]};
Field[20] = Min;
Field[20].FieldsList = {3, 6, 13};
Background Field = 20;
Mesh.MeshSizeExtendFromBoundary = 0;
Mesh.MeshSizeFromPoints = 0;
Mesh.MeshSizeFromCurvature = 0;

// HexBlock = 1: a structured block of nblock^3 hexahedra, every edge graded by `growth` from
// the contact corner (0, 0, 0) (first cell 10 (growth - 1) / (growth^nblock - 1): 0.20 for the
// defaults); the sphere keeps its tetrahedra (slave quadrilaterals against master triangles).
If (HexBlock)
  For k In {0 : #blkCurves[] - 1}
    c = blkCurves[k];
    ends[] = PointsOf{ Curve{c}; };
    p0[] = Point{ends[0]};
    p1[] = Point{ends[1]};
    If (Fabs(p0[0]) + Fabs(p0[1]) + Fabs(p0[2]) < Fabs(p1[0]) + Fabs(p1[1]) + Fabs(p1[2]))
      Transfinite Curve{c} = nblock + 1 Using Progression growth;
    Else
      Transfinite Curve{c} = nblock + 1 Using Progression 1 / growth;
    EndIf
  EndFor
  Transfinite Surface{blkAll[]};
  Recombine Surface{blkAll[]};
  Transfinite Volume{2};
  Recombine Volume{2};
EndIf

Physical Volume("sphere", 1) = {1};
Physical Volume("block", 2) = {2};
Physical Surface("sphere_contact", 1) = {sphContact[]};   // the curved face
Physical Surface("sphere_top", 2) = {sphTop[]};           // z = R, loaded
Physical Surface("sphere_sym_x", 3) = {sphSymX[]};        // x = 0
Physical Surface("sphere_sym_y", 4) = {sphSymY[]};        // y = 0
Physical Surface("block_contact", 11) = {blkContact[]};   // z = 0
Physical Surface("block_bottom", 12) = {blkBottom[]};     // z = -H, clamped
Physical Surface("block_sym_x", 13) = {blkSymX[]};        // x = 0
Physical Surface("block_sym_y", 14) = {blkSymY[]};        // y = 0
