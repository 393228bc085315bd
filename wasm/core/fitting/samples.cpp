#include "fitting/samples.h"

#include "fitting/distance.h"

#include <algorithm>
#include <cmath>

namespace vqsa {

Samples vertex_samples(const std::vector<Vec3>& points, const std::vector<Triangle>& triangles,
                       const std::vector<int>& faces) {
    std::vector<int> vertices;
    vertices.reserve(3 * faces.size());
    for (int f : faces)
        for (int v : triangles[f]) vertices.push_back(v);
    std::sort(vertices.begin(), vertices.end());
    vertices.erase(std::unique(vertices.begin(), vertices.end()), vertices.end());
    Samples out;
    for (int v : vertices) out.add(points[v], 1.0);
    return out;
}

Samples region_samples(const Model& model, const std::vector<int>& faces, const std::vector<double>* roughness) {
    Samples out = vertex_samples(model.points, model.triangles, faces);
    std::vector<int> sorted(faces);
    if (!std::is_sorted(sorted.begin(), sorted.end())) std::sort(sorted.begin(), sorted.end());
    const DualGraph& g = model.graph;
    // A median needs no more than a thousand faces, evenly strided.
    const std::size_t stride = sorted.size() / 1024 + 1;
    std::vector<double> deviation, noise;
    deviation.reserve(sorted.size() / stride + 1);
    for (std::size_t i = 0; i < sorted.size(); i += stride) {
        const int f = sorted[i];
        if (roughness) noise.push_back((*roughness)[f]);
        double largest = 0;
        for (int e = g.begin(f); e < g.end(f); ++e) {
            const int h = g.neighbor[e];
            if (!std::binary_search(sorted.begin(), sorted.end(), h)) continue;
            largest = std::max(largest, g.sagitta[e]);
            const std::array<int, 2> edge = shared_edge(model, f, h);
            if (edge[0] >= 0) out.edge_midpoints.push_back(0.5 * (model.points[edge[0]] + model.points[edge[1]]));
        }
        out.midpoint_tolerances.resize(out.edge_midpoints.size(), largest);
        deviation.push_back(largest);
    }
    if (!noise.empty()) {
        std::nth_element(noise.begin(), noise.begin() + noise.size() / 2, noise.end());
        out.noise = noise[noise.size() / 2];
    }
    if (deviation.empty()) return out;
    const auto middle = deviation.begin() + deviation.size() / 2;
    std::nth_element(deviation.begin(), middle, deviation.end());
    out.tolerance = *middle;
    return out;
}

double taubin_rms(const Samples& s, const Quadric& q, double cap) {
    const double a = q.hessian_norm();
    return weighted_rms(s, [&](const Vec3& p) { return std::min(std::abs(taubin_distance(q, a, p)), cap); });
}

}  // namespace vqsa
