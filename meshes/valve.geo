// Aortic valve (paper section 3.2): a rigid aortic root with three thin solid leaflets.
// SI units [m].  Axis along z, blood flows towards +z; the annulus (leaflet base) is at z = 0.
// Every size is a parameter (override with gmsh -setnumber NAME VALUE or the scene's
// -mesh_params NAME=VALUE; -mesh_h sets h):
//   Ra       annulus = root radius (Labrosse 2006: 12.5-13 mm)
//   Lin      inlet extension upstream of the annulus (LVOT)
//   Lout     outlet extension downstream of the commissures (ascending aorta)
//   t        leaflet thickness (0.4-0.5 mm)
//   rho_l    radius of the leaflet's spherical mid-surface, centred on the root wall at the
//            commissure height: > Ra so that the leaflet reaches the axis; rho_l - Ra sets
//            how far below the commissures the free edges meet the axis
//   stretch  vertical stretch of that sphere (leaflet height = stretch * rho_l)
//   gap      gap between neighbouring free edges in this reference (nearly closed) shape
//   rcenter  radius of a central hole the three leaflets end on (default 0: their corners meet
//            with the gap between them): a column of fluid at the valve's centre that the axis
//            rod of the contact (-contact_axis_radius < rcenter) keeps open and the gap seal closes
//   sinus    1: three Valsalva sinus bulges behind the leaflets; 0: a straight tube
//   sdepth   how far the sinus bulges reach out of the tube; swidth their half-width
//   h        element size on and near the leaflets; hfar far from them (default 4 h);
//   hgrow    distance over which the size grows from h to hfar
//   tlayers  solid elements through the thickness wanted (1 or 2; sizes the leaflet mesh)
//   hbase    element size along the leaflets' attachment to the root (default: h, no band),
//            where the opening leaflet bends most: at h = 1.5 mm the thin elements there
//            invert when the valve is half open; hbasew the width of that band (default 2 mm)
//   coapt    coaptation height: each leaflet's free edge carries a band of this height
//            (default 0: none) standing up into the aortic side along its dividing plane, flush
//            with the free edge, so that the closed valve's neighbouring bands face each other
//            across the gap and the aortic pressure presses them together (a lunula) instead
//            of pushing the nearly horizontal free edges down into the ventricle; with shape=1
//            the height of the strip leaflet's coaptation strip
//   post     radial depth of three commissural posts (default 0: none): rigid wall strips
//            filling the gap between neighbouring leaflets within this distance of the root
//            wall, from the annulus to the commissure height (the interleaflet triangles and
//            commissures of a real root), so that the leaflets' free edges are attached there
//            and the clamped edges leave no slit along the wall for a closed valve to leak by
//   hcenter  element size within hcenterw of the axis from the annulus to the commissures
//            (default: h, no refinement), where the three free edges meet when the valve closes
//   shape    0: ellipsoid leaflets (below); 1: strip leaflets, the closed native valve's shape:
//            each leaflet a cup whose free edge runs level at zc - edrop from its commissure to
//            the axis, with a coaptation strip of height coapt (over a width coaptw) rising steeply
//            to it along the gap plane, so that the aortic pressure presses neighbouring strips
//            together and opening bends them across their thickness (no band, no posts)
//   gapw     (shape 1) the gap between neighbouring leaflets' mid-surfaces where they meet the
//            wall at a commissure: it narrows from gap over the last gapwl before the wall, to a
//            slit the gap seal holds shut at rest (gapw - t below -gap_seal_gap_closed) and that
//            contact leaves alone (gapw - t above -contact_offset)
//   nsec, nj (shape 1) sections lofted per leaflet and points per section (12 x 16: the loft
//            takes ~20 s; 36 x 40 ~5 min)
// Leaflet k (k = 0, 1, 2, centre angle 90 + 120 k degrees) is the shell of thickness t about an
// ellipsoid (semi-axes rho_l, rho_l, stretch rho_l) centred on the wall at the commissure
// height, cut to its own 120-degree sector (less gap/2 from each dividing plane), to the lower
// half and to the tube.  It meets the wall along a curve that rises from the leaflet base
// (z = 0) to the commissures; the three free edges meet near the axis with a gap.
SetFactory("OpenCASCADE");
If (!Exists(Ra)) Ra = 0.0125; EndIf
If (!Exists(Lin)) Lin = 0.015; EndIf
If (!Exists(Lout)) Lout = 0.05; EndIf
If (!Exists(t)) t = 0.00045; EndIf
If (!Exists(rho_l)) rho_l = 0.0135; EndIf
If (!Exists(stretch)) stretch = 1.25; EndIf
If (!Exists(gap)) gap = 0.0008; EndIf
If (!Exists(rcenter)) rcenter = 0; EndIf
If (!Exists(sinus)) sinus = 1; EndIf
If (!Exists(sdepth)) sdepth = 0.004; EndIf
If (!Exists(swidth)) swidth = 0.009; EndIf
If (!Exists(sheight)) sheight = 0.75; EndIf
If (!Exists(h)) h = 0.001; EndIf
If (!Exists(hfar)) hfar = 4 * h; EndIf
If (!Exists(hgrow)) hgrow = 0.008; EndIf
If (!Exists(tlayers)) tlayers = 1; EndIf
If (!Exists(hbasew)) hbasew = 0.002; EndIf
If (!Exists(coapt)) coapt = 0; EndIf
If (!Exists(post)) post = 0; EndIf
If (!Exists(shape)) shape = 0; EndIf
If (!Exists(coaptw)) coaptw = 0.0015; EndIf
If (!Exists(edrop)) edrop = 0.0005; EndIf
If (!Exists(nsec)) nsec = 12; EndIf
If (!Exists(nj)) nj = 16; EndIf
If (!Exists(gapw)) gapw = gap; EndIf
If (!Exists(gapwl)) gapwl = 0.004; EndIf
If (post < 0)
  Error("valve.geo: post (the commissural posts' depth) must be >= 0");
