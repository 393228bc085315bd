#include "fitting/classify.h"

#include "geometry/portable_math.h"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>

namespace vqsa {

const char* type_name(QuadricType type) {
    switch (type) {
        case QuadricType::plane: return "plane";
        case QuadricType::sphere: return "sphere";
        case QuadricType::cylinder: return "cylinder";
        case QuadricType::cone: return "cone";
        case QuadricType::ellipsoid: return "ellipsoid";
        case QuadricType::hyperboloid_one_sheet: return "hyperboloid_one_sheet";
        case QuadricType::hyperboloid_two_sheets: return "hyperboloid_two_sheets";
        case QuadricType::elliptic_paraboloid: return "elliptic_paraboloid";
        case QuadricType::hyperbolic_paraboloid: return "hyperbolic_paraboloid";
        case QuadricType::elliptic_cylinder: return "elliptic_cylinder";
        case QuadricType::hyperbolic_cylinder: return "hyperbolic_cylinder";
        case QuadricType::parabolic_cylinder: return "parabolic_cylinder";
        case QuadricType::elliptic_cone: return "elliptic_cone";
        case QuadricType::intersecting_planes: return "intersecting_planes";
        case QuadricType::parallel_planes: return "parallel_planes";
        case QuadricType::empty: return "empty";
    }
    return "unknown";
}

int degrees_of_freedom(QuadricType type) {
    switch (type) {
        case QuadricType::plane: return 3;
        case QuadricType::sphere: return 4;
        case QuadricType::cylinder: return 5;  // axis line 4, radius
        case QuadricType::cone: return 6;      // apex 3, axis 2, angle
        case QuadricType::parabolic_cylinder: return 6;  // vertex line 4, turn about it, curvature
        case QuadricType::elliptic_cylinder:
        case QuadricType::hyperbolic_cylinder: return 7;  // axis line 4, turn about it, two semi-axes
        case QuadricType::intersecting_planes: return 6;
        case QuadricType::parallel_planes: return 4;
        case QuadricType::elliptic_cone: return 8;  // apex 3, rotation 3, two slopes
        case QuadricType::elliptic_paraboloid:
        case QuadricType::hyperbolic_paraboloid: return 8;  // vertex 3, rotation 3, two curvatures
        case QuadricType::ellipsoid:
        case QuadricType::hyperboloid_one_sheet:
        case QuadricType::hyperboloid_two_sheets:
        case QuadricType::empty: return 9;
    }
    return 9;
}

namespace {

bool nearly_equal(double a, double b, double tolerance) {
    return std::abs(a - b) <= tolerance * std::max(std::abs(a), std::abs(b));
}

// Orders the eigen-directions so that the distinguished one is last, keeping a
// right-handed frame.
void put_last(Eigen::Matrix3d& R, Vec3& lambda, int index) {
    if (index == 2) return;
    std::swap(lambda[index], lambda[2]);
    R.col(index).swap(R.col(2));
    R.col(0) = -R.col(0).eval();
}

}  // namespace

Classification classify(const Quadric& f_unit, const Vec3& region_center, double region_radius,
                        const ClassifyOptions& options) {
    Classification out;
    // Local frame: the region centred at the origin with radius 1.
    const Quadric f = change_frame(f_unit, 1.0 / region_radius, -region_center / region_radius);
    const Eigen::Matrix3d A = f.A();
    const Vec3 b = f.b();
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(A);
    Eigen::Matrix3d R = eig.eigenvectors();
    if (R.determinant() < 0) R.col(0) = -R.col(0).eval();
    Vec3 lambda = eig.eigenvalues();
    Vec3 beta = R.transpose() * b;
    const double largest = lambda.cwiseAbs().maxCoeff();

    auto finish = [&](const Vec3& local_center) {
        out.rotation = R;
        out.center = local_center;
        return change_frame(out, region_radius, region_center);
    };

    if (largest <= options.flat * b.norm() || largest == 0) {
        // A plane: f ≈ bᵀ y + c; the point nearest the region's centre.
        const Vec3 n = b.normalized();
        Eigen::Matrix3d frame;
        frame.col(2) = n;
        frame.col(0) = n.unitOrthogonal();
        frame.col(1) = n.cross(frame.col(0));
        R = frame;
        out.type = QuadricType::plane;
        return finish(-f.c[0] / b.norm() * n);
    }

    // Make the majority of the non-zero eigenvalues positive (f and -f are the same surface).
    int zeros = 0, positives = 0;
    for (int i = 0; i < 3; ++i) {
        if (std::abs(lambda[i]) <= options.zero_eigenvalue * largest) ++zeros;
        else if (lambda[i] > 0) ++positives;
    }
    const int rank = 3 - zeros;
    double c0 = f.c[0];
    if (positives * 2 < rank) lambda = -lambda, beta = -beta, c0 = -c0;

    // Complete the squares along the non-zero eigenvalues.
    Vec3 y0 = Vec3::Zero();  // centre in the eigenframe
    double k = c0;
    int zero_axes[3], nz = 0;
    for (int i = 0; i < 3; ++i) {
        if (std::abs(lambda[i]) <= options.zero_eigenvalue * largest) {
            zero_axes[nz++] = i;
            continue;
        }
        y0[i] = -beta[i] / (2 * lambda[i]);
        k -= beta[i] * beta[i] / (4 * lambda[i]);
    }
    double linear2 = 0;
    for (int z = 0; z < nz; ++z) linear2 += beta[zero_axes[z]] * beta[zero_axes[z]];
    const double linear = std::sqrt(linear2);
    const bool has_linear = linear > options.zero_offset * largest;
    const bool has_constant = std::abs(k) > options.zero_offset * largest;

    auto semi = [&](int i, double value) { return std::sqrt(std::abs(value / lambda[i])); };

    if (rank == 3) {
        const Vec3 center = R * y0;
        int negative_axis = -1;
        for (int i = 0; i < 3; ++i)
            if (lambda[i] < 0) negative_axis = i;
        if (negative_axis >= 0) put_last(R, lambda, negative_axis);
        if (!has_constant) {
            if (negative_axis < 0) {
                out.type = QuadricType::empty;  // a single point
                return finish(center);
            }
            // λ0 y0² + λ1 y1² = |λ2| y2²: the cone's opening along each principal axis.
            out.type = nearly_equal(lambda[0], lambda[1], options.equal_eigenvalues) ? QuadricType::cone
                                                                                      : QuadricType::elliptic_cone;
            out.semi_axes = Vec3(std::sqrt(-lambda[2] / lambda[0]), std::sqrt(-lambda[2] / lambda[1]), 1.0);
            out.half_angle = portable::atan(std::sqrt(-lambda[2] / (0.5 * (lambda[0] + lambda[1]))));
            out.nappes_apart = nappes_apart(center, Vec3::Zero(), 1);  // the local frame
            return finish(center);
        }
        for (int i = 0; i < 3; ++i) out.semi_axes[i] = semi(i, k);
        if (negative_axis < 0) {
            if (k > 0) {
                out.type = QuadricType::empty;
                return finish(center);
            }
            const bool round = nearly_equal(lambda.minCoeff(), lambda.maxCoeff(), options.equal_eigenvalues);
            out.type = round ? QuadricType::sphere : QuadricType::ellipsoid;
            out.radius = out.semi_axes.mean();
            return finish(center);
        }
        out.type = k < 0 ? QuadricType::hyperboloid_one_sheet : QuadricType::hyperboloid_two_sheets;
        return finish(center);
    }

    if (has_linear) {
        // Paraboloids and the parabolic cylinder: the linear term's direction is the axis.
        Vec3 axis_local = Vec3::Zero();  // in the eigenframe
        for (int z = 0; z < nz; ++z) axis_local[zero_axes[z]] = beta[zero_axes[z]] / linear;
        // Vertex: where the axis line through y0 meets the surface, f = k + linear * t = 0.
        const Vec3 vertex = R * (y0 - k / linear * axis_local);
        Eigen::Matrix3d frame;
        frame.col(2) = -(R * axis_local);  // opening direction: f decreases along it
        if (rank == 2) {
            int a0 = -1, a1 = -1;
            for (int i = 0; i < 3; ++i)
                if (std::abs(lambda[i]) > options.zero_eigenvalue * largest) (a0 < 0 ? a0 : a1) = i;
            frame.col(0) = R.col(a0);
            frame.col(1) = frame.col(2).cross(frame.col(0));
            out.type = lambda[a0] * lambda[a1] > 0 ? QuadricType::elliptic_paraboloid : QuadricType::hyperbolic_paraboloid;
            out.semi_axes = Vec3(semi(a0, linear), semi(a1, linear), 0);
        } else {
            int a0 = 0;
            for (int i = 0; i < 3; ++i)
                if (std::abs(lambda[i]) > options.zero_eigenvalue * largest) a0 = i;
            frame.col(0) = R.col(a0);
            frame.col(1) = frame.col(2).cross(frame.col(0));
            out.type = QuadricType::parabolic_cylinder;
            out.semi_axes = Vec3(semi(a0, linear), 0, 0);
        }
        R = frame;
        return finish(vertex);
    }

    if (rank == 2) {
        const Vec3 center = R * y0;  // y0 is 0 along the axis: the axis point nearest the region's centre
        put_last(R, lambda, zero_axes[0]);
        const bool same_sign = lambda[0] * lambda[1] > 0;
        if (!has_constant) {
            out.type = same_sign ? QuadricType::empty : QuadricType::intersecting_planes;
            // The planes y0/a = ±y1/b: a and b are what matters, their scale is arbitrary.
            if (!same_sign) out.semi_axes = Vec3(1 / std::sqrt(std::abs(lambda[0])), 1 / std::sqrt(std::abs(lambda[1])), 0);
            return finish(center);
        }
        out.semi_axes = Vec3(semi(0, k), semi(1, k), 0);
        if (same_sign) {
            if (k > 0) {
                out.type = QuadricType::empty;
                return finish(center);
            }
            out.type = nearly_equal(lambda[0], lambda[1], options.equal_eigenvalues) ? QuadricType::cylinder
                                                                                      : QuadricType::elliptic_cylinder;
            out.radius = 0.5 * (out.semi_axes[0] + out.semi_axes[1]);
            return finish(center);
        }
        // Branch axis first: the one whose eigenvalue has the sign opposite to k.
        if ((lambda[0] > 0) == (k > 0)) {
            std::swap(lambda[0], lambda[1]);
            std::swap(out.semi_axes[0], out.semi_axes[1]);
            R.col(0).swap(R.col(1));
            R.col(2) = -R.col(2).eval();
        }
        out.type = QuadricType::hyperbolic_cylinder;
        return finish(center);
    }

    // rank 1: λ (y - y0)² + k
    int a0 = 0;
    for (int i = 0; i < 3; ++i)
        if (std::abs(lambda[i]) > options.zero_eigenvalue * largest) a0 = i;
    const Vec3 n = R.col(a0);
    Eigen::Matrix3d frame;
    frame.col(2) = n;
    frame.col(0) = n.unitOrthogonal();
    frame.col(1) = n.cross(frame.col(0));
    R = frame;
    const Vec3 center = n * y0[a0];
    if (!has_constant) {
        // A double plane: two parallel planes closer than the region's scale resolves
        // (zero separation), the same plane twice or a thin plate's two faces. Callers
        // judge by the faces.
        out.type = QuadricType::parallel_planes;
        return finish(center);
    }
    if (k * lambda[a0] > 0) {
        out.type = QuadricType::empty;
        return finish(center);
    }
    out.type = QuadricType::parallel_planes;
    out.semi_axes = Vec3(0, 0, semi(a0, k));
    return finish(center);
}

Classification change_frame(const Classification& c, double scale, const Vec3& translation) {
    Classification out = c;
    out.center = scale * c.center + translation;
    out.semi_axes = c.semi_axes * scale;
    out.radius = c.radius * scale;
    return out;
}

bool nappes_apart(const Vec3& apex, const Vec3& region_center, double region_radius) {
    return (apex - region_center).norm() > 2 * region_radius;
}

bool has_two_parts(const Classification& c) {
    const QuadricType type = c.type;
    return type == QuadricType::hyperboloid_two_sheets || type == QuadricType::hyperbolic_cylinder ||
           type == QuadricType::intersecting_planes || type == QuadricType::parallel_planes ||
           ((type == QuadricType::cone || type == QuadricType::elliptic_cone) && c.nappes_apart);
}

int part_of(const Classification& c, const Vec3& p, double margin) {
    const Vec3 y = c.rotation.transpose() * (p - c.center);
    double side = 0, separation = 0;
    switch (c.type) {
        case QuadricType::hyperboloid_two_sheets: side = separation = y[2]; break;
        case QuadricType::hyperbolic_cylinder: side = separation = y[0]; break;
        case QuadricType::parallel_planes: side = separation = y[2]; break;
        case QuadricType::cone:
        case QuadricType::elliptic_cone:
            if (!c.nappes_apart) return 0;
            side = separation = y[2];
            break;
        case QuadricType::intersecting_planes: side = y[0] * y[1], separation = std::hypot(y[0], y[1]); break;
        default: return 0;
    }
    if (std::abs(separation) <= margin) return 0;
    return side > 0 ? 1 : side < 0 ? -1 : 0;
}

}  // namespace vqsa
