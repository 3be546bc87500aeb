// Box [-1,1]^3 for manufactured / exact solutions.  Lengths [m]; h = target element size.
// Unstructured on purpose: a structured split of the cube leaves corner tetrahedra with all
// vertices on the boundary, which gives P2-P1 (Taylor-Hood) spurious pressure modes.
SetFactory("OpenCASCADE");
If (!Exists(h)) h = 0.5; EndIf
Box(1) = {-1, -1, -1, 2, 2, 2};
Mesh.CharacteristicLengthMin = h;
Mesh.CharacteristicLengthMax = h;
Mesh.Optimize = 1;
Physical Volume("fluid", 1) = {1};
Physical Surface("boundary", 10) = Surface{:};
