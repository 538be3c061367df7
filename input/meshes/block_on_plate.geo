// An aluminium plate (30 x 20 x 5) under a steel block of the same footprint (height 5),
// meshed by gmsh as one conforming mesh; `tribos-msh2exo --split-bodies` gives each body its
// own nodes on the interface, so the contact pairs are node-to-node. Physical groups become
// element blocks ("plate", "block") and side sets + node sets ("plate_bottom" clamped,
// "interface" -> "interface_plate" (slave) and "interface_block" (master), "block_top" loaded).
// Regenerate: gmsh -3 -format msh41 block_on_plate.geo -o block_on_plate.msh
h = 3.0;
Point(1) = {0, 0, 0, h}; Point(2) = {30, 0, 0, h}; Point(3) = {30, 20, 0, h}; Point(4) = {0, 20, 0, h};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4}; Plane Surface(1) = {1};
plate[] = Extrude {0, 0, 5} { Surface{1}; };
block[] = Extrude {0, 0, 5} { Surface{plate[0]}; };
Physical Volume("plate", 1) = {plate[1]};
Physical Volume("block", 2) = {block[1]};
Physical Surface("plate_bottom", 1) = {1};
Physical Surface("interface", 2) = {plate[0]};
Physical Surface("block_top", 3) = {block[0]};
