// sin, cos, atan and log from additions, multiplications, divisions and square roots only,
// so that what they compute is the same bits in every build: the platforms' libm (glibc
// natively, musl under Emscripten) differ in the last bit now and then. One bit moved a
// procedural example's vertex enough to change labels (turned_part, flange), and a cone's
// coefficients, taken from its half-angle, differed between the builds' reports. Accurate
// to a few units in the last place over the arguments used (|x| up to a few turns).
#pragma once

#include <cmath>

namespace vqsa::portable {

namespace detail {

template <int N>
double horner(double x, const double (&coefficients)[N]) {
    double p = coefficients[0];
    for (int i = 1; i < N; ++i) p = p * x + coefficients[i];
    return p;
}

// Taylor series on [-π/4, π/4], in x²: the last terms are below 1e-20.
inline double sin_reduced(double x) {
    constexpr double kSeries[] = {1.0 / 355687428096000.0, -1.0 / 1307674368000.0, 1.0 / 6227020800.0,
                                  -1.0 / 39916800.0,       1.0 / 362880.0,         -1.0 / 5040.0,
                                  1.0 / 120.0,             -1.0 / 6.0};  // 1/17! … -1/3!
    const double x2 = x * x;
    return x + x * x2 * horner(x2, kSeries);
}

inline double cos_reduced(double x) {
    constexpr double kSeries[] = {1.0 / 6402373705728000.0, -1.0 / 20922789888000.0, 1.0 / 87178291200.0,
                                  -1.0 / 479001600.0,       1.0 / 3628800.0,         -1.0 / 40320.0,
                                  1.0 / 720.0,              -1.0 / 24.0,             0.5};  // 1/18! … 1/2!
    const double x2 = x * x;
    return 1.0 - x2 * horner(x2, kSeries);
}

// x = k π/2 + r, |r| ≤ π/4 (Cody–Waite: π/2 in two parts, the first exact times small k).
inline double reduce(double x, long& k) {
    constexpr double kTwoOverPi = 0.63661977236758134308;
    constexpr double kPiOver2High = 1.57079632673412561417e+00;
    constexpr double kPiOver2Low = 6.07710050650619224932e-11;
    const double q = std::nearbyint(x * kTwoOverPi);
    k = static_cast<long>(q);
    return (x - q * kPiOver2High) - q * kPiOver2Low;
}

}  // namespace detail

inline double sin(double x) {
    long k;
    const double r = detail::reduce(x, k);
    switch (k & 3) {
        case 0: return detail::sin_reduced(r);
        case 1: return detail::cos_reduced(r);
        case 2: return -detail::sin_reduced(r);
        default: return -detail::cos_reduced(r);
    }
}

inline double cos(double x) {
    long k;
    const double r = detail::reduce(x, k);
    switch (k & 3) {
        case 0: return detail::cos_reduced(r);
        case 1: return -detail::sin_reduced(r);
        case 2: return -detail::cos_reduced(r);
        default: return detail::sin_reduced(r);
    }
}

// Arctangent: beyond 1 by π/2 − atan(1/x), beyond tan(π/12) by π/6 + atan((√3 x − 1)/(√3 + x)),
// then its series in x² (x² ≤ 0.072: sixteen terms leave under 1e-18).
inline double atan(double x) {
    constexpr double kPiOver2 = 1.57079632679489661923, kPiOver6 = 0.52359877559829887308;
    constexpr double kTanPiOver12 = 0.26794919243112270647, kSqrt3 = 1.73205080756887729353;
    if (x < 0) return -atan(-x);
    if (x > 1) return kPiOver2 - atan(1 / x);
    if (x > kTanPiOver12) return kPiOver6 + atan((kSqrt3 * x - 1) / (kSqrt3 + x));
    const double x2 = x * x;
    double p = 0;
    for (int k = 16; k >= 0; --k) p = p * x2 + (k % 2 ? -1.0 : 1.0) / (2 * k + 1);
    return x * p;
}

// Natural logarithm of x > 0: x = m 2^e with m in [√½, √2], log m = 2 atanh((m-1)/(m+1)).
inline double log(double x) {
    int e;
    double m = std::frexp(x, &e);  // exact
    if (m < 0.70710678118654752440) m *= 2, --e;
    const double s = (m - 1) / (m + 1), s2 = s * s;
    double p = 1.0 / 21;
    for (int n = 19; n >= 1; n -= 2) p = p * s2 + 1.0 / n;
    constexpr double kLn2 = 0.69314718055994530942;
    return e * kLn2 + 2 * s * p;
}

}  // namespace vqsa::portable
