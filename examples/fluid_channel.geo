// Seed 004 B14 channel for Gmsh: L = 2 pi, H = 1, mean edge about 3e-2 (the seed's 2.989e-2).
// gmsh -2 -format msh22 fluid_channel.geo -o fluid_channel.msh
// The fluid solver reads the physical curves below by name (examples/fluid_channel.json) and
// needs an acute (well-centred) mesh: Frontal-Delaunay with a uniform size gives mostly acute
// triangles; the solver refuses a mesh with non-positive Hodge stars and says how many.
h = 0.03;
L = 2 * Pi;
Point(1) = {0, 0, 0, h};
Point(2) = {L, 0, 0, h};
Point(3) = {L, 1, 0, h};
Point(4) = {0, 1, 0, h};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Physical Curve("bottom") = {1};
Physical Curve("right") = {2};
Physical Curve("top") = {3};
Physical Curve("left") = {4};
Physical Surface("fluid") = {1};
Mesh.Algorithm = 6;
