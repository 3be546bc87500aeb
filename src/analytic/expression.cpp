#include "fsi/analytic/expression.hpp"
#include "fsi/common.hpp"

#include <cmath>
#include <muParser.h>

namespace fsi {

struct Expression::Impl {
  mu::Parser parser;
  double x = 0, y = 0, z = 0, t = 0; // the variables the parser reads (their addresses)
};

Expression::Expression(const std::string &text, const std::string &option, int size)
    : impl_(std::make_unique<Impl>()), option_(option) {
  try {
    impl_->parser.DefineVar("x", &impl_->x);
    impl_->parser.DefineVar("y", &impl_->y);
    impl_->parser.DefineVar("z", &impl_->z);
    impl_->parser.DefineVar("t", &impl_->t);
    impl_->parser.SetExpr(text);
    impl_->parser.Eval(size_); // parses now: syntax errors and unknown names surface here
  } catch (mu::Parser::exception_type &e) {
    throw InputError("option -" + option + " '" + text + "': " + e.GetMsg() +
                     " (variables x, y, z [m], t [s]; e.g. '0, 0, 1 - (x^2 + y^2)/1e-4')");
  }
  if (size != 0 && size_ != size)
    throw InputError("option -" + option + " '" + text + "' gives " + std::to_string(size_) +
                     " value(s), " + std::to_string(size) + " expected (separate them by commas)");
}

Expression::~Expression() = default;

void Expression::eval(const double x[3], double t, double *out) const {
  impl_->x = x[0], impl_->y = x[1], impl_->z = x[2], impl_->t = t;
  int n = 0;
  const double *v = impl_->parser.Eval(n);
  for (int i = 0; i < n; ++i) {
    if (!std::isfinite(v[i]))
      throw InputError("option -" + option_ + " is not finite at x = (" + std::to_string(x[0]) +
                       ", " + std::to_string(x[1]) + ", " + std::to_string(x[2]) +
                       "), t = " + std::to_string(t) + ": check the formula");
    out[i] = v[i];
  }
}

double Expression::scalar(double t) const {
  const double x[3] = {0, 0, 0};
  double v = 0;
  eval(x, t, &v);
  return v;
}

} // namespace fsi
