// A solid block in a fluid-filled box, for remeshing tests: the block is translated by a
// prescribed displacement far beyond what smoothing the fluid mesh survives.  Lengths [m]:
// box [0, L] x [0, W] x [0, W], block of side b centred at (xb, W/2, W/2); h = cell size.
// Groups: volumes fluid, block; surfaces inlet (x = 0), walls (the sides), outlet (x = L),
// interface (the block's faces).
SetFactory("OpenCASCADE");
If (!Exists(h)) h = 0.002; EndIf
If (!Exists(L)) L = 0.03; EndIf
If (!Exists(W)) W = 0.01; EndIf
If (!Exists(b)) b = 0.004; EndIf
If (!Exists(xb)) xb = 0.008; EndIf
Box(1) = {0, 0, 0, L, W, W};
Box(2) = {xb - b / 2, (W - b) / 2, (W - b) / 2, b, b, b};
v() = BooleanFragments{ Volume{1}; Delete; }{ Volume{2}; Delete; };
e = 1e-3 * L;
blk() = Volume In BoundingBox{xb - b / 2 - e, (W - b) / 2 - e, (W - b) / 2 - e, xb + b / 2 + e, (W + b) / 2 + e, (W + b) / 2 + e};
all() = Volume{:};
fl() = all();
fl() -= blk();
Physical Volume("fluid", 1) = {fl()};
Physical Volume("block", 2) = {blk()};
bs() = Boundary{ Volume{blk()}; };
Physical Surface("interface", 11) = {bs()};
Physical Surface("outlet", 12) = Surface In BoundingBox{L - e, -e, -e, L + e, W + e, W + e};
out() = Surface In BoundingBox{L - e, -e, -e, L + e, W + e, W + e};
Physical Surface("inlet", 14) = Surface In BoundingBox{-e, -e, -e, e, W + e, W + e};
inl() = Surface In BoundingBox{-e, -e, -e, e, W + e, W + e};
ext() = Boundary{ Volume{fl()}; };
ext() -= bs();
ext() -= out();
ext() -= inl();
Physical Surface("walls", 13) = {ext()};
Mesh.CharacteristicLengthMin = 0;
Mesh.CharacteristicLengthMax = h;
Mesh.Optimize = 1;
