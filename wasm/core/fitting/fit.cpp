#include "fitting/fit.h"

#include "fitting/classify.h"

#include <Eigen/Eigenvalues>

#include <cmath>
#include <limits>
#include <stdexcept>
#include <utility>

namespace vqsa {

namespace {

// The region seen from its centroid, in units of its RMS radius, with moments divided
// by the area: every entry is O(1), whatever the region's size and place.
struct LocalMoments {
    Moments mean;  // ∫ ((p - center)/radius)^e dA / area
    Vec3 center;
    double radius;
};

LocalMoments localize(const Moments& m) {
    const RegionFrame frame = region_frame(m);
    LocalMoments local{shifted_moments(m, frame.center, frame.radius), frame.center, frame.radius};
    for (double& v : local.mean) v /= m[0];
    return local;
}

Fit to_unit_frame(const Fit& local_fit, const LocalMoments& local) {
    // q_local = (p - center) / radius, i.e. p = radius * q_local + center.
    const double squared_scale = local.radius * local.radius;
    return {normalized(change_frame(local_fit.quadric, local.radius, local.center)), local_fit.mean_squared * squared_scale,
            local_fit.next_mean_squared * squared_scale};
}

// The quadric monomials' exponents, C0..C9.
constexpr int kMonomial[10][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {2, 0, 0},
                                  {1, 1, 0}, {1, 0, 1}, {0, 2, 0}, {0, 1, 1}, {0, 0, 2}};

using Matrix10 = Eigen::Matrix<double, 10, 10>;

// Taubin's two forms over the monomials: M, the mean squared value of a quadric, and N,
// that of its gradient.
std::pair<Matrix10, Matrix10> taubin_forms(const Moments& mu) {
    auto moment = [&](int i, int j, int k) { return mu[moment_index(i, j, k)]; };
    Matrix10 M, N;
    for (int a = 0; a < 10; ++a)
        for (int b = 0; b < 10; ++b) {
            M(a, b) = moment(kMonomial[a][0] + kMonomial[b][0], kMonomial[a][1] + kMonomial[b][1],
                             kMonomial[a][2] + kMonomial[b][2]);
            // ∫ ∇v_a · ∇v_b: each partial derivative is a coefficient times a monomial.
            double n = 0;
            for (int axis = 0; axis < 3; ++axis) {
                if (kMonomial[a][axis] == 0 || kMonomial[b][axis] == 0) continue;
                int e[3];
                for (int k = 0; k < 3; ++k) e[k] = kMonomial[a][k] + kMonomial[b][k] - (k == axis ? 2 : 0);
                n += kMonomial[a][axis] * kMonomial[b][axis] * moment(e[0], e[1], e[2]);
            }
            N(a, b) = n;
        }
    return {M, N};
}

// Taubin's problem with C0 eliminated (it has no gradient): C0 = -m0ᵀ s̃ / m00 with m00 = 1.
struct ReducedTaubin {
    Eigen::Matrix<double, 9, 1> m0;
    Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::Matrix<double, 9, 9>> solver;

