// Weighted points standing for a region, for the orthogonal-distance fits.
#pragma once

#include "fitting/quadric.h"
#include "geometry/model.h"
#include "io/mesh.h"

#include <cmath>
#include <cstddef>
#include <limits>
#include <vector>

namespace vqsa {

// Weighted points standing for a region, for the orthogonal-distance fits and model
// selection (in the pipeline: its vertices, vertex_samples).
struct Samples {
    std::vector<Vec3> points;
    std::vector<double> weights;
    double total_weight = 0;
    // How far the points may stray from their surface without telling anything about it:
    // a tessellation's own chordal deviation (region_samples); 0 for exact data.
    double tolerance = 0;
    // The same over the edges that are no creases (region_samples, given the creases): what
    // the faces of one smooth surface sag by. Where the faces span two surfaces meeting at a
    // crease, most of them may border it (a coarse disc and the cylinder it caps), and the
    // tolerance is the crease's sagitta.
    double smooth_tolerance = 0;
    // Midpoints of edges between the faces (region_samples: those of at most a thousand
    // faces): a surface holds the edges a tessellation laid along its straight lines.
    std::vector<Vec3> edge_midpoints;
    // Per midpoint, the chordal deviation of the face it was taken from (its largest
    // sagitta): how far the midpoint may lie from the surface the vertices are on.
    std::vector<double> midpoint_tolerances;
    // On a noisy mesh, the region's noise (the median roughness of its faces, about 0.9 σ);
    // 0 otherwise. Model selection caps each point's distance at a few times this: beyond
    // it a point tells of a neighbouring face the region holds, not of the region's type.
    double noise = 0;
    // The scatter of the points that no surface accounts for (region_scatter; 0 when
    // unknown). Model selection does not prefer a quadric to an elementary type it departs
    // from by less: a noisy cylinder is not a hyperboloid of waist 0.2 σ.
    double scatter = 0;
    void add(const Vec3& p, double w) {
        points.push_back(p);
        weights.push_back(w);
        total_weight += w;
    }
};

// How vertex_samples weighs each vertex.
enum class VertexWeight {
    // One: under noise each vertex is one measurement, whatever the size of its faces
    // (what model selection fits).
    one,
    // A third of the area of each of the faces at it: each vertex stands for its share of
    // the surface, as in the distance between the input and the projected mesh, which
    // interpolates the vertices' displacements over the triangles.
    area,
};

// Each vertex of the faces once, by index, in increasing order.
std::vector<int> face_vertices(const std::vector<Triangle>& triangles, const std::vector<int>& faces);

// Each vertex of the faces once.
Samples vertex_samples(const std::vector<Vec3>& points, const std::vector<Triangle>& triangles,
                       const std::vector<int>& faces, VertexWeight weight = VertexWeight::one);

// vertex_samples of a region of the model, with the tessellation's chordal deviation there
// as the tolerance: per face, the largest sagitta (DualGraph) across its edges inside the
// region (a tessellated cylinder turns across one edge of each face); the median of
// those over the region's faces (a crease or a few noisy faces do not make it), at most
// a thousand of them evenly strided. `roughness` (per face, Features::roughness; given on a
// noisy mesh only) sets the samples' noise, the median over the same faces. `creases` (per
// dual-graph link, Features::crease) sets the smooth tolerance.
Samples region_samples(const Model& model, const std::vector<int>& faces,
                       const std::vector<double>* roughness = nullptr, VertexWeight weight = VertexWeight::one,
                       const std::vector<char>* creases = nullptr);

// The scatter of a region's vertices that no surface accounts for: the median roughness
// of its faces (as region_samples takes it) beyond the tessellation's deviation,
// √(r² − tolerance²): about 0.9 σ under noise, about 0 on a clean tessellation, coarse
// or fine (its roughness is the sag the tolerance measures).
double region_scatter(const std::vector<int>& faces, const std::vector<double>& roughness, double tolerance);

// Σ of the points' moments, each of its weight: what a quadric fit of the points takes.
inline Moments moments_of(const Samples& s) {
    Moments m{};
    for (std::size_t i = 0; i < s.points.size(); ++i) add_to(m, point_moments(s.points[i], s.weights[i]));
    return m;
}

inline Vec3 weighted_centroid(const Samples& s) {
    Vec3 c = Vec3::Zero();
    for (std::size_t i = 0; i < s.points.size(); ++i) c += s.weights[i] * s.points[i];
    return c / s.total_weight;
}

// The points' principal directions about `centroid` (their weighted centroid): the
// eigenvectors of their weighted scatter, columns by increasing variance.
Eigen::Matrix3d principal_axes(const Samples& s, const Vec3& centroid);

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

// Weighted RMS of the samples' Taubin distance to q (fitting/distance.h), each distance
// capped at `cap`.
double taubin_rms(const Samples& s, const Quadric& q, double cap = std::numeric_limits<double>::infinity());

}  // namespace vqsa