EndIf
If (shape != 0 && shape != 1)
  Error("valve.geo: shape must be 0 (ellipsoid leaflets) or 1 (strip leaflets)");
EndIf
If (shape == 1)
  If (coapt <= 0 || coapt >= stretch * rho_l / 2 || coaptw <= 0)
    Error("valve.geo: shape=1 needs a coaptation strip: coapt in (0, half the commissure height) and coaptw > 0, e.g. coapt=0.004,coaptw=0.0015");
  EndIf
  If (gapw > gap || gapw - t < 0.0003 || gap - t < 0.0003)
    Error("valve.geo: shape=1 needs t + 0.3 mm < gapw <= gap (the fluid slit between neighbouring strips, at the wall and elsewhere); e.g. gap=0.002,gapw=0.00108");
  EndIf
  If (edrop < 0 || edrop >= coapt)
    Error("valve.geo: edrop (how far the free edge lies below the commissure height) must lie in [0, coapt)");
  EndIf
  If (post > 0)
    Error("valve.geo: shape=1 has no commissural posts (post=0): its strips meet the wall gapw apart instead");
  EndIf
EndIf
// Shapes whose leaflets would intersect each other or miss the axis.
If (gap <= 0 || gap >= Ra / 4)
  Error("valve.geo: gap (between neighbouring free edges) must lie in (0, Ra/4): at 0 the leaflets intersect; e.g. gap=0.002");
EndIf
If (rho_l <= Ra)
  Error("valve.geo: rho_l (the leaflet ellipsoid's radius) must exceed Ra, or the leaflets do not reach the axis");
EndIf
If (rcenter >= Ra / 2 || post >= Ra / 2)
  Error("valve.geo: rcenter and post must be below Ra/2, or the leaflets lose most of their free edge");
EndIf
If (coapt < 0)
  Error("valve.geo: coapt (the coaptation height) must be >= 0");
EndIf
// (gmsh's parser evaluates both sides of || and &&, so hbase is tested in its own If)
If (h <= 0 || hbasew <= 0)
  Error("valve.geo: the sizes h, hbase and hbasew must be positive");
