// Boundary smoothing by graph cut (docs/METHOD.md §8).
#pragma once

#include "fitting/face_errors.h"
#include "fitting/quadric.h"
#include "geometry/model.h"

#include <utility>
#include <vector>

namespace vqsa {

struct SmoothingOptions {
    int rings = 1;        // width of the fuzzy band on each side of a boundary, in dual-graph hops
    double lambda = 1.0;  // weight of boundary length against distance to the proxies
};

// Relabels the faces near the boundary of every pair of adjacent regions by a minimum
// s–t cut: E(X) = Σ d_x/(d0+d1) + λ Σ_cut len/(len + mean length). Faces outside the
// band, or touching a third region, keep their label. One pair per step, so a caller
// can show the boundaries moving.
class BoundarySmoother {
public:
    // `anchors`: faces that keep their label (one per region, so no region vanishes);
    // `crease` (per dual-graph link, optional): sharp edges, along which a boundary is free;
    // `regions` (per region, optional): only boundaries between two of these move.
    BoundarySmoother(const Model& model, std::vector<Quadric> proxies, std::vector<int>& labels,
                     const std::vector<int>& anchors, const SmoothingOptions& options,
                     const std::vector<char>* crease = nullptr, const std::vector<char>* regions = nullptr);

    // Smooths the next pair; false once every pair is done (then regions are made
    // connected again: stray pieces go to the neighbour they share most edges with).
    bool step();
    int pair_count() const { return static_cast<int>(pairs_.size()); }
    int pairs_done() const { return next_; }

private:
    void smooth(int a, int b);
    void reconnect();

    const Model& model_;
    std::vector<int>& labels_;
    SmoothingOptions options_;
    const std::vector<char>* crease_;
    FaceErrors errors_;
    double mean_edge_length_ = 0;
    std::vector<std::pair<int, int>> pairs_;
    int next_ = 0;
    std::vector<int> ring_;  // per face: 0 outside the band, else its ring (scratch)
    std::vector<int> node_;  // per face: graph node, or -1 (scratch)
    std::vector<char> anchored_;
};

}  // namespace vqsa
