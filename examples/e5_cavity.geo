// E5 cavity (issue 11, seed 000 experiment E5): the PEC box [0,1]x[0,0.8]x[0,0.6] meshed with
// tetrahedra refined near the walls: size h_wall at the walls growing linearly to h_core at
// distance d_grow. Regenerate with scripts/e5_mesh.sh (gmsh -3 -format msh22).
SetFactory("OpenCASCADE");
h_wall = 0.05;
h_core = 0.12;
d_grow = 0.2;
Box(1) = {0, 0, 0, 1, 0.8, 0.6};
Field[1] = Distance;
Field[1].SurfacesList = {1, 2, 3, 4, 5, 6};
Field[2] = Threshold;
Field[2].InField = 1;
Field[2].SizeMin = h_wall;
Field[2].SizeMax = h_core;
Field[2].DistMin = 0.0;
Field[2].DistMax = d_grow;
Background Field = 2;
Mesh.MeshSizeExtendFromBoundary = 0;
Mesh.MeshSizeFromPoints = 0;
Mesh.MeshSizeFromCurvature = 0;
// Delaunay throughout and no optimisation: the tetrahedralisation stays Delaunay, so the
// circumcentric (Voronoi) dual has positive ⋆_ε on every interior edge and ⋆_ν on every interior
// face and the diagonal star and the AVI run on it. Gmsh's optimisers (edge swaps, smoothing,
// Netgen) break the Delaunay property: with Mesh.Optimize = 1 the same mesh had 125 interior
// edges and 275 faces with non-positive stars.
Mesh.Algorithm = 5;
Mesh.Algorithm3D = 10;
Mesh.Optimize = 0;
Mesh.OptimizeNetgen = 0;
Mesh.Smoothing = 0;
Mesh.RandomSeed = 1;
Physical Volume("cavity") = {1};
