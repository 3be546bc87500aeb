// Rigid straight pipe (fluid only), axis along z from z = 0 to z = L.  SI units [m].
// Parameters (override with gmsh -setnumber NAME VALUE or the scene's -mesh_h):
//   R pipe radius, L pipe length, h target element size.
SetFactory("OpenCASCADE");
If (!Exists(R)) R = 0.005; EndIf
If (!Exists(L)) L = 0.02; EndIf
If (!Exists(h)) h = 0.001; EndIf
Cylinder(1) = {0, 0, 0, 0, 0, L, R};
Mesh.CharacteristicLengthMin = h;
Mesh.CharacteristicLengthMax = h;
Mesh.Optimize = 1;
eps = 1e-6 * L;
Physical Volume("fluid", 1) = {1};
Physical Surface("inlet", 11) = Surface In BoundingBox{-2*R, -2*R, -eps, 2*R, 2*R, eps};
Physical Surface("outlet", 12) = Surface In BoundingBox{-2*R, -2*R, L - eps, 2*R, 2*R, L + eps};
Physical Surface("wall", 13) = Surface In BoundingBox{-2*R, -2*R, eps, 2*R, 2*R, L - eps};
