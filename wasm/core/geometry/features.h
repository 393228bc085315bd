// Sharp creases, the charts they bound, and each face's roughness: what the Lloyd stage
// seeds, floods and stops by (docs/METHOD.md §3).
#pragma once

#include "geometry/model.h"

#include <vector>

namespace vqsa {

// The cosine of `fraction` of a crease angle in degrees, the same bits in every build
// (portable_math): the threshold dot products of normals are compared with.
double crease_cosine(double crease_angle, double fraction = 1);

struct FeatureOptions {
    // A dual edge is a crease when the (filtered) normals of its faces differ by more
    // than this, in degrees; 180 finds none. Above the facet angle of most CAD
    // tessellations of small holes (40–50° seen), below a right angle.
    double crease_angle = 50;
    // Bilateral filtering of the face normals (Zheng et al. 2011) before measuring
    // angles, so that noise makes no creases and a coarsely tessellated cylinder makes
    // few: iterations, and the normal difference that halves a neighbour's weight.
    int filter_iterations = 8;
    double filter_range = 0.35;
};

struct Features {
    std::vector<Vec3> normals;    // per face: filtered, consistently oriented where the mesh allows
    std::vector<char> crease;     // per dual-graph link (DualGraph::neighbor's indexing)
    std::vector<int> chart;       // per face: its chart, the faces reachable without crossing a crease
    int chart_count = 0;
    // Per face: the RMS distance a locally exact surface would leave on it (the noise),
    // estimated over its chart from local quadric fits at its vertices (on an `exact`
    // tessellation, no more than the largest sag of the chart's facets); unit frame.
    std::vector<double> roughness;
    // Per face: off a smooth surface by a coarse arc's sag beyond the stored precision (one
    // of its facets, or a flat face beside one), its noise or not.
    std::vector<char> arc_facet;
    // Whether the mesh is an exact tessellation: half its faces, or faces holding half its
    // area, lie in one plane with a neighbour to the stored precision, as no noise or
    // remeshing leaves them.
    bool exact = false;
};

Features detect_features(const Model& model, const FeatureOptions& options = {});

// The squared error the noise explains on face f, area · roughness², before any factor.
inline double face_noise(const Model& model, const std::vector<double>& roughness, int f) {
    return model.areas[f] * roughness[f] * roughness[f];
}

}  // namespace vqsa
