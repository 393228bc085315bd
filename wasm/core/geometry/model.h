// The mesh as the algorithms see it: in the unit frame (docs/METHOD.md §0), with per-face
// areas, barycentres and moments computed once, and the dual graph.
#pragma once

#include "io/mesh.h"
#include "geometry/moments.h"

#include <array>
#include <utility>
#include <vector>

namespace vqsa {

// How far (RMS, in the unit frame: relative to the longest bounding-box side) a
// tessellation's vertices may lie off its surfaces and count as on them: what a mesh file's
// six or seven significant digits keep. Noise, however small it is, moves them farther.
constexpr double kStoredPrecision = 1e-6;

// Faces are adjacent when they share an edge (every pair around a non-manifold edge).
struct DualGraph {
    std::vector<int> start;         // neighbours of face f: neighbor[start[f] .. start[f+1])
    std::vector<int> neighbor;
    std::vector<double> edge_length;  // length of the shared edge, unit frame
    // The sagitta a curve through both faces would have over their mean height above the
    // shared edge: θ(h₁ + h₂)/16 for faces turning by θ (orientation aside) over heights
    // h₁, h₂, the curve's curvature being 2θ/(h₁ + h₂). A tessellation's chordal deviation
    // across the edge, or twice the noise's effect on it (region_samples).
    std::vector<double> sagitta;

    int begin(int f) const { return start[f]; }
    int end(int f) const { return start[f + 1]; }
};

// Gives face `seed` (-1 in `labels`) and every face of its component the label `label`: the
// faces `member(face)` admits that it reaches over the links `joins(face, link)` admits,
// `link` being one of `face`'s (DualGraph::neighbor's indexing).
template <class Member, class Joins>
void label_component(const DualGraph& graph, int seed, int label, std::vector<int>& labels, Member member, Joins joins) {
    std::vector<int> stack{seed};
    labels[seed] = label;
    while (!stack.empty()) {
        const int h = stack.back();
        stack.pop_back();
        for (int e = graph.begin(h); e < graph.end(h); ++e) {
            const int m = graph.neighbor[e];
            if (labels[m] >= 0 || !joins(h, e) || !member(m)) continue;
            labels[m] = label;
            stack.push_back(m);
        }
    }
}

// Gives every face that is still -1 in `labels` and that `member(face)` admits the label of
// its component (label_component). Labels run from `next` on, in the order of each
// component's first face; returns the next unused.
template <class Member, class Joins>
int label_components(const DualGraph& graph, std::vector<int>& labels, int next, Member member, Joins joins) {
    for (int f = 0; f < static_cast<int>(labels.size()); ++f)
        if (labels[f] < 0 && member(f)) label_component(graph, f, next++, labels, member, joins);
    return next;
}

struct Model {
    Frame frame;  // unit frame → input frame
    std::vector<Vec3> points;
    std::vector<Triangle> triangles;
    std::vector<Vec3> barycentres;
    std::vector<double> areas;
    std::vector<Moments> moments;
    DualGraph graph;
    std::vector<int> component;  // connected component of each face
    int component_count = 0;
    double total_area = 0;

    int face_count() const { return static_cast<int>(triangles.size()); }
};

Model make_model(const Mesh& mesh);

// The cross product of face f's edges from its first vertex: along its normal (by its
// winding), twice its area long.
Vec3 area_normal(const Model& model, int f);

// Whether faces f and h lie in one plane to the stored precision (each within it of the
// other's plane), which no noise leaves.
bool exactly_coplanar(const Model& model, int f, int h);
// Whether face f lies in one plane with a neighbour so (a face of an exact tessellation).
bool coplanar_with_a_neighbour(const Model& model, int f);

// Σ of the faces' moments.
Moments moments_of(const Model& model, const std::vector<int>& faces);

// The two vertices faces a and b share (in a's order), or {-1, -1} when they share no edge.
std::array<int, 2> shared_edge(const Model& model, int a, int b);

// Pairs of labels (a < b) of adjacent faces, sorted: the region adjacency of a labelling.
std::vector<std::pair<int, int>> adjacent_regions(const Model& model, const std::vector<int>& labels);

}  // namespace vqsa