EndIf
If (Exists(hbase))
  If (hbase <= 0)
    Error("valve.geo: the sizes h, hbase and hbasew must be positive");
  EndIf
EndIf
If (rcenter < 0)
  Error("valve.geo: rcenter (the central hole's radius) must be >= 0");
EndIf
If (Exists(hcenter))
  If (hcenter <= 0)
    Error("valve.geo: hcenter (the element size about the axis) must be positive");
  EndIf
EndIf
If (Exists(hcenterw))
  If (hcenterw <= 0)
    Error("valve.geo: hcenterw (the width of the refinement about the axis) must be positive");
  EndIf
EndIf

zc = stretch * rho_l;         // commissure height: the ellipsoids' centre height
Ltot = Lin + zc + Lout;
big = 4 * Ra;

// Fluid: the tube and the sinus bulges.
Cylinder(1) = {0, 0, -Lin, 0, 0, Ltot, Ra};
// OpenCASCADE's cylinders have a seam line at angle 0: turn it to a commissure (30 degrees),
// where it crosses no leaflet attachment (a seam through an attachment leaves slivers there).
Rotate {{0, 0, 1}, {0, 0, 0}, Pi / 6} { Volume{1}; }
fluid() = {1};
If (sinus)
  // Each bulge: an ellipsoid (sdepth radially, swidth along the wall, 0.9 zc vertically)
  // centred on the wall at the commissure height, inside its leaflet's inner ellipsoid so that it
  // never reaches the leaflet's attachment curve.
  For k In {0:2}
    th = Pi / 2 + 2 * Pi * k / 3;
    Sphere(10 + k) = {0, 0, 0, 1};
    Dilate {{0, 0, 0}, {sdepth, swidth, sheight * zc}} { Volume{10 + k}; }
    Translate {Ra, 0, zc} { Volume{10 + k}; }
    Rotate {{0, 0, 1}, {0, 0, 0}, th} { Volume{10 + k}; }
  EndFor
  fluid() = BooleanUnion{ Volume{1}; Delete; }{ Volume{10, 11, 12}; Delete; };
EndIf
If (post > 0)
  // Post k: the gap strip about the dividing plane at 30 + 120 k degrees, within post of the
  // wall (and beyond it, through the sinus-free wall there), from the annulus to zc.
  For k In {0:2}
    Box(15 + k) = {-gap / 2, Ra - post, 0, gap, post + Ra, zc};
    Rotate {{0, 0, 1}, {0, 0, 0}, -Pi / 3 + 2 * Pi * k / 3} { Volume{15 + k}; }
  EndFor
  fluid() = BooleanDifference{ Volume{fluid()}; Delete; }{ Volume{15, 16, 17}; Delete; };
EndIf

// Leaflets.
leaf() = {};
If (shape == 1)
  // The strip leaflet's mid-surface z(x, y) in the leaflet's own frame (x from the axis towards
  // its sinus, y along the wall): the height of a point follows its distance d from the nearer
  // gap plane (a smooth minimum, so that the leaflet has no crease along its middle).  Within
  // coaptw of the plane the surface rises steeply by coapt to the level free edge at zc - edrop
  // (S, the coaptation strip); below it the belly falls to the nadir as the cup 1 - (1 - u)^2
  // (P, u = d / its value at the nadir).
  sn = Sin(Pi / 3);
  cs = Cos(Pi / 3);
  kS = 0.0007;  // smoothing of the minimum for the strip [m]: it rounds the leaflet's tip
  kB = 0.0006;  // and for the belly: a curvature radius ~1 mm on the leaflet's middle line
  zfe = zc - edrop;
  // u reaches 0.8 at the nadir, so that the cup still falls where it meets the wall (at its
  // bottom, u = 1, the leaflet would meet the wall tangentially, in slivers); its depth bA puts the
  // nadir at z = 0
  dBmax = (Ra * sn - gapw / 2 - kB * Log(2)) / 0.8;
  bA = (zfe - coapt) / (2 * 0.8 - 0.8^2);
  Macro StripLeafletZ
    // in: xq, yq [m]; out: zq [m]
    // the gap narrows to gapw over the last gapwl before the wall (smoothstep)
    _s = Min(Max((Sqrt(xq^2 + yq^2) - Ra + gapwl) / gapwl, 0), 1);
    _g = gap - (gap - gapw) * (3 * _s^2 - 2 * _s^3);
    _d1 = xq * sn - yq * cs - _g / 2;
    _d2 = xq * sn + yq * cs - _g / 2;
    _m = Min(_d1, _d2);
    _dS = _m - kS * Log(Exp((_m - _d1) / kS) + Exp((_m - _d2) / kS));
    _dB = _m - kB * Log(Exp((_m - _d1) / kB) + Exp((_m - _d2) / kB));
    _v = Min(_dS / coaptw, 1);
    _u = _dB / dBmax;
    zq = zfe - coapt * (1 - (1 - _v)^2) - bA * (2 * _u - _u^2);
  Return