    // The quadric of eigenvector `k`, C0 restored.
    Eigen::Matrix<double, 10, 1> coefficients(int k) const {
        const Eigen::Matrix<double, 9, 1> s = solver.eigenvectors().col(k);
        Eigen::Matrix<double, 10, 1> c;
        c[0] = -m0.dot(s);
        c.tail<9>() = s;
        return c;
    }
};

ReducedTaubin solve_reduced(const Matrix10& M, const Matrix10& N, double regularization) {
    ReducedTaubin out;
    out.m0 = M.block<9, 1>(1, 0);
    Eigen::Matrix<double, 9, 9> reduced = M.block<9, 9>(1, 1) - out.m0 * out.m0.transpose();
    Eigen::Matrix<double, 9, 9> gradient = N.block<9, 9>(1, 1);
    gradient.diagonal().array() += regularization * gradient.trace() / 9.0;
    reduced = 0.5 * (reduced + reduced.transpose()).eval();
    out.solver.compute(reduced, gradient);
    if (out.solver.info() != Eigen::Success) throw std::runtime_error("quadric fit: the eigen solver failed");
    return out;
}

Quadric quadric_of(const Eigen::Matrix<double, 10, 1>& c) {
    Quadric q;
    for (int i = 0; i < 10; ++i) q.c[i] = c[i];
    return q;
}

Fit taubin_local(const LocalMoments& local, double regularization) {
    const auto [M, N] = taubin_forms(local.mean);
    const ReducedTaubin taubin = solve_reduced(M, N, regularization);
    const auto& eigenvalues = taubin.solver.eigenvalues();
    return {quadric_of(taubin.coefficients(0)), std::max(0.0, eigenvalues[0]), std::max(0.0, eigenvalues[1])};
}

// E[q qᵀ] over the region, q about its centroid (its covariance).
Eigen::Matrix3d second_moments(const LocalMoments& local) {
    Eigen::Matrix3d m;
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) {
            int e[3] = {0, 0, 0};
            ++e[r], ++e[c];
            m(r, c) = local.mean[moment_index(e[0], e[1], e[2])];
        }
    return m;
}

Fit plane_local(const LocalMoments& local) {
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(second_moments(local));
    return {Quadric::plane(solver.eigenvectors().col(0), Vec3::Zero()), std::max(0.0, solver.eigenvalues()[0])};
}

// E[(n·q)⁴] / E[(n·q)²]² over the region, q about its centroid: from the degree-4 moments.
double residual_kurtosis(const LocalMoments& local, const Vec3& n) {
    double e2 = 0, e4 = 0;
    for (int i = 0; i <= 4; ++i)
        for (int j = 0; i + j <= 4; ++j) {
            const int k4 = 4 - i - j;
            static const double factorial[] = {1, 1, 2, 6, 24};
            e4 += 24 / (factorial[i] * factorial[j] * factorial[k4]) * std::pow(n.x(), i) * std::pow(n.y(), j) *
                  std::pow(n.z(), k4) * local.mean[moment_index(i, j, k4)];
        }
    for (int i = 0; i <= 2; ++i)
        for (int j = 0; i + j <= 2; ++j) {
            const int k2 = 2 - i - j;
            static const double factorial[] = {1, 1, 2};
            e2 += 2 / (factorial[i] * factorial[j] * factorial[k2]) * std::pow(n.x(), i) * std::pow(n.y(), j) *
                  std::pow(n.z(), k2) * local.mean[moment_index(i, j, k2)];
        }
    return e2 > 0 ? e4 / (e2 * e2) : 3;
}

// The mean squared distance of the region to the plane n·q = d (n a unit vector), in its
// local frame, whose origin is the region's centroid.
double plane_mean_squared(const LocalMoments& local, const Vec3& n, double d) {
    return std::max(0.0, n.dot(second_moments(local) * n) + d * d);
}

// Whether one plane of `shape`, a pair of intersecting planes (in the local frame), holds
// the region about as well as its plane fit does.
bool one_plane_of_pair(const LocalMoments& local, const Classification& shape, const Fit& plane,
                       const FitOptions& options) {
    if (shape.type != QuadricType::intersecting_planes) return false;
    const double bound = (1 + options.plane_tolerance) * plane.mean_squared +
                         options.negligible_distance * options.negligible_distance;
    for (double sign : {-1.0, 1.0}) {
        const Vec3 n = (shape.rotation * Vec3(1 / shape.semi_axes.x(), sign / shape.semi_axes.y(), 0)).normalized();
        if (plane_mean_squared(local, n, n.dot(shape.center)) <= bound) return true;
    }
    return false;
}

}  // namespace

RegionFrame region_frame(const Moments& m) {
    const double area = m[0];
    if (!(area > 0)) throw std::invalid_argument("cannot fit a region of zero area");
    RegionFrame frame{Vec3(m[1], m[2], m[3]) / area, 1.0};
    const Moments centred = shifted_moments(m, frame.center, 1.0);
    const double spread =
        (centred[moment_index(2, 0, 0)] + centred[moment_index(0, 2, 0)] + centred[moment_index(0, 0, 2)]) / area;
    if (spread > 0) frame.radius = std::sqrt(spread);
    return frame;
}

Fit fit_taubin(const Moments& region) {
    const LocalMoments local = localize(region);
    return to_unit_frame(taubin_local(local, FitOptions{}.regularization), local);
}

