// PEC cylinder cavity (issue 11, "3-D PEC cavity"): radius 0.5, height 0.6, tetrahedra of
// size h (uniform). Regenerate the three levels with scripts/cavity_cylinder_mesh.sh.
SetFactory("OpenCASCADE");
DefineConstant[ h = {0.1, Name "h"} ];
Cylinder(1) = {0, 0, 0, 0, 0, 0.6, 0.5};
Mesh.MeshSizeMin = h;
Mesh.MeshSizeMax = h;
Mesh.MeshSizeFromCurvature = 0;
Mesh.Optimize = 1;
