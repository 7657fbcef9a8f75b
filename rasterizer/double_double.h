// Double-double arithmetic: a value as the unevaluated sum hi + lo of two doubles, about 106 bits
// of precision, from the error-free transformations TwoSum and TwoProduct (fma). Used where
// double alone cancels away the answer: clipping edges whose endpoints lie 10^20 pixels apart.
#pragma once

#include <cmath>

namespace rast {

struct DoubleDouble {
  double hi = 0;
  double lo = 0;  // |lo| <= ulp(hi) / 2

  // a * b exactly.
  static DoubleDouble product(double a, double b) {
    const double p = a * b;
    return {p, std::fma(a, b, -p)};
  }

  friend DoubleDouble operator+(const DoubleDouble& a, const DoubleDouble& b) {
    const double s = a.hi + b.hi;
    const double z = s - a.hi;
    // TwoSum's error is exact (the same whichever operand comes first), and the tails are added
    // to each other before it, so a + b and b + a have the same bits: the clipper's symmetry.
    const double e = ((a.hi - (s - z)) + (b.hi - z)) + (a.lo + b.lo);
    return normalized(s, e);
  }

  friend DoubleDouble operator*(const DoubleDouble& a, double b) {
    const DoubleDouble p = product(a.hi, b);
    return normalized(p.hi, p.lo + a.lo * b);
  }

  DoubleDouble abs() const { return hi < 0 ? DoubleDouble{-hi, -lo} : *this; }

  // a / b rounded to double: one Newton step on the double quotient.
  friend double divide(const DoubleDouble& a, const DoubleDouble& b) {
    const double q = a.hi / b.hi;
    const DoubleDouble remainder = a + (b * -q);
    return q + remainder.hi / b.hi;
  }

 private:
  static DoubleDouble normalized(double s, double e) {
    const double hi = s + e;
    return {hi, e - (hi - s)};
  }
};

}  // namespace rast
