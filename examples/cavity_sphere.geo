// PEC sphere cavity (issue 11, "3-D PEC cavity"): radius 0.5, tetrahedra of size h (uniform).
// Regenerate the three levels with scripts/cavity_sphere_mesh.sh. Delaunay surface (5) and HXT
// volume (10) meshing, on one thread so the output is reproducible; Gmsh's optimisation on:
// the sphere meshes are not well-centred either way (with Optimize = 0 the diagonal star still
// has a few non-positive entries near the wall, and slivers cut its CFL step 5x), and the
// optimised tetrahedra give the Whitney star the smaller errors (docs/maxwell-mesh.md).
SetFactory("OpenCASCADE");
DefineConstant[ h = {0.1, Name "h"} ];
Sphere(1) = {0, 0, 0, 0.5};
General.NumThreads = 1;
Mesh.MeshSizeMin = h;
Mesh.MeshSizeMax = h;
Mesh.MeshSizeFromCurvature = 0;
Mesh.Algorithm = 5;
Mesh.Algorithm3D = 10;
Mesh.Optimize = 1;
Mesh.OptimizeNetgen = 0;
Mesh.Smoothing = 0;
