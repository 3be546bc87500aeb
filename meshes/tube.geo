// Flexible tube (paper section 3.1): fluid cylinder inside a conforming solid annulus, axis along z.
// SI units [m].  R inner radius, T wall thickness, L length, h element size.
SetFactory("OpenCASCADE");
If (!Exists(R)) R = 0.005; EndIf
If (!Exists(T)) T = 0.001; EndIf
If (!Exists(L)) L = 0.05; EndIf
If (!Exists(h)) h = 0.001; EndIf
Cylinder(1) = {0, 0, 0, 0, 0, L, R};
Cylinder(2) = {0, 0, 0, 0, 0, L, R + T};
BooleanFragments{ Volume{2}; Delete; }{ Volume{1}; Delete; }
Mesh.CharacteristicLengthMin = 0;
Mesh.CharacteristicLengthMax = h;
// Elements per 2 pi along curved boundaries (0: off).  Straight-sided tetrahedra inscribe the
// circle: flux ~ R^4 loses ~ (2 pi / n)^2 / 1.5 of its value, so resolve the circumference.
If (!Exists(ncirc)) ncirc = 0; EndIf
Mesh.MeshSizeFromCurvature = ncirc;
Mesh.Optimize = 1;
eps = 1e-2 * T; // selection tolerance [m], well below the wall thickness
Ro = R + T;
fl() = Volume In BoundingBox{-R - eps, -R - eps, -eps, R + eps, R + eps, L + eps};
so() = Volume{:};
so() -= fl();
Physical Volume("fluid", 1) = fl();
Physical Volume("solid", 2) = so();
Physical Surface("inlet", 11) = Surface In BoundingBox{-R - eps, -R - eps, -eps, R + eps, R + eps, eps};
Physical Surface("outlet", 12) = Surface In BoundingBox{-R - eps, -R - eps, L - eps, R + eps, R + eps, L + eps};
iface() = Surface In BoundingBox{-R - eps, -R - eps, -eps, R + eps, R + eps, L + eps};
iface() -= Surface In BoundingBox{-R - eps, -R - eps, -eps, R + eps, R + eps, eps};
iface() -= Surface In BoundingBox{-R - eps, -R - eps, L - eps, R + eps, R + eps, L + eps};
Physical Surface("interface", 13) = iface();
ends() = Surface In BoundingBox{-Ro - eps, -Ro - eps, -eps, Ro + eps, Ro + eps, eps};
ends() += Surface In BoundingBox{-Ro - eps, -Ro - eps, L - eps, Ro + eps, Ro + eps, L + eps};
ends() -= Surface In BoundingBox{-R - eps, -R - eps, -eps, R + eps, R + eps, eps};
ends() -= Surface In BoundingBox{-R - eps, -R - eps, L - eps, R + eps, R + eps, L + eps};
Physical Surface("wall_ends", 14) = ends();
outer() = Surface{:};
outer() -= ends();
outer() -= iface();
outer() -= Surface In BoundingBox{-R - eps, -R - eps, -eps, R + eps, R + eps, eps};
outer() -= Surface In BoundingBox{-R - eps, -R - eps, L - eps, R + eps, R + eps, L + eps};
Physical Surface("outer", 15) = outer();
