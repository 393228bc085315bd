// Quadric surfaces f(p) = C0 + C1 x + C2 y + C3 z + C4 x² + C5 xy + C6 xz + C7 y² + C8 yz + C9 z².
#pragma once

#include "io/mesh.h"

#include <Eigen/Core>
#include <array>
#include <cmath>

namespace vqsa {

struct Quadric {
    std::array<double, 10> c{};

    // f = pᵀ A p + bᵀ p + c0
    Eigen::Matrix3d A() const;
    Vec3 b() const { return {c[1], c[2], c[3]}; }
    bool is_plane() const { return c[4] == 0 && c[5] == 0 && c[6] == 0 && c[7] == 0 && c[8] == 0 && c[9] == 0; }

    double value(const Vec3& p) const {
        const double x = p.x(), y = p.y(), z = p.z();
        return c[0] + x * (c[1] + c[4] * x + c[5] * y + c[6] * z) + y * (c[2] + c[7] * y + c[8] * z) +
               z * (c[3] + c[9] * z);
    }
    Vec3 gradient(const Vec3& p) const {
        const double x = p.x(), y = p.y(), z = p.z();
        return {c[1] + 2 * c[4] * x + c[5] * y + c[6] * z, c[2] + c[5] * x + 2 * c[7] * y + c[8] * z,
                c[3] + c[6] * x + c[8] * y + 2 * c[9] * z};
    }
    // ‖A‖ Frobenius: the a' of Taubin's second-order distance (docs/METHOD.md §1).
    double hessian_norm() const {
        return std::sqrt(c[4] * c[4] + c[7] * c[7] + c[9] * c[9] + 0.5 * (c[5] * c[5] + c[6] * c[6] + c[8] * c[8]));
    }

    static Quadric from(const Eigen::Matrix3d& A, const Vec3& b, double c0);
    static Quadric plane(const Vec3& normal, const Vec3& point);
};

// The same surface in coordinates q = scale * p + translation.
Quadric change_frame(const Quadric& f, double scale, const Vec3& translation);

// Unit coefficient norm, and a sign fixed so that equal surfaces give equal vectors:
// the coefficient of largest magnitude is positive.
Quadric normalized(const Quadric& f);

}  // namespace vqsa
