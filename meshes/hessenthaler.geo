// The Hessenthaler et al. (2017) FSI phantom (Phase I): a silicone flap clamped on the end wall
// of a pipe, between two inlet pipes whose jets merge around it.  SI units [m].  Axis along z,
// blood-analogue flows towards +z, gravity along -y.  Dimensions from the paper (the data set's
// exact surface is not used); what we assume is marked "assumed":
//   Rout   outlet pipe radius (76.2 mm diameter), from the end wall z = 0 to z = Lout
//   Lout   89.5 mm of phantom plus the 250 mm extension the published computations use
//   Rin    inlet pipe radius (21.9 mm diameter); yin their centres' offset (y = +-27.15 mm)
//   Lin    inlet pipe length: the inlet planes at z = -29.5 mm
//   fw, ft, fl  flap width (x), thickness (y), length (z): 11 x 2 x 65 mm, clamped at z = 0
//   flap_only  1: mesh the flap alone (solid-only scenes: the calibration without flow)
//   h      element size on the flap; hjet in the inlet pipes and the jets' first 100 mm;
//          hfar in the rest of the phantom; hext at the outlet end of the extension
// Assumed: the inlet pipes are straight circular cylinders meeting the flat end wall of the
// outlet pipe at z = 0 (their discs touch the outlet pipe's wall: 27.15 + 10.95 = 38.1 mm); the
// flap is centred on the axis with its faces normal to x, y, z; every edge is sharp.
// Groups: volumes fluid, flap; surfaces inlet_upper (y > 0), inlet_lower, outlet, wall (pipes
// and end wall), clamp (the flap's base), interface (the flap's wetted faces).
SetFactory("OpenCASCADE");
If (!Exists(Rout)) Rout = 0.0381; EndIf
If (!Exists(Lout)) Lout = 0.0895 + 0.25; EndIf
If (!Exists(Rin)) Rin = 0.01095; EndIf
If (!Exists(yin)) yin = 0.02715; EndIf
If (!Exists(Lin)) Lin = 0.0295; EndIf
If (!Exists(fw)) fw = 0.011; EndIf
If (!Exists(ft)) ft = 0.002; EndIf
If (!Exists(fl)) fl = 0.065; EndIf
If (!Exists(flap_only)) flap_only = 0; EndIf
If (!Exists(h)) h = 0.001; EndIf
If (!Exists(hjet)) hjet = 3 * h; EndIf
If (!Exists(hfar)) hfar = 6 * h; EndIf
If (!Exists(hext)) hext = 15 * h; EndIf
If (h <= 0 || hjet <= 0 || hfar <= 0 || hext <= 0)
  Error("hessenthaler.geo: the sizes h, hjet, hfar and hext must be positive");
EndIf
If (yin + Rin > Rout + 1e-9 || yin - Rin < ft / 2)
  Error("hessenthaler.geo: each inlet disc must lie on the end wall between the flap and the outlet pipe's wall (ft/2 <= yin - Rin, yin + Rin <= Rout)");
EndIf
If (fl >= Lout || fw / 2 >= Rout)
  Error("hessenthaler.geo: the flap must fit inside the outlet pipe (fl < Lout, fw/2 < Rout)");
EndIf

If (flap_only)
  Box(4) = {-fw / 2, -ft / 2, 0, fw, ft, fl};
  eps = 1e-4 * fl;
  Physical Volume("flap", 2) = {4};
  clamp() = Surface In BoundingBox{-fw / 2 - eps, -ft / 2 - eps, -eps, fw / 2 + eps, ft / 2 + eps, eps};
  iface() = Abs(Boundary{ Volume{4}; });
  iface() -= clamp();
  Physical Surface("clamp", 15) = clamp();
  Physical Surface("interface", 16) = iface();
  Mesh.CharacteristicLengthMin = 0;
  Mesh.CharacteristicLengthMax = h;
  Mesh.Optimize = 1;
