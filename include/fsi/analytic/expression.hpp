// A user's formula in x, y, z [m] and t [s], parsed once by muparser (Debian's libmuparser):
// "0, 0, 2*(1 - (x^2 + y^2)/25e-6)" gives a vector of 3 values, "sin(2*_pi*t)" one.  Constants
// _pi and _e and the usual functions (sin, exp, sqrt, abs, min, max, ...) are muparser's.
// Syntax errors and unknown names are InputErrors naming the option at construction.
#pragma once
#include <memory>
#include <string>

namespace fsi {

class Expression {
public:
  // option: the option the text came from (for error messages); size: values expected (1 or 3,
  // 0: either).
  Expression(const std::string &text, const std::string &option, int size);
  ~Expression();
  int size() const { return size_; }
  // out: size() values at (x, t).
  void eval(const double x[3], double t, double *out) const;
  double scalar(double t) const; // size 1, at x = 0

private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  std::string option_;
  int size_ = 0;
};

} // namespace fsi
