#include "post/project.h"

#include "geometry/portable_math.h"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <array>
#include <complex>
#include <limits>
#include <cmath>

namespace vqsa {

namespace {

using Poly = std::array<double, 7>;  // coefficients, lowest degree first

Poly multiply(const Poly& a, double c0, double c1) {
    Poly out{};
    for (int k = 0; k < 7; ++k) {
        out[k] += a[k] * c0;
        if (k + 1 < 7) out[k + 1] += a[k] * c1;
    }
    return out;
}

double evaluate(const Poly& a, double x) {
    double v = 0;
    for (int k = 6; k >= 0; --k) v = v * x + a[k];
    return v;
}

double derivative(const Poly& a, double x) {
    double v = 0;
    for (int k = 6; k >= 1; --k) v = v * x + k * a[k];
    return v;
}

// Newton steps onto {f = 0} along the gradient: removes the last rounding of a foot point.
Vec3 polish(const Quadric& f, Vec3 x) {
    for (int i = 0; i < 3; ++i) {
        const Vec3 g = f.gradient(x);
        const double g2 = g.squaredNorm();
        if (!(g2 > 0)) break;
        x -= f.value(x) / g2 * g;
    }
    return x;
}

}  // namespace

FootPoint::FootPoint(const Quadric& f) : f_(f) {
    if (f.is_plane()) return;
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(f.A());
    R_ = eig.eigenvectors();
    lambda_ = eig.eigenvalues();
}

std::optional<Vec3> foot_point(const Quadric& f, const Vec3& p) { return FootPoint(f)(p); }

std::optional<Vec3> FootPoint::operator()(const Vec3& p) const {
    if (f_.is_plane()) {
        const Vec3 n = f_.b();
        return p - (f_.value(p) / n.squaredNorm()) * n;
    }
    const Vec3 beta = R_.transpose() * f_.b(), y = R_.transpose() * p;
    const double c = f_.c[0];
    const double inf = std::numeric_limits<double>::infinity();
    // The interval where every 1 + μ λ_i > 0.
    double lo = -inf, hi = inf;
    for (int i = 0; i < 3; ++i) {
        if (lambda_[i] > 0) lo = std::max(lo, -1 / lambda_[i]);
        if (lambda_[i] < 0) hi = std::min(hi, -1 / lambda_[i]);
    }
    Vec3 x;
    auto F = [&](double mu, double* slope) {
        double value = c, derivative = 0;
        for (int i = 0; i < 3; ++i) {
            const double D = 1 + mu * lambda_[i];
            x[i] = (y[i] - 0.5 * mu * beta[i]) / D;
            const double g = lambda_[i] * x[i] + 0.5 * beta[i];  // half the gradient
            value += (lambda_[i] * x[i] + beta[i]) * x[i];
            derivative -= 2 * g * g / D;
        }
        if (slope) *slope = derivative;
        return value;
    };
    double slope;
    const double f0 = F(0, &slope);
    if (f0 == 0) return p;
    // Bracket the root on the side F's sign points to: F decreases.
    double a = 0, b = f0 > 0 ? hi : lo;
    if (!std::isfinite(b)) {
        double step = slope < 0 ? std::abs(f0 / slope) : 1;
        bool found = false;
        for (int k = 0; k < 200 && !found; ++k, step *= 4) {
            const double mu = f0 > 0 ? step : -step;
            const double v = F(mu, nullptr);
            if (!std::isfinite(v)) break;
            if ((v > 0) == (f0 > 0)) a = mu; else b = mu, found = true;
        }
        if (!found) return by_polynomial(p);
    }
    // Newton inside [a, b] (a on f0's side), bisection when a step leaves it.
    double mu = a;
    bool converged = false;
    for (int it = 0; it < 100; ++it) {
        const double v = F(mu, &slope);
        if (v == 0) { converged = true; break; }
        if ((v > 0) == (f0 > 0)) a = mu; else b = mu;
        double next = slope != 0 ? mu - v / slope : 0.5 * (a + b);
        const bool inside = f0 > 0 ? next > a && next < b : next < a && next > b;
        if (!inside) next = 0.5 * (a + b);
        if (std::abs(next - mu) <= 1e-15 * (1 + std::abs(next))) { mu = next; converged = true; break; }
        mu = next;
    }
    F(mu, nullptr);
    bool at_pole = false;
    for (int i = 0; i < 3; ++i) at_pole = at_pole || std::abs(1 + mu * lambda_[i]) < 1e-9;
    if (at_pole) {
        // The hard case: p lies where the directions of the bounding eigenvalue meet the
        // centre (a symmetry axis or plane), F keeps its sign up to the pole, and there x
        // is free along those directions: f(x) = 0 fixes how far.
        const double pole = f0 > 0 ? hi : lo;
        if (!std::isfinite(pole)) return by_polynomial(p);
        const double lj = -1 / pole;
        double rest = c;
        int free_axis = -1;
        for (int i = 0; i < 3; ++i) {
            const double D = 1 + pole * lambda_[i];
            if (std::abs(D) < 1e-9) {
                x[i] = -0.5 * beta[i] / lj;  // the centre along this direction
                if (free_axis < 0) free_axis = i;
            } else {
                x[i] = (y[i] - 0.5 * pole * beta[i]) / D;
            }
            rest += (lambda_[i] * x[i] + beta[i]) * x[i];
        }
        // λ_j (x_j − x_j⁰)² = −f(x⁰) along the free axis.
        const double squared = -rest / lj;
        if (free_axis < 0 || squared < 0) return by_polynomial(p);
        x[free_axis] += std::sqrt(squared);
        converged = true;
    }
    if (!converged || !x.allFinite()) return by_polynomial(p);
    const Vec3 foot = polish(f_, R_ * x);
    if (!foot.allFinite()) return by_polynomial(p);
    return foot;
}

std::optional<Vec3> FootPoint::by_polynomial(const Vec3& p) const {
    if (f_.is_plane()) return (*this)(p);
    const Quadric& f = f_;
    const Eigen::Matrix3d& R = R_;
    const Vec3& lambda = lambda_;
    const Vec3 beta = R.transpose() * f.b(), y = R.transpose() * p;
    const double c = f.c[0];

    // P(μ) = Σ λ_i N_i² Π_{j≠i} D_j² + Σ β_i N_i D_i Π_{j≠i} D_j² + c Π D_j²,
    // N_i = y_i − μ β_i / 2, D_i = 1 + μ λ_i.
    Poly P{};
    for (int i = 0; i < 3; ++i) {
        Poly others{};
        others[0] = 1;
        for (int j = 0; j < 3; ++j)
            if (j != i) others = multiply(multiply(others, 1, lambda[j]), 1, lambda[j]);
        const Poly quadratic = multiply(multiply(others, y[i], -0.5 * beta[i]), y[i], -0.5 * beta[i]);
        const Poly linear = multiply(multiply(others, y[i], -0.5 * beta[i]), 1, lambda[i]);
        for (int k = 0; k < 7; ++k) P[k] += lambda[i] * quadratic[k] + beta[i] * linear[k];
    }
    Poly all{};
    all[0] = 1;
    for (int j = 0; j < 3; ++j) all = multiply(multiply(all, 1, lambda[j]), 1, lambda[j]);
    for (int k = 0; k < 7; ++k) P[k] += c * all[k];

    double largest = 0;
    for (double a : P) largest = std::max(largest, std::abs(a));
    int degree = 6;
    while (degree > 0 && std::abs(P[degree]) <= 1e-14 * largest) --degree;

    std::vector<double> roots;
    if (degree == 1) {
        roots.push_back(-P[0] / P[1]);
    } else if (degree > 1) {
        Eigen::MatrixXd companion = Eigen::MatrixXd::Zero(degree, degree);
        for (int k = 0; k < degree; ++k) companion(0, k) = -P[degree - 1 - k] / P[degree];
        for (int k = 1; k < degree; ++k) companion(k, k - 1) = 1;
        Eigen::EigenSolver<Eigen::MatrixXd> solver(companion, false);
        for (int k = 0; k < degree; ++k) {
            const std::complex<double> r = solver.eigenvalues()[k];
            if (std::abs(r.imag()) <= 1e-6 * (1 + std::abs(r.real()))) roots.push_back(r.real());
        }
    }

    std::optional<Vec3> best;
    double best_distance = std::numeric_limits<double>::infinity();
    for (double mu : roots) {
        for (int it = 0; it < 8; ++it) {  // Newton on P
            const double d = derivative(P, mu);
            if (d == 0) break;
            const double step = evaluate(P, mu) / d;
            mu -= step;
            if (std::abs(step) <= 1e-15 * (1 + std::abs(mu))) break;
        }
        Vec3 x;
        bool pole = false;
        for (int i = 0; i < 3; ++i) {
            const double D = 1 + mu * lambda[i];
            if (std::abs(D) < 1e-12) pole = true;
            x[i] = (y[i] - 0.5 * mu * beta[i]) / D;
        }
        if (pole || !x.allFinite()) continue;
        const Vec3 candidate = polish(f, R * x);
        const double distance = (candidate - p).norm();
        if (candidate.allFinite() && distance < best_distance) best_distance = distance, best = candidate;
    }
    return best;
}

Vec3 special_foot_point(const Classification& shape, const Vec3& p) {
    const Vec3 u = shape.axis(), d = p - shape.center;
    switch (shape.type) {
        case QuadricType::plane: return p - d.dot(u) * u;
        case QuadricType::sphere: {
            const double r = d.norm();
            return r > 0 ? shape.center + shape.radius / r * d : shape.center + shape.radius * u;
        }
        case QuadricType::cylinder: {
            const Vec3 on_axis = shape.center + d.dot(u) * u;
            Vec3 radial = p - on_axis;
            const double r = radial.norm();
            radial = r > 0 ? Vec3(radial / r) : Vec3(shape.rotation.col(0));
            return on_axis + shape.radius * radial;
        }
        case QuadricType::cone: {
            // In the half-plane through the axis and p: the generator of p's nappe.
            const double h = d.dot(u);
            Vec3 radial = d - h * u;
            const double rho = radial.norm();
            radial = rho > 0 ? Vec3(radial / rho) : Vec3(shape.rotation.col(0));
            const Vec3 generator = (h >= 0 ? 1.0 : -1.0) * portable::cos(shape.half_angle) * u + portable::sin(shape.half_angle) * radial;
            const double t = std::max(0.0, d.dot(generator));
            return shape.center + t * generator;
        }
        default: throw std::invalid_argument("special_foot_point: not a special type");
    }
}

Projector::Projector(const Model& model, const std::vector<int>& labels, const std::vector<ProjectionTarget>& targets,
                     double max_distance, int vertices_per_step)
    : model_(model), labels_(labels), targets_(targets), max_distance_(max_distance),
      vertices_per_step_(std::max(1, vertices_per_step)), first_face_(model.points.size(), -1),
      next_face_(3 * model.triangles.size(), -1), out_(model.points) {
    for (const ProjectionTarget& t : targets_) solvers_.emplace_back(t.quadric);
    // Corner k of face f is entry 3f + k of its vertex's list.
    for (int f = model.face_count() - 1; f >= 0; --f)
        for (int k = 0; k < 3; ++k) {
            const int v = model.triangles[f][k];
            next_face_[3 * f + k] = first_face_[v];
            first_face_[v] = 3 * f + k;
        }
}

bool Projector::step() {
    const std::size_t end = std::min(out_.size(), next_ + vertices_per_step_);
    std::vector<int> seen;
    for (std::size_t v = next_; v < end; ++v) {
        // The vertex's distinct proxies, from its faces.
        seen.clear();
        for (int corner = first_face_[v]; corner >= 0; corner = next_face_[corner]) {
            const int proxy = labels_[corner / 3];
            if (std::find(seen.begin(), seen.end(), proxy) == seen.end()) seen.push_back(proxy);
        }
        Vec3 sum = Vec3::Zero();
        int count = 0;
        const Vec3& p = model_.points[v];
        for (int proxy : seen) {
            const ProjectionTarget& t = targets_[proxy];
            const std::optional<Vec3> foot =
                t.special ? std::optional<Vec3>(special_foot_point(*t.special, p)) : solvers_[proxy](p);
            if (foot && (*foot - p).norm() <= max_distance_) sum += *foot, ++count;
        }
        if (count > 0) out_[v] = sum / count;
    }
    next_ = end;
    return next_ < out_.size();
}

double Projector::fraction() const { return out_.empty() ? 1 : double(next_) / out_.size(); }

}  // namespace vqsa