EndIf
For k In {0:2}
  th = Pi / 2 + 2 * Pi * k / 3;
  If (shape == 1)
    // Sections x = const across the leaflet, each the closed outline of the shell (its two faces
    // sampled densest near the gap planes), lofted into one solid and cut to the sector below.
    xs = Max(0.5 * rcenter, gap / (2 * sn) + 0.0001);
    xe = Ra + 0.001;
    wires() = {};
    For i In {0:nsec}
      xi = xs + (xe - xs) * i / nsec;
      ye = Min((xi * sn - gap / 2 + 0.0006) / cs, Sqrt(Max((Ra + 0.0015)^2 - xi^2, 0)) + 0.0015);
      up() = {};
      lo() = {};
      For j In {0:nj}
        yj = ye * Sin(Pi / 2 * (2 * j / nj - 1));
        // the faces: t/2 either side along the normal (slopes by central differences); each
        // Call on a line of its own: gmsh 4.8 drops what follows a Call on the same line
        xq = xi + 1e-6;
        yq = yj;
        Call StripLeafletZ;
        zxp = zq;
        xq = xi - 1e-6;
        Call StripLeafletZ;
        zxm = zq;
        xq = xi;
        yq = yj + 1e-6;
        Call StripLeafletZ;
        zyp = zq;
        yq = yj - 1e-6;
        Call StripLeafletZ;
        zym = zq;
        yq = yj;
        Call StripLeafletZ;
        zx = (zxp - zxm) / 2e-6;
        zy = (zyp - zym) / 2e-6;
        nn = Sqrt(1 + zx^2 + zy^2);
        p1 = newp; Point(p1) = {xi - t / 2 * zx / nn, yj - t / 2 * zy / nn, zq + t / 2 / nn};
        p2 = newp; Point(p2) = {xi + t / 2 * zx / nn, yj + t / 2 * zy / nn, zq - t / 2 / nn};
        up() += p1;
        lo() += p2;
      EndFor
      c1 = newc; Spline(c1) = up();
      c2 = newc; Line(c2) = {up(nj), lo(nj)};
      c3 = newc; Spline(c3) = lo();
      c4 = newc; Line(c4) = {lo(0), up(0)};
      w = newll; Wire(w) = {c1, c2, -c3, c4};
      wires() += w;
    EndFor
    v = newv;
    ThruSections(v) = {wires()};
    shell() = {v};
    Rotate {{0, 0, 1}, {0, 0, 0}, th} { Volume{shell()}; }
  Else
  ro = rho_l + t / 2;
  ri = rho_l - t / 2;
  Sphere(20 + 10 * k) = {0, 0, 0, 1};
  Dilate {{0, 0, 0}, {ro, ro, stretch * rho_l + t / 2}} { Volume{20 + 10 * k}; }
  Sphere(21 + 10 * k) = {0, 0, 0, 1};
  Dilate {{0, 0, 0}, {ri, ri, stretch * rho_l - t / 2}} { Volume{21 + 10 * k}; }
  shell() = BooleanDifference{ Volume{20 + 10 * k}; Delete; }{ Volume{21 + 10 * k}; Delete; };
  If (coapt > 0)
    // The band: from the leaflet's lower face to coapt above its upper face (inside the outer
    // ellipsoid, outside the inner one raised by coapt), within a slab of thickness t on the
    // sector side of each dividing plane (clipped to the sector below with the shell).
    Sphere(26 + 10 * k) = {0, 0, 0, 1};
    Dilate {{0, 0, 0}, {ro, ro, stretch * rho_l + t / 2}} { Volume{26 + 10 * k}; }
    Sphere(27 + 10 * k) = {0, 0, 0, 1};
    Dilate {{0, 0, 0}, {ri, ri, stretch * rho_l - t / 2}} { Volume{27 + 10 * k}; }
    Translate {0, 0, coapt} { Volume{27 + 10 * k}; }
    band() = BooleanDifference{ Volume{26 + 10 * k}; Delete; }{ Volume{27 + 10 * k}; Delete; };
    Translate {Ra, 0, zc} { Volume{band()}; }
    Rotate {{0, 0, 1}, {0, 0, 0}, th} { Volume{band()}; }
    Box(28 + 10 * k) = {gap / 2, -big, -Lin, t, 2 * big, zc + Lin};
    Rotate {{0, 0, 1}, {0, 0, 0}, th + Pi / 3 - Pi / 2} { Volume{28 + 10 * k}; }
    Box(29 + 10 * k) = {gap / 2, -big, -Lin, t, 2 * big, zc + Lin};
    Rotate {{0, 0, 1}, {0, 0, 0}, th - Pi / 3 + Pi / 2} { Volume{29 + 10 * k}; }
    slabs() = BooleanUnion{ Volume{28 + 10 * k}; Delete; }{ Volume{29 + 10 * k}; Delete; };
    fins() = BooleanIntersection{ Volume{band()}; Delete; }{ Volume{slabs()}; Delete; };
  EndIf
  Translate {Ra, 0, zc} { Volume{shell()}; }
  Rotate {{0, 0, 1}, {0, 0, 0}, th} { Volume{shell()}; }
  If (coapt > 0)
    shell() = BooleanUnion{ Volume{shell()}; Delete; }{ Volume{fins()}; Delete; };
  EndIf
  EndIf
  // The sector: two half-spaces bounded by the dividing planes at th +- 60 degrees, each moved
  // gap/2 into the sector, and the lower half (z < zc).
  // (the strip leaflet's free edge is the horizontal cut at zfe: its steep strip cut by the gap
  // plane would leave a long sliver face, so the planes move out past its ventricular face)
  gcut = gap / 2;
  ztop = zc;
  If (shape == 1)
    gcut = 0.00015;
    ztop = zfe;
  EndIf
  Box(22 + 10 * k) = {gcut, -big, -Lin, big, 2 * big, ztop + Lin};
  Rotate {{0, 0, 1}, {0, 0, 0}, th + Pi / 3 - Pi / 2} { Volume{22 + 10 * k}; }
  Box(23 + 10 * k) = {gcut, -big, -Lin, big, 2 * big, ztop + Lin};
  Rotate {{0, 0, 1}, {0, 0, 0}, th - Pi / 3 + Pi / 2} { Volume{23 + 10 * k}; }
  Cylinder(24 + 10 * k) = {0, 0, -Lin, 0, 0, Lin + ztop, Ra};
  Rotate {{0, 0, 1}, {0, 0, 0}, Pi / 6} { Volume{24 + 10 * k}; }
  sector() = BooleanIntersection{ Volume{22 + 10 * k}; Delete; }{ Volume{23 + 10 * k}; Delete; };
  sector() = BooleanIntersection{ Volume{sector()}; Delete; }{ Volume{24 + 10 * k}; Delete; };
  If (rcenter > 0) // the leaflets end on a circle of radius rcenter about the axis
    Cylinder(25 + 10 * k) = {0, 0, -Lin, 0, 0, Lin + zc, rcenter};
    sector() = BooleanDifference{ Volume{sector()}; Delete; }{ Volume{25 + 10 * k}; Delete; };
  EndIf
  leaf() += BooleanIntersection{ Volume{shell()}; Delete; }{ Volume{sector()}; Delete; };
