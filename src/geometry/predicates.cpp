#include "geometry/predicates.hpp"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Interval_nt.h>
#include <CGAL/gmpxx.h>

#include <cmath>
#include <cstdint>
#include <cstring>

namespace curvemesh::geometry {

namespace {
using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
}

int orientation(const Vec2& a, const Vec2& b, const Vec2& c) {
  return static_cast<int>(CGAL::orientation(Kernel::Point_2(a.x(), a.y()), Kernel::Point_2(b.x(), b.y()),
                                            Kernel::Point_2(c.x(), c.y())));
}

int orientation(const ExactPoint& a, const ExactPoint& b, const ExactPoint& c) {
  {  // An interval filter first: the rationals' arithmetic (a gcd per operation) only when it fails.
    CGAL::Protect_FPU_rounding<true> upward;
    using I = CGAL::Interval_nt<false>;
    const auto iv = [](const mpq_class& q) { return I(CGAL::to_interval(q)); };
    const I det = (iv(b.x) - iv(a.x)) * (iv(c.y) - iv(a.y)) - (iv(b.y) - iv(a.y)) * (iv(c.x) - iv(a.x));
    if (det.inf() > 0) return 1;
    if (det.sup() < 0) return -1;
  }
  const mpq_class det = (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
  return sgn(det);
}

double nearest_double(const mpq_class& q) {
  // get_d truncates towards zero; the nearest double is that one or its successor away from zero.
  const double lo = q.get_d();
  if (!std::isfinite(lo)) return lo;
  const double hi = std::nextafter(lo, q >= 0 ? HUGE_VAL : -HUGE_VAL);
  if (!std::isfinite(hi)) return lo;
  const mpq_class dlo = abs(q - mpq_class(lo));
  const mpq_class dhi = abs(mpq_class(hi) - q);
  if (dlo < dhi) return lo;
  if (dhi < dlo) return hi;
  // A tie: the one with an even last mantissa bit.
  std::int64_t bits = 0;
  std::memcpy(&bits, &lo, sizeof bits);
  return (bits & 1) == 0 ? lo : hi;
}

Vec2 nearest_double(const ExactPoint& p) { return {nearest_double(p.x), nearest_double(p.y)}; }

}  // namespace curvemesh::geometry
