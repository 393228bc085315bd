#include "fitting/quadric.h"

#include <cmath>

namespace vqsa {

Eigen::Matrix3d Quadric::A() const {
    Eigen::Matrix3d a;
    a << c[4], 0.5 * c[5], 0.5 * c[6], 0.5 * c[5], c[7], 0.5 * c[8], 0.5 * c[6], 0.5 * c[8], c[9];
    return a;
}

Quadric Quadric::from(const Eigen::Matrix3d& A, const Vec3& b, double c0) {
    Quadric q;
    q.c = {c0, b.x(), b.y(), b.z(), A(0, 0), A(0, 1) + A(1, 0), A(0, 2) + A(2, 0), A(1, 1), A(1, 2) + A(2, 1), A(2, 2)};
    return q;
}

Quadric Quadric::plane(const Vec3& normal, const Vec3& point) {
    Quadric q;
    q.c[0] = -normal.dot(point);
    q.c[1] = normal.x(), q.c[2] = normal.y(), q.c[3] = normal.z();
    return q;
}

Quadric change_frame(const Quadric& f, double scale, const Vec3& translation) {
    // p = (q - t) / s  ⇒  f(p) = qᵀ A q / s² + (b/s - 2 A t / s²)ᵀ q + c - bᵀ t / s + tᵀ A t / s²
    const Eigen::Matrix3d A = f.A();
    const Vec3 b = f.b();
    const Vec3 At = A * translation;
    const double s2 = scale * scale;
    return Quadric::from(A / s2, b / scale - 2.0 * At / s2, f.c[0] - b.dot(translation) / scale + translation.dot(At) / s2);
}

Quadric normalized(const Quadric& f) {
    double norm = 0, largest = 0;
    for (double v : f.c) {
        norm += v * v;
        if (std::abs(v) > std::abs(largest)) largest = v;
    }
    norm = std::sqrt(norm);
    if (norm == 0) return f;
    Quadric q;
    const double s = (largest < 0 ? -1.0 : 1.0) / norm;
    for (int i = 0; i < 10; ++i) q.c[i] = f.c[i] * s;
    return q;
}

}  // namespace vqsa
