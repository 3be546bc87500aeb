// Two leaflet-like plates facing each other across a gap, clamped at their base, for contact
// tests.  Lengths [m]: plates t thick, hp high, w wide (y), centred on x = W/2 with gap g between
// them, standing on z = 0; with fluid = 1 they stand in a fluid box [0, W] x [0, D] x [0, H]
// whose floor opens, between the plates, into a drain channel (g x w, depth dr): fluid that
// enters at the top and leaves through the drain flows down the gap, like blood through a valve
// that closes: the pressure outside the plates exceeds the pressure in the gap.
// Groups: volumes plates (and fluid); surfaces base (the plates' feet, clamped), outer (the faces
// that look away from the gap), interface (every plate face but the base), and with the fluid:
// inlet (z = H), outlet (the drain's end, z = -dr), walls (the rest).  With wr > 0 the box's face
// x = 0 is replaced by a cylinder of radius wr, axis along z at (wr, D/2): a concave wall that
// gmsh facets, for the rigid-wall contact's facet kinks (it touches x = 0 at y = D/2 only).
SetFactory("OpenCASCADE");
If (!Exists(h)) h = 0.001; EndIf
If (!Exists(t)) t = 0.001; EndIf
If (!Exists(hp)) hp = 0.01; EndIf
If (!Exists(w)) w = 0.006; EndIf
If (!Exists(g)) g = 0.002; EndIf
If (!Exists(W)) W = 0.014; EndIf
If (!Exists(D)) D = 0.008; EndIf
If (!Exists(H)) H = 0.016; EndIf
If (!Exists(fluid)) fluid = 1; EndIf
If (!Exists(dr)) dr = 0.004; EndIf
If (!Exists(wr)) wr = 0; EndIf
// plate b shifted by sy in y and meshed hb times finer: meshes that do not mirror each other
If (!Exists(sy)) sy = 0; EndIf
If (!Exists(hb)) hb = 1; EndIf
xa = W / 2 - g / 2 - t;
xb = W / 2 + g / 2;
y0 = (D - w) / 2;
Box(1) = {xa, y0, 0, t, w, hp};
Box(2) = {xb, y0 + sy, 0, t, w, hp};
e = 1e-4 * W;
If (fluid)
  If (wr > 0) // the box reaches past x = 0 so that no face is tangent to the cylinder
    Box(3) = {-W, 0, 0, 2 * W, D, H};
    Cylinder(5) = {wr, D / 2, -H, 0, 0, 3 * H, wr};
    v3 = BooleanIntersection{ Volume{3}; Delete; }{ Volume{5}; Delete; };
  Else
    Box(3) = {0, 0, 0, W, D, H};
    v3 = 3;
  EndIf
  Box(4) = {xa + t, y0, -dr, g, w, dr};
  v() = BooleanFragments{ Volume{v3, 4}; Delete; }{ Volume{1, 2}; Delete; };
EndIf
pl() = Volume In BoundingBox{xa - e, y0 - e, -e, xb + t + e, y0 + sy + w + e, hp + e};
Physical Volume("plates", 2) = {pl()};
ps() = Boundary{ Volume{pl()}; };
base() = Surface In BoundingBox{xa - e, y0 - e, -e, xb + t + e, y0 + sy + w + e, e};
outa() = Surface In BoundingBox{xa - e, y0 - e, -e, xa + e, y0 + w + e, hp + e};
outb() = Surface In BoundingBox{xb + t - e, y0 + sy - e, -e, xb + t + e, y0 + sy + w + e, hp + e};
Physical Surface("base", 21) = {base()};
Physical Surface("outer", 22) = {outa(), outb()};
wet() = ps();
wet() -= base();
Physical Surface("interface", 23) = {wet()};
If (fluid)
  all() = Volume{:};
  fl() = all();
  fl() -= pl();
  Physical Volume("fluid", 1) = {fl()};
  inl() = Surface In BoundingBox{-e, -e, H - e, W + e, D + e, H + e};
  Physical Surface("inlet", 11) = {inl()};
  out() = Surface In BoundingBox{-e, -e, -dr - e, W + e, D + e, -dr + e};
  Physical Surface("outlet", 12) = {out()};
  ext() = Boundary{ Volume{fl()}; };
  ext() -= wet();
  ext() -= inl();
  ext() -= out();
  Physical Surface("walls", 13) = {ext()};
EndIf
Characteristic Length{ PointsOf{ Volume{:}; } } = h;
If (hb != 1)
  pb() = Volume In BoundingBox{xb - e, y0 + sy - e, -e, xb + t + e, y0 + sy + w + e, hp + e};
  Characteristic Length{ PointsOf{ Volume{pb()}; } } = hb * h;
EndIf
Mesh.CharacteristicLengthMin = 0;
Mesh.CharacteristicLengthMax = h;
Mesh.Optimize = 1;
