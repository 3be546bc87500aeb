// One family of fibres added to the solid's isotropic law: the circumferential collagen of valve
// leaflets, which carries the closed valve's diastolic load from commissure to commissure.
//   W_f = c1/2 (exp(c2 (I4 - 1)^2) - 1)  for I4 > 1 (fibres carry no compression), else 0,
//   I4 = a0 . C a0 = |F a0|^2, a0 the unit fibre direction in the reference configuration
// (the anisotropic part of the Lee-Sacks leaflet law).  The switch at I4 = 1 is a kink of W_f''
// (W'' jumps from c1 c2 to 0): -solid_fibre_tension_only false drops it (fibres then resist
// compression as well), which the finite-difference Jacobian test uses.  Options: -solid_fibres
// none | circumferential | chord, -solid_fibre_c1 [Pa], -solid_fibre_c2 [-]; directions about the z
// axis through the origin (the valve's axis):
//   circumferential  a0 = e_theta at the point;
//   chord            a0 = the chord joining the two commissures that bound the point's sector
//                    (-solid_fibre_commissures a1,a2,... [deg]): constant over each leaflet, so
//                    near the free edge it runs within half a sector of the edge's line.
// P_iJ += 2 W' (F a)_i a_J;  A_iJkL += 2 W' d_ik a_J a_L + 4 W'' (F a)_i a_J (F a)_k a_L.
#pragma once
#include <string>
#include <vector>

namespace fsi {

struct FibreFamily {
  enum Kind { None, Circumferential, Chord } kind = None;
  double c1 = 0, c2 = 0;
  bool tension_only = true;        // false: W_f for I4 < 1 too (smooth at I4 = 1)
  std::vector<double> commissures; // [rad], sorted, in [0, 2 pi)

  bool active() const { return kind != None; }
  std::string name() const;
  // Unit direction at reference point X (zero on the axis itself).
  void direction(const double X[3], double a[3]) const;
  double energy(const double F[3][3], const double a[3]) const;
  void add_stress(const double F[3][3], const double a[3], double P[3][3]) const;
  void add_tangent(const double F[3][3], const double a[3], double P[3][3],
                   double A[3][3][3][3]) const;
  // Reads the options above; material_kind: -solid_material (fibres need a hyperelastic law).
  static FibreFamily from_options(const std::string &material_kind);
};

} // namespace fsi
