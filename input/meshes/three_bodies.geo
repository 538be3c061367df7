// Three bodies on two contact interfaces (issue 30): a steel punch with rounded bottom edges
// (fillet radius r) pressed onto an aluminium block that rests on a steel foundation. Each
// body is meshed on its own (OpenCASCADE volumes that share no entity), so no interface
// matches and every body has its own nodes: convert without --split-bodies.
// Physical groups: volumes "punch", "block", "foundation" (element blocks); surfaces
// "punch_bottom" (the flat face and the fillets), "punch_top", "block_top", "block_bottom",
// "foundation_top", "foundation_bottom" (side sets + node sets).
// Regenerate (gmsh 4.8.4 from Debian 12), from input/meshes:
//   gmsh -3 -format msh41 three_bodies.geo -o three_bodies.msh
//   ../../build/bin/tribos-msh2exo three_bodies.msh three_bodies.exo
SetFactory("OpenCASCADE");
r = 2.0;          // fillet radius of the punch's bottom edges
hPunch = 1.0;     // element sizes: the block (slave of both interfaces) is the softer body
hBlock = 1.5;
hFoundation = 3.0;
Box(1) = {-30, -20, -10, 60, 40, 10};   // foundation
Box(2) = {-15, -10, 0, 30, 20, 10};     // block
Box(3) = {-5, -5, 10, 10, 10, 10};      // punch
// The four bottom edges of the punch (at z = 10), rounded.
bottomEdges() = Curve In BoundingBox{-5.1, -5.1, 9.9, 5.1, 5.1, 10.1};
filleted() = Fillet{3}{bottomEdges()}{r};  // the rounded punch replaces volume 3
punch = filleted(0);
// Surfaces by position.
foundationTop() = Surface In BoundingBox{-30.1, -20.1, -0.1, 30.1, 20.1, 0.1};
foundationBottom() = Surface In BoundingBox{-30.1, -20.1, -10.1, 30.1, 20.1, -9.9};
blockBottom() = Surface In BoundingBox{-15.1, -10.1, -0.1, 15.1, 10.1, 0.1};
blockTop() = Surface In BoundingBox{-15.1, -10.1, 9.9, 15.1, 10.1, 10.1};
punchTop() = Surface In BoundingBox{-5.1, -5.1, 19.9, 5.1, 5.1, 20.1};
punchBottom() = Surface In BoundingBox{-5.1, -5.1, 9.9, 5.1, 5.1, 10 + r + 0.01};
// A box holds the faces of another body that lie in it too: keep each body's own.
foundationTop() -= Abs(Boundary{Volume{2};});
blockTop() -= Abs(Boundary{Volume{punch};});
MeshSize{PointsOf{Volume{1};}} = hFoundation;
MeshSize{PointsOf{Volume{2};}} = hBlock;
MeshSize{PointsOf{Volume{punch};}} = hPunch;
Physical Volume("foundation", 1) = {1};
Physical Volume("block", 2) = {2};
Physical Volume("punch", 3) = {punch};
Physical Surface("foundation_bottom", 1) = {foundationBottom()};
Physical Surface("foundation_top", 2) = {foundationTop()};
Physical Surface("block_bottom", 3) = {blockBottom()};
Physical Surface("block_top", 4) = {blockTop()};
Physical Surface("punch_bottom", 5) = {punchBottom()};
Physical Surface("punch_top", 6) = {punchTop()};
