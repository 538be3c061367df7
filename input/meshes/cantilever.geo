// Slender cantilever (issue 32: tip deflection per element type, doc/elements.md). Units mm.
// Beam 0 <= x <= L, square section H x H (0 <= y, z <= H); Physical Volume "beam",
// Physical Surfaces "clamped" (x = 0) and "tip" (x = L). The section (y-z plane at x = 0) is
// extruded along x. One nominal element size h = H / N for every type:
//   Hex = 1:    transfinite N x N section, recombined, extruded in L/h layers -> 8-node hexahedra
//   Prism = 1:  section triangulated (size h), extruded in L/h recombined layers -> 6-node prisms
//   otherwise:  unstructured tetrahedra of characteristic length h; Degree = 2 -> 10-node tetrahedra
// (Degree applies to the tetrahedra only: second-order hexahedra and prisms are 27/18-node
// elements, which tribos refuses.)
// Regenerate the committed meshes (from input/meshes, gmsh 4.8.4; the .msh files are not kept):
//   gmsh -3 -format msh41 -setnumber Hex 1 -setnumber N 4 cantilever.geo -o cantilever_hex8.msh
//   ../../build/bin/tribos-msh2exo cantilever_hex8.msh cantilever_hex8.exo
//   gmsh -3 -format msh41 -setnumber Degree 2 -setnumber N 4 cantilever.geo -o cantilever_tet10.msh
//   ../../build/bin/tribos-msh2exo cantilever_tet10.msh cantilever_tet10.exo
//   gmsh -3 -format msh41 -setnumber Degree 1 -setnumber N 4 cantilever.geo -o cantilever_tet4.msh
//   ../../build/bin/tribos-msh2exo cantilever_tet4.msh cantilever_tet4.exo
//   gmsh -3 -format msh41 -setnumber Prism 1 -setnumber N 4 cantilever.geo -o cantilever_wedge6.msh
//   ../../build/bin/tribos-msh2exo cantilever_wedge6.msh cantilever_wedge6.exo
DefineConstant[
  L = {10.0, Name "Parameters/L (length)"},
  H = {1.0, Name "Parameters/H (side of the square section)"},
  N = {2, Name "Parameters/N (elements through the depth: h = H / N)"},
  Hex = {0, Choices {0, 1}, Name "Parameters/Hex (1: 8-node hexahedra)"},
  Prism = {0, Choices {0, 1}, Name "Parameters/Prism (1: 6-node prisms)"},
  Degree = {1, Choices {1, 2}, Name "Parameters/Degree (tetrahedra: 1 -> 4 nodes, 2 -> 10 nodes)"}
];
h = H / N;
layers = Round(L / h);

Point(1) = {0, 0, 0, h};
Point(2) = {0, H, 0, h};
Point(3) = {0, H, H, h};
Point(4) = {0, 0, H, h};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};

If (Hex)
  Transfinite Curve{1, 2, 3, 4} = N + 1;
  Transfinite Surface{1};
  Recombine Surface{1};
  out[] = Extrude {L, 0, 0} { Surface{1}; Layers{layers}; Recombine; };
ElseIf (Prism)
  out[] = Extrude {L, 0, 0} { Surface{1}; Layers{layers}; Recombine; };
Else
  out[] = Extrude {L, 0, 0} { Surface{1}; };
  Mesh.ElementOrder = Degree;
EndIf

// out[0]: the face at x = L, out[1]: the volume, out[2..5]: the lateral faces
Physical Volume("beam") = {out[1]};
Physical Surface("clamped") = {1};
Physical Surface("tip") = {out[0]};
