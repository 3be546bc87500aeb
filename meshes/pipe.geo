// Rigid straight pipe (fluid only), axis along z from z = 0 to z = L.  SI units [m].
// Parameters (override with gmsh -setnumber NAME VALUE or the scene's -mesh_h):
//   R pipe radius, L pipe length, h target element size.
SetFactory("OpenCASCADE");
If (!Exists(R)) R = 0.005; EndIf
If (!Exists(L)) L = 0.02; EndIf
If (!Exists(h)) h = 0.001; EndIf
Cylinder(1) = {0, 0, 0, 0, 0, L, R};
Mesh.CharacteristicLengthMin = 0;
Mesh.CharacteristicLengthMax = h;
// Elements per 2 pi along curved boundaries (0: off).  Straight-sided tetrahedra inscribe the
// circle: flux ~ R^4 loses ~ (2 pi / n)^2 / 1.5 of its value, so resolve the circumference.
If (!Exists(ncirc)) ncirc = 0; EndIf
Mesh.MeshSizeFromCurvature = ncirc;
Mesh.Optimize = 1;
eps = 1e-3 * R; // selection tolerance [m]
Physical Volume("fluid", 1) = {1};
in() = Surface In BoundingBox{-2*R, -2*R, -eps, 2*R, 2*R, eps};
out() = Surface In BoundingBox{-2*R, -2*R, L - eps, 2*R, 2*R, L + eps};
wall() = Surface{:};
wall() -= in();
wall() -= out();
Physical Surface("inlet", 11) = in();
Physical Surface("outlet", 12) = out();
Physical Surface("wall", 13) = wall();
