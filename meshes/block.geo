// Rectangular solid block [x0, x0+lx] x [y0, y0+ly] x [z0, z0+lz] for solid verification and the
// bar benchmarks.  Lengths [m]; h = target element size.  Groups: volume "solid", faces xmin,
// xmax, ymin, ymax, zmin, zmax (a face in two physical groups would reach only one label).
SetFactory("OpenCASCADE");
If (!Exists(h)) h = 0.25; EndIf
If (!Exists(x0)) x0 = 0; EndIf
If (!Exists(y0)) y0 = 0; EndIf
If (!Exists(z0)) z0 = 0; EndIf
If (!Exists(lx)) lx = 1; EndIf
If (!Exists(ly)) ly = 1; EndIf
If (!Exists(lz)) lz = 1; EndIf
Box(1) = {x0, y0, z0, lx, ly, lz};
e = 1e-2 * (lx + ly + lz) / 3; // selection margin (OCC bounding boxes carry a tolerance)
Physical Volume("solid", 1) = {1};
Physical Surface("xmin", 11) = Surface In BoundingBox{x0 - e, y0 - e, z0 - e, x0 + e, y0 + ly + e, z0 + lz + e};
Physical Surface("xmax", 12) = Surface In BoundingBox{x0 + lx - e, y0 - e, z0 - e, x0 + lx + e, y0 + ly + e, z0 + lz + e};
Physical Surface("ymin", 13) = Surface In BoundingBox{x0 - e, y0 - e, z0 - e, x0 + lx + e, y0 + e, z0 + lz + e};
Physical Surface("ymax", 14) = Surface In BoundingBox{x0 - e, y0 + ly - e, z0 - e, x0 + lx + e, y0 + ly + e, z0 + lz + e};
Physical Surface("zmin", 15) = Surface In BoundingBox{x0 - e, y0 - e, z0 - e, x0 + lx + e, y0 + ly + e, z0 + e};
Physical Surface("zmax", 16) = Surface In BoundingBox{x0 - e, y0 - e, z0 + lz - e, x0 + lx + e, y0 + ly + e, z0 + lz + e};
Mesh.CharacteristicLengthMin = 0;
Mesh.CharacteristicLengthMax = h;
Mesh.Optimize = 1;
