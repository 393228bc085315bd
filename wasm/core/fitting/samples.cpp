#include "fitting/samples.h"

#include "fitting/distance.h"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>

namespace vqsa {

std::vector<int> face_vertices(const std::vector<Triangle>& triangles, const std::vector<int>& faces) {
    std::vector<int> vertices;
    vertices.reserve(3 * faces.size());
    for (int f : faces)
        for (int v : triangles[f]) vertices.push_back(v);
    std::sort(vertices.begin(), vertices.end());
    vertices.erase(std::unique(vertices.begin(), vertices.end()), vertices.end());
    return vertices;
}

Samples vertex_samples(const std::vector<Vec3>& points, const std::vector<Triangle>& triangles,
                       const std::vector<int>& faces, VertexWeight weight) {
    const std::vector<int> vertices = face_vertices(triangles, faces);
    std::vector<double> weights(vertices.size(), 1.0);
    if (weight == VertexWeight::area) {
        std::vector<double> shares(vertices.size(), 0.0);
        double total = 0;
        for (int f : faces) {
            const Triangle& t = triangles[f];
            const double third = (points[t[1]] - points[t[0]]).cross(points[t[2]] - points[t[0]]).norm() / 6;
            for (int v : t) shares[std::lower_bound(vertices.begin(), vertices.end(), v) - vertices.begin()] += third;
            total += 3 * third;
        }
        // Faces of no area carry no surface; if none has any, every vertex counts one.
        if (total > 0) weights.swap(shares);
    }
    Samples out;
    for (std::size_t i = 0; i < vertices.size(); ++i) out.add(points[vertices[i]], weights[i]);
    return out;
}

namespace {

// A median needs no more than a thousand faces, evenly strided.
std::size_t median_stride(const std::vector<int>& faces) { return faces.size() / 1024 + 1; }

// The upper median, reordering `values`; 0 of none.
double upper_median(std::vector<double>& values) {
    if (values.empty()) return 0;
    const auto middle = values.begin() + values.size() / 2;
    std::nth_element(values.begin(), middle, values.end());
    return *middle;
}

// The median of a per-face value over the (sorted) faces, strided as region_samples does.
double strided_median(const std::vector<int>& sorted, const std::vector<double>& values) {
    std::vector<double> picked;
    const std::size_t stride = median_stride(sorted);
    for (std::size_t i = 0; i < sorted.size(); i += stride) picked.push_back(values[sorted[i]]);
    return upper_median(picked);
}

std::vector<int> sorted_copy(const std::vector<int>& faces) {
    std::vector<int> sorted(faces);
    if (!std::is_sorted(sorted.begin(), sorted.end())) std::sort(sorted.begin(), sorted.end());
    return sorted;
}

}  // namespace

Samples region_samples(const Model& model, const std::vector<int>& faces, const std::vector<double>* roughness,
                       VertexWeight weight, const std::vector<char>* creases) {
    Samples out = vertex_samples(model.points, model.triangles, faces, weight);
    const std::vector<int> sorted = sorted_copy(faces);
    const DualGraph& g = model.graph;
    const std::size_t stride = median_stride(sorted);
    std::vector<double> deviation, smooth_deviation;
    deviation.reserve(sorted.size() / stride + 1);
    for (std::size_t i = 0; i < sorted.size(); i += stride) {
        const int f = sorted[i];
        double largest = 0, largest_smooth = 0;
        for (int e = g.begin(f); e < g.end(f); ++e) {
            const int h = g.neighbor[e];
            if (!std::binary_search(sorted.begin(), sorted.end(), h)) continue;
            largest = std::max(largest, g.sagitta[e]);
            if (creases && !(*creases)[e]) largest_smooth = std::max(largest_smooth, g.sagitta[e]);
            const std::array<int, 2> edge = shared_edge(model, f, h);
            if (edge[0] >= 0) out.edge_midpoints.push_back(0.5 * (model.points[edge[0]] + model.points[edge[1]]));
        }
        out.midpoint_tolerances.resize(out.edge_midpoints.size(), largest);
        deviation.push_back(largest);
        if (creases) smooth_deviation.push_back(largest_smooth);
    }
    if (roughness) out.noise = strided_median(sorted, *roughness);
    out.tolerance = upper_median(deviation);
    out.smooth_tolerance = creases ? upper_median(smooth_deviation) : out.tolerance;
    return out;
}

double region_scatter(const std::vector<int>& faces, const std::vector<double>& roughness, double tolerance) {
    const double median = strided_median(sorted_copy(faces), roughness);
    return std::sqrt(std::max(median * median - tolerance * tolerance, 0.0));
}

double taubin_rms(const Samples& s, const Quadric& q, double cap) {
    const double a = q.hessian_norm();
    return weighted_rms(s, [&](const Vec3& p) { return std::min(std::abs(taubin_distance(q, a, p)), cap); });
}

Eigen::Matrix3d principal_axes(const Samples& s, const Vec3& centroid) {
    Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
    for (std::size_t i = 0; i < s.points.size(); ++i)
        cov += s.weights[i] * (s.points[i] - centroid) * (s.points[i] - centroid).transpose();
    return Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(cov).eigenvectors();
}

}  // namespace vqsa
