// Unit cube, tetrahedra (used by the mesh reader tests).
SetFactory("OpenCASCADE");
Box(1) = {0, 0, 0, 1, 1, 1};
Mesh.CharacteristicLengthMax = 0.4;
Physical Volume("solid", 3) = {1};
Physical Surface("skin", 4) = {1, 2, 3, 4, 5, 6};
