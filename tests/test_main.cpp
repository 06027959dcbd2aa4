// Test style: doctest::Approx(x).epsilon(e) passes when |a - b| < e (scale + max(|a|, |b|)), and
// scale is 1 by default, so for quantities far below 1 (forces of 0.01 N, gaps of 1e-4 mm,
// energies of 1e-3 N mm, in the mm-N-MPa units) e acts as an ABSOLUTE tolerance and the check
// can hardly fail: Approx(0.01).epsilon(0.02) accepts anything in [-0.01, 0.03]. For such
// quantities write Approx(x).epsilon(e).scale(0), a relative tolerance |a - b| < e max(|a|, |b|).
// Note that with scale(0) two exact zeros do not compare equal (0 < 0 is false): compare
// quantities that can be exactly 0, and positions whose size depends on the origin, with an
// explicit absolute bound, std::abs(a - b) <= tol.
#define DOCTEST_CONFIG_IMPLEMENT_WITH_MAIN
#include <doctest/doctest.h>
