// Plane-strain shrink fit, quarter model, as a user meshes it from CAD: both contact surfaces are
// true circles (the shaft's r = 20.01 mm, the hub's bore r = 20 mm: an interference of 0.01 mm),
// each body meshed on its own with its own element size, so the meshes do not match and the
// facets of linear elements sag by h^2 / (8 R) between their nodes (0.006 mm at h = 1: as much as
// the interference). Scene: test/integration/shrink_fit.xml (its node and side set names; Lame's
// contact pressure 34.615 MPa). Units mm.
//   shaft (block_0): hollow, r in [10, 20.01];  hub (block_1): r in [20, 40];  slab z in [0, T].
// Regenerate (from input/meshes):
//   gmsh -3 -format msh41 -setnumber hs 1.0 -setnumber hh 1.3 shrink_fit.geo -o f.msh   (4-node tetrahedra;
//     -setnumber Hex 1: 8-node hexahedra; -order 2: 10-node tetrahedra with faces on the circles)
//   ../../build/bin/tribos-msh2exo f.msh shrink_fit_gmsh_tet4_h1.exo
// OpenCASCADE: the two bodies stay separate entities with their own nodes.
SetFactory("OpenCASCADE");
DefineConstant[
  hs = {1.0, Name "Parameters/hs (shaft element size)"},
  hh = {1.3, Name "Parameters/hh (hub element size)"},
  T = {2.0, Name "Parameters/T (slab thickness)"},
  nl = {2, Name "Parameters/nl (element layers through T)"},
  Hex = {0, Name "Parameters/Hex (1: quadrilateral sections extruded into hexahedra)"}
];
delta = 0.01;  // radial interference
Point(1) = {0, 0, 0};
Point(2) = {10, 0, 0}; Point(3) = {20 + delta, 0, 0}; Point(4) = {0, 20 + delta, 0}; Point(5) = {0, 10, 0};
Line(1) = {2, 3}; Circle(2) = {3, 1, 4}; Line(3) = {4, 5}; Circle(4) = {5, 1, 2};
Curve Loop(1) = {1, 2, 3, 4}; Plane Surface(1) = {1};
Point(11) = {0, 0, 0};
Point(12) = {20, 0, 0}; Point(13) = {40, 0, 0}; Point(14) = {0, 40, 0}; Point(15) = {0, 20, 0};
Line(11) = {12, 13}; Circle(12) = {13, 11, 14}; Line(13) = {14, 15}; Circle(14) = {15, 11, 12};
Curve Loop(11) = {11, 12, 13, 14}; Plane Surface(11) = {11};
MeshSize{ PointsOf{Surface{1};} } = hs;
MeshSize{ PointsOf{Surface{11};} } = hh;
// Extruded along z: out[0] the face z = T, out[1] the volume, out[2..5] the faces swept by the
// section's curves in their order (shaft: line y = 0, outer arc, line x = 0, inner arc).
If (Hex)
  Recombine Surface{1, 11};
  Mesh.RecombinationAlgorithm = 1;
  Mesh.SubdivisionAlgorithm = 1;
  s[] = Extrude {0, 0, T} { Surface{1}; Layers{nl}; Recombine; };
  h[] = Extrude {0, 0, T} { Surface{11}; Layers{nl}; Recombine; };
Else
  s[] = Extrude {0, 0, T} { Surface{1}; Layers{nl}; };
  h[] = Extrude {0, 0, T} { Surface{11}; Layers{nl}; };
EndIf
Physical Volume("block_0", 1) = {s[1]};
Physical Volume("block_1", 2) = {h[1]};
Physical Surface("shaft_x0", 1) = {s[4]};
Physical Surface("hub_x0", 2) = {h[4]};
Physical Surface("shaft_y0", 3) = {s[2]};
Physical Surface("hub_y0", 4) = {h[2]};
Physical Surface("all_z0", 5) = {1, 11};
Physical Surface("all_z1", 6) = {s[0], h[0]};
Physical Surface("shaft_outer", 7) = {s[3]};
Physical Surface("hub_bore", 8) = {h[5]};