Else
  Cylinder(1) = {0, 0, 0, 0, 0, Lout, Rout};
  Cylinder(2) = {0, yin, -Lin, 0, 0, Lin, Rin};
  Cylinder(3) = {0, -yin, -Lin, 0, 0, Lin, Rin};
  fluid() = BooleanUnion{ Volume{1}; Delete; }{ Volume{2, 3}; Delete; };
  Box(4) = {-fw / 2, -ft / 2, 0, fw, ft, fl};
  all() = BooleanFragments{ Volume{fluid()}; Delete; }{ Volume{4}; Delete; };

  eps = 1e-4 * Rout; // selection tolerance [m]
  flap() = Volume In BoundingBox{-fw / 2 - eps, -ft / 2 - eps, -eps, fw / 2 + eps, ft / 2 + eps, fl + eps};
  fvol() = Volume{:};
  fvol() -= flap();
  Physical Volume("fluid", 1) = fvol();
  Physical Volume("flap", 2) = flap();

  fbound() = Abs(Boundary{ Volume{fvol()}; });
  sbound() = Abs(Boundary{ Volume{flap()}; });
  inu() = Surface In BoundingBox{-Rin - eps, yin - Rin - eps, -Lin - eps, Rin + eps, yin + Rin + eps, -Lin + eps};
  inl() = Surface In BoundingBox{-Rin - eps, -yin - Rin - eps, -Lin - eps, Rin + eps, -yin + Rin + eps, -Lin + eps};
  outl() = Surface In BoundingBox{-Rout - eps, -Rout - eps, Lout - eps, Rout + eps, Rout + eps, Lout + eps};
  clamp() = Surface In BoundingBox{-fw / 2 - eps, -ft / 2 - eps, -eps, fw / 2 + eps, ft / 2 + eps, eps};
  iface() = sbound();
  iface() -= clamp();
  wall() = fbound();
  wall() -= iface();
  wall() -= inu();
  wall() -= inl();
  wall() -= outl();
  Physical Surface("inlet_upper", 11) = inu();
  Physical Surface("inlet_lower", 12) = inl();
  Physical Surface("outlet", 13) = outl();
  Physical Surface("wall", 14) = wall();
  Physical Surface("clamp", 15) = clamp();
  Physical Surface("interface", 16) = iface();

  // Sizes: h on the flap growing to hjet over 10 mm; hjet in the inlet pipes and the jets' path
  // (|y| within yin + Rin, z below 100 mm); hfar elsewhere in the phantom, growing to hext at the
  // outlet end of the extension.
  Field[1] = Distance;
  Field[1].SurfacesList = {iface()};
  Field[1].NumPointsPerCurve = 40;
  Field[2] = Threshold;
  Field[2].InField = 1;
  Field[2].SizeMin = h;
  Field[2].SizeMax = hext;
  Field[2].DistMin = 0.002;
  Field[2].DistMax = 0.002 + 10 * (hjet - h);
  Field[3] = Box;
  Field[3].VIn = hjet;
  Field[3].VOut = hext;
  Field[3].XMin = -Rout;
  Field[3].XMax = Rout;
  Field[3].YMin = -Rout;
  Field[3].YMax = Rout;
  Field[3].ZMin = -Lin;
  Field[3].ZMax = 0.1;
  Field[3].Thickness = 0.02;
  Field[4] = MathEval;
  Field[4].F = Sprintf("%g + (%g - %g) * Max(0, Min(1, (z - 0.0895) / 0.2))", hfar, hext, hfar);
  Field[5] = Min;
  Field[5].FieldsList = {2, 3, 4};
  Background Field = 5;
  Mesh.CharacteristicLengthExtendFromBoundary = 0;
  Mesh.CharacteristicLengthFromPoints = 0;
  Mesh.CharacteristicLengthFromCurvature = 0;
  Mesh.CharacteristicLengthMin = 0;
  Mesh.CharacteristicLengthMax = hext;
  Mesh.Optimize = 1;
  Mesh.OptimizeThreshold = 0.6;
EndIf
