#include "fitting/special_fit.h"

#include "fitting/distance.h"

#include "fitting/least_squares.h"
#include "geometry/portable_math.h"

#include <Eigen/Dense>

#include <cmath>

namespace vqsa {

namespace {

Eigen::Matrix3d frame_with_axis(const Vec3& axis) {
    Eigen::Matrix3d r;
    r.col(2) = axis.normalized();
    r.col(0) = r.col(2).unitOrthogonal();
    r.col(1) = r.col(2).cross(r.col(0));
    return r;
}

// The normal of the samples' least-squares plane through `centroid`, their weighted centroid.
Vec3 plane_normal(const Samples& s, const Vec3& centroid) { return principal_axes(s, centroid).col(0); }

// The fit that is `shape`: its quadric and its RMS orthogonal distance to the samples.
SpecialFit fit_of(const Classification& shape, const Samples& s) {
    SpecialFit fit;
    fit.shape = shape;
    fit.quadric = special_quadric(shape);
    fit.rms = weighted_rms(s, [&](const Vec3& p) { return special_distance(shape, p); });
    return fit;
}

}  // namespace

bool has_closed_form(QuadricType type) {
    return type == QuadricType::plane || type == QuadricType::sphere || type == QuadricType::cylinder ||
           type == QuadricType::cone;
}

double special_distance(const Classification& shape, const Vec3& p) {
    const Vec3 d = p - shape.center;
    const Vec3 u = shape.axis();
    switch (shape.type) {
        case QuadricType::plane: return std::abs(d.dot(u));
        case QuadricType::sphere: return std::abs(d.norm() - shape.radius);
        case QuadricType::cylinder: return std::abs((d - d.dot(u) * u).norm() - shape.radius);
        case QuadricType::cone: {
            // In the half-plane through the axis: distance to the generator on p's nappe,
            // or to the apex when p lies beyond it.
            const double h = d.dot(u), rho = (d - h * u).norm();
            const double c = portable::cos(shape.half_angle), s = portable::sin(shape.half_angle);
            const double along = std::abs(h) * c + rho * s;
            return along >= 0 ? std::abs(rho * c - std::abs(h) * s) : d.norm();
        }
        case QuadricType::elliptic_paraboloid: return taubin_distance(special_quadric(shape), p);
        default: throw std::invalid_argument("special_distance: not a special type");
    }
}

Quadric special_quadric(const Classification& shape) {
    const Vec3 u = shape.axis(), c = shape.center;
    const Eigen::Matrix3d P = Eigen::Matrix3d::Identity() - u * u.transpose();
    Eigen::Matrix3d A;
    double k = 0;
    switch (shape.type) {
        case QuadricType::plane: return normalized(Quadric::plane(u, c));
        case QuadricType::sphere: A = Eigen::Matrix3d::Identity(), k = -shape.radius * shape.radius; break;
        case QuadricType::cylinder: A = P, k = -shape.radius * shape.radius; break;
        case QuadricType::cone: {
            const double co = portable::cos(shape.half_angle), s = portable::sin(shape.half_angle);
            A = co * co * P - s * s * u * u.transpose();
            break;
        }
        case QuadricType::elliptic_paraboloid: {
            // z' = x'²/a² + y'²/b² about the vertex.
            const Eigen::Matrix3d& R = shape.rotation;
            const double k1 = 1 / (shape.semi_axes[0] * shape.semi_axes[0]), k2 = 1 / (shape.semi_axes[1] * shape.semi_axes[1]);
            A = k1 * R.col(0) * R.col(0).transpose() + k2 * R.col(1) * R.col(1).transpose();
            return normalized(Quadric::from(A, -R.col(2) - 2 * A * c, c.dot(A * c) + R.col(2).dot(c)));
        }
        default: throw std::invalid_argument("special_quadric: not a special type");
    }
    // (p - c)ᵀ A (p - c) + k
    return normalized(Quadric::from(A, -2 * A * c, c.dot(A * c) + k));
}

std::optional<SpecialFit> fit_plane_geometric(const Samples& s) {
    const Vec3 c = weighted_centroid(s);
    Classification shape;
    shape.type = QuadricType::plane;
    shape.center = c;
    shape.rotation = frame_with_axis(plane_normal(s, c));
    return fit_of(shape, s);
}

std::optional<SpecialFit> fit_sphere_geometric(const Samples& s) {
    // Algebraic start: |p|² = 2 c·p + k, then orthogonal distances.
    Eigen::Matrix4d AtA = Eigen::Matrix4d::Zero();
    Eigen::Vector4d Atb = Eigen::Vector4d::Zero();
    const Vec3 origin = weighted_centroid(s);
    for (std::size_t i = 0; i < s.points.size(); ++i) {
        const Vec3 p = s.points[i] - origin;
        const Eigen::Vector4d row(2 * p.x(), 2 * p.y(), 2 * p.z(), 1);
        AtA += s.weights[i] * row * row.transpose();
        Atb += s.weights[i] * row * p.squaredNorm();
    }
    const Eigen::Vector4d x = AtA.ldlt().solve(Atb);
    const double r2 = x[3] + x.head<3>().squaredNorm();
    if (!(r2 > 0) || !x.allFinite()) return std::nullopt;
    Eigen::Vector4d theta(origin.x() + x[0], origin.y() + x[1], origin.z() + x[2], std::sqrt(r2));
    theta = least_squares<4>(
        s, theta,
        [](const Eigen::Vector4d& t) {
            const Vec3 c = t.head<3>();
            const double r = t[3];
            return [c, r](const Vec3& p) { return (p - c).norm() - r; };
        },
        std::sqrt(r2));
    Classification shape;
    shape.type = QuadricType::sphere;
    shape.center = theta.head<3>();
    shape.radius = std::abs(theta[3]);
    return fit_of(shape, s);
}

std::optional<SpecialFit> fit_cylinder_geometric(const Samples& s, const Vec3& axis_guess) {
    // Start: a circle fitted to the samples projected along the guessed axis.
    const Eigen::Matrix3d frame = frame_with_axis(axis_guess);
    const Vec3 origin = weighted_centroid(s);
    Eigen::Matrix3d AtA = Eigen::Matrix3d::Zero();
    Vec3 Atb = Vec3::Zero();
    for (std::size_t i = 0; i < s.points.size(); ++i) {
        const Vec3 q = frame.transpose() * (s.points[i] - origin);
        const Vec3 row(2 * q.x(), 2 * q.y(), 1);
        AtA += s.weights[i] * row * row.transpose();
        Atb += s.weights[i] * row * (q.x() * q.x() + q.y() * q.y());
    }
    const Vec3 x = AtA.ldlt().solve(Atb);
    const double r2 = x[2] + x[0] * x[0] + x[1] * x[1];
    if (!(r2 > 0) || !x.allFinite()) return std::nullopt;
    const Vec3 start = origin + frame.col(0) * x[0] + frame.col(1) * x[1];
    // θ: axis tilt (2), axis offset (2) in the start frame, radius.
    auto unpack = [&](const Eigen::Matrix<double, 5, 1>& t, Vec3& point, Vec3& axis) {
        axis = (frame.col(2) + t[0] * frame.col(0) + t[1] * frame.col(1)).normalized();
        point = start + t[2] * frame.col(0) + t[3] * frame.col(1);
    };
    Eigen::Matrix<double, 5, 1> theta;
    theta << 0, 0, 0, 0, std::sqrt(r2);
    theta = least_squares<5>(
        s, theta,
        [&](const Eigen::Matrix<double, 5, 1>& t) {
            Vec3 point, axis;
            unpack(t, point, axis);
            const double r = t[4];
            return [point, axis, r](const Vec3& p) {
                const Vec3 d = p - point;
                return (d - d.dot(axis) * axis).norm() - r;
            };
        },
        std::sqrt(r2));
    Vec3 point, axis;
    unpack(theta, point, axis);
    Classification shape;
    shape.type = QuadricType::cylinder;
    shape.rotation = frame_with_axis(axis);
    shape.center = point + (origin - point).dot(axis) * axis;  // the axis point nearest the region
    shape.radius = std::abs(theta[4]);
    return fit_of(shape, s);
}

std::optional<SpecialFit> fit_cone_geometric(const Samples& s, const Vec3& axis_guess, const Vec3& apex_guess) {
    const Eigen::Matrix3d frame = frame_with_axis(axis_guess);
    // Start: with the guessed axis line, fit ρ = m h + q over the samples (one nappe).
    double sw = 0, sh = 0, sr = 0, shh = 0, shr = 0;
    for (std::size_t i = 0; i < s.points.size(); ++i) {
        const Vec3 d = s.points[i] - apex_guess;
        const double h = d.dot(frame.col(2)), rho = (d - h * frame.col(2)).norm(), w = s.weights[i];
        sw += w, sh += w * h, sr += w * rho, shh += w * h * h, shr += w * h * rho;
    }
    const double det = sw * shh - sh * sh;
    if (!(std::abs(det) > 0)) return std::nullopt;
    double m = (sw * shr - sh * sr) / det, q = (sr - m * sh) / sw;
    Vec3 axis = frame.col(2);
    if (m < 0) m = -m, axis = -axis;  // open along +axis: ρ = m h' + q with h' = -h
    if (!(m > 1e-6) || !std::isfinite(q)) return std::nullopt;
    const Vec3 apex = apex_guess - (q / m) * axis;
    const double scale = std::sqrt(sr / sw) + 1e-12;
    // θ: axis tilt (2), apex offset (3), slope tan(half-angle). The slope rather than the
    // angle keeps sin and cos (whose last bits differ between C libraries) out of the
    // iteration, so native and WASM builds converge to the same cone.
    auto unpack = [&](const Eigen::Matrix<double, 6, 1>& t, Vec3& a, Vec3& u) {
        u = (axis + t[0] * frame.col(0) + t[1] * frame.col(1)).normalized();
        a = apex + Vec3(t[2], t[3], t[4]);
    };
    Eigen::Matrix<double, 6, 1> theta;
    theta << 0, 0, 0, 0, 0, m;
    theta = least_squares<6>(
        s, theta,
        [&](const Eigen::Matrix<double, 6, 1>& t) {
            Vec3 a, u;
            unpack(t, a, u);
            const double slope = t[5], cosine = 1 / std::sqrt(1 + slope * slope);
            return [a, u, slope, cosine](const Vec3& p) {
                const Vec3 d = p - a;
                const double h = d.dot(u), rho = (d - h * u).norm();
                return (rho - std::abs(h) * slope) * cosine;
            };
        },
        scale);
    Vec3 a, u;
    unpack(theta, a, u);
    const double alpha = portable::atan(theta[5]);
    if (!(alpha > 1e-4 && alpha < M_PI / 2 - 1e-4)) return std::nullopt;
    Classification shape;
    shape.type = QuadricType::cone;
    shape.center = a;
    shape.rotation = frame_with_axis(u);
    shape.half_angle = alpha;
    return fit_of(shape, s);
}

std::optional<SpecialFit> fit_paraboloid_geometric(const Samples& s, const Vec3& axis_guess) {
    const Vec3 origin = weighted_centroid(s);
    double spread = 0;
    for (std::size_t i = 0; i < s.points.size(); ++i) spread += s.weights[i] * (s.points[i] - origin).squaredNorm();
    const double scale = std::sqrt(spread / s.total_weight) + 1e-300;
    // A start: the heights over the plane ⊥ `axis` through the centroid, fitted by a
    // quadratic; its principal axes and curvatures, and its apex.
    struct Start {
        Vec3 apex;
        Eigen::Matrix3d frame;
        Eigen::Vector2d curvatures;
    };
    auto start_along = [&](const Vec3& axis) -> std::optional<Start> {
        const Eigen::Matrix3d frame = frame_with_axis(axis);
        Eigen::Matrix<double, 6, 6> AtA = Eigen::Matrix<double, 6, 6>::Zero();
        Eigen::Matrix<double, 6, 1> Atb = Eigen::Matrix<double, 6, 1>::Zero();
        for (std::size_t i = 0; i < s.points.size(); ++i) {
            const Vec3 q = frame.transpose() * (s.points[i] - origin);
            Eigen::Matrix<double, 6, 1> row;
            row << q.x() * q.x(), q.x() * q.y(), q.y() * q.y(), q.x(), q.y(), 1;
            AtA += s.weights[i] * row * row.transpose();
            Atb += s.weights[i] * row * q.z();
        }
        const Eigen::Matrix<double, 6, 1> c = AtA.ldlt().solve(Atb);
        if (!c.allFinite()) return std::nullopt;
        Eigen::Matrix2d H;
        H << c[0], 0.5 * c[1], 0.5 * c[1], c[2];
        Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eig(H);
        if (!(eig.eigenvalues()[0] * eig.eigenvalues()[1] > 0)) return std::nullopt;  // not elliptic
        const Eigen::Vector2d apex2 = H.ldlt().solve(-0.5 * Eigen::Vector2d(c[3], c[4]));
        const double apex_z = c[5] + 0.5 * Eigen::Vector2d(c[3], c[4]).dot(apex2);
        Start start;
        start.frame.col(0) = frame * Vec3(eig.eigenvectors()(0, 0), eig.eigenvectors()(1, 0), 0);
        start.frame.col(2) = frame.col(2);
        start.frame.col(1) = start.frame.col(2).cross(start.frame.col(0));
        start.apex = origin + frame * Vec3(apex2.x(), apex2.y(), apex_z);
        start.curvatures = eig.eigenvalues();
        if (!start.apex.allFinite()) return std::nullopt;
        return start;
    };
    // θ: apex offset (3), axis tilt (2), turn about the axis (1), curvatures (2), from a start.
    auto unpack = [](const Start& start, const Eigen::Matrix<double, 8, 1>& t, Classification& shape) {
        const Vec3 axis = (start.frame.col(2) + t[3] * start.frame.col(0) + t[4] * start.frame.col(1)).normalized();
        Vec3 x = (start.frame.col(0) + t[5] * start.frame.col(1));
        x = (x - x.dot(axis) * axis).normalized();
        shape.type = QuadricType::elliptic_paraboloid;
        shape.center = start.apex + Vec3(t[0], t[1], t[2]);
        shape.rotation.col(0) = x;
        shape.rotation.col(2) = axis;
        shape.rotation.col(1) = axis.cross(x);
        shape.semi_axes = Vec3(t[6], t[7], 0);  // curvatures while fitting
    };
    auto quadric_of = [](const Classification& shape) {
        // z' = k1 x'² + k2 y'²: f = k1 x'² + k2 y'² − z' in the shape's frame.
        const Eigen::Matrix3d& R = shape.rotation;
        const Eigen::Matrix3d A = shape.semi_axes[0] * R.col(0) * R.col(0).transpose() +
                                  shape.semi_axes[1] * R.col(1) * R.col(1).transpose();
        const Vec3 b = -R.col(2) - 2 * A * shape.center;
        return Quadric::from(A, b, shape.center.dot(A * shape.center) + R.col(2).dot(shape.center));
    };
    auto at_start = [](const Start& start) {
        Eigen::Matrix<double, 8, 1> theta;
        theta << 0, 0, 0, 0, 0, 0, start.curvatures[0], start.curvatures[1];
        return theta;
    };
    auto start_rms = [&](const Start& start) {
        Classification shape;
        unpack(start, at_start(start), shape);
        return taubin_rms(s, quadric_of(shape));
    };
    // Whether the region curves like a paraboloid at all, the general quadric's direction
    // of linearity says. But where the quadric is nearly a sphere, every direction is about
    // as flat and that axis is arbitrary: Levenberg–Marquardt then spent its 50 iterations
    // turning it. The heights over the samples' own plane (a cap's axis) start too, and the
    // start nearer the samples is descended.
    std::optional<Start> start = start_along(axis_guess);
    if (!start) return std::nullopt;
    const std::optional<Start> over_plane = start_along(plane_normal(s, origin));
    if (over_plane && start_rms(*over_plane) < start_rms(*start)) start = over_plane;
    const Eigen::Matrix<double, 8, 1> theta = least_squares<8>(
        s, at_start(*start),
        [&](const Eigen::Matrix<double, 8, 1>& t) {
            Classification shape;
            unpack(*start, t, shape);
            const Quadric q = quadric_of(shape);
            const double a = q.hessian_norm();
            return [q, a](const Vec3& p) { return taubin_distance(q, a, p); };
        },
        scale);
    SpecialFit fit;
    unpack(*start, theta, fit.shape);
    if (!(fit.shape.semi_axes[0] * fit.shape.semi_axes[1] > 0)) return std::nullopt;
    const Quadric q = quadric_of(fit.shape);
    // Report semi-axes as the classification does: √(1/|k|).
    fit.shape.semi_axes = Vec3(1 / std::sqrt(std::abs(fit.shape.semi_axes[0])), 1 / std::sqrt(std::abs(fit.shape.semi_axes[1])), 0);
    fit.quadric = normalized(q);
    fit.rms = taubin_rms(s, q);
    return fit;
}

}  // namespace vqsa