Fit fit_taubin_through(const Moments& points, const Moments& faces, double on) {
    const LocalMoments local = localize(points);
    Moments face_mean = shifted_moments(faces, local.center, local.radius);
    for (double& v : face_mean) v /= faces[0];
    const auto [Mp, Np] = taubin_forms(local.mean);
    // (Named, not bound: a lambda below uses them, and C++17 lambdas cannot capture bindings.)
    const std::pair<Matrix10, Matrix10> face_forms = taubin_forms(face_mean);
    const Matrix10 &Mf = face_forms.first, &Nf = face_forms.second;
    // The quadrics through the points: Taubin's eigenvectors within `on` of them.
    const ReducedTaubin taubin = solve_reduced(Mp, Np, FitOptions{}.regularization);
    const double squared_scale = local.radius * local.radius;
    int count = 0;
    while (count < 9 && taubin.solver.eigenvalues()[count] * squared_scale <= on) ++count;
    constexpr double kNone = std::numeric_limits<double>::infinity();
    if (count == 0) return {Quadric{}, kNone, kNone};
    Eigen::MatrixXd through(10, count);
    for (int j = 0; j < count; ++j) through.col(j) = taubin.coefficients(j);
    // Among them, Taubin's fit to the faces.
    Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> faces_solver;
    Eigen::MatrixXd B;  // the gradient form over the faces
    auto fit_faces = [&] {
        const Eigen::MatrixXd A = through.transpose() * Mf * through;
        B = through.transpose() * Nf * through;
        B = 0.5 * (B + B.transpose()).eval();
        faces_solver.compute(0.5 * (A + A.transpose()), B);
        return faces_solver.info() == Eigen::Success;
    };
    if (!fit_faces()) {
        // A combination of the quadrics through the points may have no gradient on the faces
        // (the gradient form singular: a run of exact pieces of a printed part). It has no
        // distance to them to rank; the fit is sought among the others, in the form's range.
        const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> gradient(B);
        const Eigen::VectorXd& scale = gradient.eigenvalues();  // ascending
        int first = 0;
        while (first < count && !(scale[first] > 1e-12 * scale[count - 1])) ++first;
        if (first == count) return {Quadric{}, kNone, kNone};
        count -= first;
        const Eigen::VectorXd unit = scale.tail(count).cwiseSqrt().cwiseInverse();
        through = (through * gradient.eigenvectors().rightCols(count) * unit.asDiagonal()).eval();
        if (!fit_faces()) return {Quadric{}, kNone, kNone};
    }
    const Eigen::Matrix<double, 10, 1> c = through * faces_solver.eigenvectors().col(0);
    const double next = count > 1 ? std::max(0.0, faces_solver.eigenvalues()[1]) : kNone;
    return to_unit_frame({quadric_of(c), std::max(0.0, faces_solver.eigenvalues()[0]), next}, local);
}

Fit fit_plane(const Moments& region) {
    const LocalMoments local = localize(region);
    return to_unit_frame(plane_local(local), local);
}

Vec3 principal_variances(const Moments& region) {
    const LocalMoments local = localize(region);
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(second_moments(local), Eigen::EigenvaluesOnly);
    return solver.eigenvalues().cwiseMax(0.0) * (local.radius * local.radius);
}

Fit fit_region(const Moments& region, const FitOptions& options) {
    const LocalMoments local = localize(region);
    const Fit plane = plane_local(local);
    const Fit quadric = taubin_local(local, options.regularization);
    const double negligible = options.negligible_distance * options.negligible_distance;
    // A double plane (n·p − d)² always looks better than the plane: its first-order
    // distance is half the true one, so under noise it wins the comparison. It is the
    // plane, counted twice.
    // Parallel planes whose distances from the mid-plane are not two-humped (kurtosis of
    // the plane's residuals above 2: 3 for Gaussian noise about one plane, 1 for two
    // planes) are one noisy plane too: the fit split its noise in two.
    const Classification shape = classify(quadric.quadric, Vec3::Zero(), 1.0);
    const bool double_plane = shape.type == QuadricType::parallel_planes &&
                              (shape.semi_axes.z() == 0 || residual_kurtosis(local, plane.quadric.b()) > 2);
    const bool prefer_plane = double_plane ||
                              plane.mean_squared <= (1 + options.plane_tolerance) * quadric.mean_squared + negligible ||
                              (options.plane_of_pair && one_plane_of_pair(local, shape, plane, options));
    const Fit& best = prefer_plane ? plane : quadric;
    return to_unit_frame(best, local);
}

}  // namespace vqsa
