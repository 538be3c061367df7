// Hertz line contact (plane strain), half model by the symmetry plane x = 0. Units mm.
// A steel cylinder (radius R, axis along y, centre (0, y, R)) on an aluminium block; each body
// is meshed on its own (two volumes that share no entity: independent, non-matching meshes on
// the contact interface, initially touching along the line x = 0, z = 0).
//   cylinder: the lower-right quarter disc x in [0, R], z in [0, R] (curved face = contact,
//             z = R face loaded), extruded along y over the slice thickness t.
//   block:    x in [0, W], z in [-H, 0], same slice thickness t.
// The xz section is meshed in 2D with the element size hc at the contact line growing to hmax
// far away (Distance + Threshold fields) and extruded with 2 element layers through t = 2 hc,
// so that the mesh is the same in every y-slice and there are contact nodes inside the slice.
// The cylinder is lifted by a tiny initial gap (default 1e-5 mm, i.e. its lowest line is at
// z = gap): gmsh 4.8 looks the nodes of all extruded volumes up by position when it splits the
// prisms into tetrahedra, and coincident nodes of the two bodies on the contact line would be
// mixed up (tetrahedra of one body on the other's nodes). Under a prescribed load a uniform gap
// changes nothing but the cylinder's rigid approach; with Contact/Search Distance >> gap the
// contact nodes pair as before.
// Regenerate (from input/meshes):
//   gmsh -3 -format msh41 -setnumber hc 0.1 hertz_cylinder.geo -o hertz_cylinder_h0.1.msh
//   (hexahedra: -setnumber Hex 1 ... -o hertz_cylinder_hex_h0.2.msh)
//   ../../build/bin/tribos-msh2exo hertz_cylinder_h0.1.msh hertz_cylinder_h0.1.exo
// (no --split-bodies: the bodies already have their own nodes).
// OpenCASCADE: two volumes that are never fragmented stay separate entities, each with its own
// nodes (the built-in kernel would merge the coincident points of the two bodies).
SetFactory("OpenCASCADE");

DefineConstant[
  hc = {0.1, Name "Parameters/hc (element size at the contact line)"},
  hmax = {2.0, Name "Parameters/hmax (element size far away)"},
  R = {10.0, Name "Parameters/R (cylinder radius)"},
  W = {10.0, Name "Parameters/W (block width)"},
  H = {10.0, Name "Parameters/H (block height)"},
  dmin = {1.5, Name "Parameters/dmin (radius of the uniform hc zone)"},
  dmax = {10.0, Name "Parameters/dmax (distance where hmax is reached)"},
  ratio = {1.3, Name "Parameters/ratio (block size / cylinder size at the contact)"},
  gap = {1e-5, Name "Parameters/gap (initial gap, see above)"},
  Hex = {0, Name "Parameters/Hex (1: quadrilateral sections extruded into hexahedra)"}
];
t = 2 * hc;        // slice thickness along y
nlayers = 2;       // element layers through t

// ---- cylinder (section in the plane y = 0) ----
Point(1) = {0, 0, gap};           // contact line
Point(2) = {R, 0, R + gap};       // end of the arc on the top face
Point(3) = {0, 0, R + gap};       // centre = corner of top and symmetry faces
Circle(1) = {1, 3, 2};    // contact arc
Line(2) = {2, 3};         // top (z = R)
Line(3) = {3, 1};         // symmetry (x = 0)
Curve Loop(1) = {1, 2, 3};
Plane Surface(1) = {1};

// ---- block ----
Point(11) = {0, 0, 0};    // coincides with point 1 but is a separate entity
Point(12) = {W, 0, 0};
Point(13) = {W, 0, -H};
Point(14) = {0, 0, -H};
Line(11) = {11, 12};      // contact (z = 0)
Line(12) = {12, 13};      // x = W (free)
Line(13) = {13, 14};      // bottom (z = -H)
Line(14) = {14, 11};      // symmetry (x = 0)
Curve Loop(11) = {11, 12, 13, 14};
Plane Surface(11) = {11};

// ---- mesh size: hc (cylinder) and ratio*hc (block) within dmin of the contact line, linear
// growth to hmax at dmax; each field restricted to its own body's section so that the two
// meshes do not match on the interface (the block, master, is the coarser one) ----
Field[1] = Distance;
Field[1].PointsList = {1};
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
Field[11] = Distance;
Field[11].PointsList = {11};
Field[12] = Threshold;
Field[12].InField = 11;
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
// Hex = 1: the sections are recombined into quadrilaterals (Blossom, then every remaining
// triangle split too: all quadrilaterals) and extruded with Recombine: 8-node hexahedra.
If (Hex)
  Recombine Surface{1, 11};
  Mesh.RecombinationAlgorithm = 1;
  Mesh.SubdivisionAlgorithm = 1;
  cyl[] = Extrude {0, t, 0} { Surface{1}; Layers{nlayers}; Recombine; };
  blk[] = Extrude {0, t, 0} { Surface{11}; Layers{nlayers}; Recombine; };
Else
  cyl[] = Extrude {0, t, 0} { Surface{1}; Layers{nlayers}; };
  blk[] = Extrude {0, t, 0} { Surface{11}; Layers{nlayers}; };
EndIf

// faces by position (eps: far below any element size)
eps = 1e-6;
cylAll[] = Boundary{ Volume{cyl[1]}; };
cylTop[] = Surface In BoundingBox{-eps, -eps, R + gap - eps, R + eps, t + eps, R + gap + eps};
cylSym[] = Surface In BoundingBox{-eps, -eps, gap - eps, eps, t + eps, R + gap + eps};
cylEnds[] = {1, cyl[0]};
cylContact[] = cylAll[];
cylContact[] -= {cylTop[], cylSym[], cylEnds[]};
blkAll[] = Boundary{ Volume{blk[1]}; };
blkContact[] = Surface In BoundingBox{-eps, -eps, -eps, W + eps, t + eps, eps};
blkBottom[] = Surface In BoundingBox{-eps, -eps, -H - eps, W + eps, t + eps, -H + eps};
blkSym[] = Surface In BoundingBox{-eps, -eps, -H - eps, eps, t + eps, eps};
blkEnds[] = {11, blk[0]};
If (#cylTop[] != 1 || #cylSym[] != 1 || #cylContact[] != 1 || #blkContact[] != 1 ||
    #blkBottom[] != 1 || #blkSym[] != 1)
  Error("hertz_cylinder.geo: face identification failed");
EndIf

Physical Volume("cylinder", 1) = {cyl[1]};
Physical Volume("block", 2) = {blk[1]};
Physical Surface("cylinder_contact", 1) = {cylContact[]};  // the curved face
Physical Surface("cylinder_top", 2) = {cylTop[]};          // z = R, loaded
Physical Surface("cylinder_sym", 3) = {cylSym[]};          // x = 0
Physical Surface("cylinder_ends", 4) = {cylEnds[]};        // y = 0 and y = t
Physical Surface("block_contact", 11) = {blkContact[]};    // z = 0
Physical Surface("block_bottom", 12) = {blkBottom[]};      // z = -H, clamped
Physical Surface("block_sym", 13) = {blkSym[]};            // x = 0
Physical Surface("block_ends", 14) = {blkEnds[]};          // y = 0 and y = t
