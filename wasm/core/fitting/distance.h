// Taubin's second-order approximate distance and the triangle error (docs/METHOD.md §1).
#pragma once

#include "fitting/quadric.h"

namespace vqsa {

// The non-negative root δ of ‖A‖ δ² + ‖∇f(p)‖ δ − |f(p)| = 0. Never exceeds the
// Euclidean distance to {f = 0}, equals it for a plane, and does not change when f
// is scaled.
inline double taubin_distance(const Quadric& f, double hessian_norm, const Vec3& p) {
    const double value = std::abs(f.value(p));
    if (value == 0) return 0;
    const double g = f.gradient(p).norm();
    return 2 * value / (g + std::sqrt(g * g + 4 * hessian_norm * value));
}

inline double taubin_distance(const Quadric& f, const Vec3& p) { return taubin_distance(f, f.hessian_norm(), p); }

// d(t, P) = area · (δ(v0)² + δ(v1)² + δ(v2)² + δ(g)²) / 4, g the barycentre.
inline double triangle_error(const Quadric& f, double hessian_norm, const Vec3& a, const Vec3& b, const Vec3& c,
                             const Vec3& barycentre, double area) {
    const double d0 = taubin_distance(f, hessian_norm, a), d1 = taubin_distance(f, hessian_norm, b),
                 d2 = taubin_distance(f, hessian_norm, c), d3 = taubin_distance(f, hessian_norm, barycentre);
    return 0.25 * area * (d0 * d0 + d1 * d1 + d2 * d2 + d3 * d3);
}

}  // namespace vqsa