EndFor

// Conforming fluid and leaflets.
all() = BooleanFragments{ Volume{fluid()}; Delete; }{ Volume{leaf()}; Delete; };
eps = 1e-3 * Ra; // selection tolerance [m]
// The fragments' tags: the leaflets lie within z in [0, zc], the fluid spans the whole length.
leaf() = Volume In BoundingBox{-big, -big, -Lin / 2, big, big, zc + Lout / 2};
fl() = Volume{:};
fl() -= leaf();
Physical Volume("fluid", 1) = fl();
Physical Volume("leaflets", 2) = leaf();

lbound() = Abs(Boundary{ Volume{leaf()}; });
fbound() = Abs(Boundary{ Volume{fl()}; });
inl() = Surface In BoundingBox{-big, -big, -Lin - eps, big, big, -Lin + eps};
outl() = Surface In BoundingBox{-big, -big, zc + Lout - eps, big, big, zc + Lout + eps};
// Leaflet faces shared with the fluid are the interface; the others lie on the root wall.
iface() = {};
attach() = {};
For i In {0:#lbound() - 1}
  s = lbound(i);
  shared = 0;
  For j In {0:#fbound() - 1}
    If (fbound(j) == s)
      shared = 1;
    EndIf
  EndFor
  If (shared)
    iface() += s;
  Else
    attach() += s;
  EndIf
EndFor
wall() = fbound();
wall() -= iface();
wall() -= inl();
wall() -= outl();
Physical Surface("inlet", 11) = inl();
Physical Surface("outlet", 12) = outl();
Physical Surface("root_wall", 13) = wall();
Physical Surface("attachment", 14) = attach();
Physical Surface("interface", 15) = iface();

// Sizes: h on and near the leaflets, growing to hfar over hgrow.
hleaf = h;
If (tlayers >= 2)
  hleaf = Min(h, t / 2 * 1.5);
EndIf
Field[1] = Distance;
Field[1].SurfacesList = {iface()};
Field[1].NumPointsPerCurve = 50;
Field[2] = Threshold;
Field[2].InField = 1;
Field[2].SizeMin = hleaf;
Field[2].SizeMax = hfar;
Field[2].DistMin = 0.1 * hgrow;
Field[2].DistMax = hgrow;
bg = 2;
Background Field = bg;
If (Exists(hbase))
  Field[3] = Distance;
  Field[3].SurfacesList = {attach()};
  Field[3].NumPointsPerCurve = 50;
  Field[4] = Threshold;
  Field[4].InField = 3;
  Field[4].SizeMin = Min(hbase, hleaf);
  Field[4].SizeMax = hfar;
  Field[4].DistMin = hbasew;
  Field[4].DistMax = 2 * hbasew;
  Field[5] = Min;
  Field[5].FieldsList = {2, 4};
  bg = 5;
  Background Field = bg;
EndIf
If (Exists(hcenter))
  If (!Exists(hcenterw)) hcenterw = 0.003; EndIf
  Field[6] = Box;
  Field[6].VIn = Min(hcenter, hleaf);
  Field[6].VOut = hfar;
  Field[6].XMin = -hcenterw;
  Field[6].XMax = hcenterw;
  Field[6].YMin = -hcenterw;
  Field[6].YMax = hcenterw;
  Field[6].ZMin = 0;
  Field[6].ZMax = zc;
  Field[6].Thickness = hcenterw;
  Field[7] = Min;
  Field[7].FieldsList = {bg, 6};
  Background Field = 7;
EndIf
Mesh.CharacteristicLengthExtendFromBoundary = 0;
Mesh.CharacteristicLengthFromPoints = 0;
Mesh.CharacteristicLengthFromCurvature = 0;
Mesh.CharacteristicLengthMin = 0;
Mesh.CharacteristicLengthMax = hfar;
Mesh.Optimize = 1;
Mesh.OptimizeThreshold = 0.6; // optimise every tet of quality (gamma) below 0.6, not 0.3

