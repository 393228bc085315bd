// Levenberg–Marquardt on weighted samples, for the few-parameter geometric fits.
#pragma once

#include "fitting/samples.h"

#include <Eigen/Dense>

#include <cmath>
#include <vector>

namespace vqsa {

// At most `limit` samples, evenly strided: enough to pin a handful of parameters.
inline Samples thinned(const Samples& s, std::size_t limit) {
    if (s.points.size() <= limit) return s;
    Samples out;
    out.tolerance = s.tolerance;
    out.noise = s.noise;
    out.scatter = s.scatter;
    const double stride = double(s.points.size()) / limit;
    for (std::size_t k = 0; k < limit; ++k) {
        const std::size_t i = static_cast<std::size_t>(k * stride);
        out.add(s.points[i], s.weights[i]);
    }
    return out;
}

// Minimises Σ w r(p; θ)² from `theta`, with a forward-difference Jacobian (steps of
// 1e-7 × `scale`): the parametrisations used are smooth and few-dimensional, and this
// runs once per region. At most 6000 samples take part. It stops once a step gains less
// than 1e-8 of the cost (the RMS then moves by parts in 10⁹: no model-selection decision
// turns on that, and a third of the iterations went to gains below it).
// `residual(θ)` returns the residual function of one parameter vector, r(p) (a callable
// on Vec3): what depends on θ alone (a normalised axis, a sine) is computed once, not
// once per sample. Both are templates, not std::function: the residual runs ~10⁵ times
// per fit, and an indirect call each time made the fits 1.4× slower in WASM.
template <int N, class ResidualFactory>
Eigen::Matrix<double, N, 1> least_squares(const Samples& all, Eigen::Matrix<double, N, 1> theta,
                                          const ResidualFactory& residual, double scale) {
    using Vector = Eigen::Matrix<double, N, 1>;
    const Samples s = thinned(all, 6000);
    const std::size_t n = s.points.size();
    auto cost = [&](const Vector& t) {
        const auto r = residual(t);
        double c = 0;
        for (std::size_t i = 0; i < n; ++i) {
            const double v = r(s.points[i]);
            c += s.weights[i] * v * v;
        }
        return c;
    };
    double current = cost(theta), damping = 1e-3;
    std::vector<double> base(n);
    Eigen::Matrix<double, Eigen::Dynamic, N> J(n, N);
    for (int iteration = 0; iteration < 50; ++iteration) {
        const double h = 1e-7 * scale;
        const auto r = residual(theta);
        for (std::size_t i = 0; i < n; ++i) base[i] = r(s.points[i]);
        for (int k = 0; k < N; ++k) {
            Vector t = theta;
            t[k] += h;
            const auto rk = residual(t);
            for (std::size_t i = 0; i < n; ++i) J(i, k) = (rk(s.points[i]) - base[i]) / h;
        }
        Eigen::Matrix<double, N, N> JtJ = Eigen::Matrix<double, N, N>::Zero();
        Vector Jtr = Vector::Zero();
        for (std::size_t i = 0; i < n; ++i) {
            const Vector row = J.row(i).transpose();
            JtJ += s.weights[i] * row * row.transpose();
            Jtr += s.weights[i] * base[i] * row;
        }
        bool improved = false;
        for (int attempt = 0; attempt < 10 && !improved; ++attempt) {
            Eigen::Matrix<double, N, N> A = JtJ;
            A.diagonal() += damping * JtJ.diagonal().cwiseMax(1e-30 * Vector::Ones());
            const Vector step = A.ldlt().solve(-Jtr);
            const Vector next = theta + step;
            const double c = cost(next);
            if (std::isfinite(c) && c < current) {
                const double gain = current - c;
                theta = next;
                current = c;
                damping = std::max(damping / 3, 1e-12);
                improved = true;
                if (gain < 1e-8 * (current + 1e-300)) return theta;
            } else {
                damping *= 10;
            }
        }
        if (!improved) break;
    }
    return theta;
}

}  // namespace vqsa
