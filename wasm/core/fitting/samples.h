// Weighted points standing for a region, for the orthogonal-distance fits.
#pragma once

#include "io/mesh.h"

#include <cmath>
#include <cstddef>
#include <vector>

namespace vqsa {

// Weighted points standing for a region, for the orthogonal-distance fits and model
// selection (in the pipeline: its vertices, vertex_samples).
struct Samples {
    std::vector<Vec3> points;
    std::vector<double> weights;
    double total_weight = 0;
    void add(const Vec3& p, double w) {
        points.push_back(p);
        weights.push_back(w);
        total_weight += w;
    }
};

// Each vertex of the faces once, of weight one: under noise each vertex is one
// measurement, whatever the size of its faces (what model selection fits).
Samples vertex_samples(const std::vector<Vec3>& points, const std::vector<Triangle>& triangles,
                       const std::vector<int>& faces);

inline Vec3 weighted_centroid(const Samples& s) {
    Vec3 c = Vec3::Zero();
    for (std::size_t i = 0; i < s.points.size(); ++i) c += s.weights[i] * s.points[i];
    return c / s.total_weight;
}

// √(Σ wᵢ d(pᵢ)² / Σ wᵢ) for a distance function d.
template <class Distance>
double weighted_rms(const Samples& s, const Distance& distance) {
    double sum = 0;
    for (std::size_t i = 0; i < s.points.size(); ++i) {
        const double d = distance(s.points[i]);
        sum += s.weights[i] * d * d;
    }
    return std::sqrt(sum / s.total_weight);
}

}  // namespace vqsa
