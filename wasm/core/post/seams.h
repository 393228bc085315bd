// Tangent seams settled by simplicity (docs/METHOD.md §6): the faces along a seam that
// two surfaces explain alike go to the side that lets its neighbour be a simpler type.
#pragma once

#include "fitting/face_errors.h"
#include "fitting/fit.h"
#include "fitting/model_selection.h"
#include "geometry/model.h"
#include "lloyd/lloyd.h"
#include "lloyd/local_lloyd.h"

#include <optional>
#include <vector>

namespace vqsa {

struct SeamOptions {
    // A face is explained by a region's surface when its mean squared distance to it is
    // at most this factor times the region's own.
    double tolerance = 1.25;
    // At most this fraction of a region's area leaves it, at most this many faces deep
    // (a quad of the tessellation is two triangles).
    double max_fraction = 0.1;
    int rings = 3;
    // Vertices a first, cheap model selection sees (see seams.cpp).
    std::size_t screening_samples = 400;
    ModelSelectionOptions selection;
    // The fits, and the hand-over's local Lloyd iterations.
    LloydOptions lloyd;
    int hand_over_iterations = 4;
};

// Where a facet strip beside a tangent seam (a plane next to a fillet, a slot's wall next
// to its round end) went to the flat side, the flat side's quadric bends into it and model
// selection calls the plane a parabolic cylinder or a sphere: both fits are exact, and
// the distances cannot tell. Each region not of the simplest type gives each neighbour
// (across non-crease edges) the faces next to it that the neighbour's surface explains,
// when without them it selects a type of fewer parameters and the neighbour keeps its
// type: the same fit, fewer parameters. Beside a neighbour that explains none of them (a
// band of a torus fillet, which no quadric holds), a region that without them is exactly a
// plane, sphere, cylinder or cone gives the faces with a vertex off that surface, when the
// neighbour, refitted with them, holds its own about as well: a CAD face holds only faces
// on it.
// A region may also bend over a plane and part of the curved face beside it, its neighbour
// holding the rest of that face (a plane, half a fillet) while the noise hides the bend:
// when the region is explained by its noise and the half of it farthest from the neighbour
// lies on a plane within that half's noise, the pair is partitioned again by local Lloyd
// iterations with that plane imposed (the hand-over), and the result is kept when it needs
// fewer parameters in all and leaves no more error. `choices` (from select_model, per region) and
// `proxies` (quadric, moments, faces, area) are updated for the regions that change.
// One region per step; the arrays must outlive the simplifier.
class SeamSimplifier {
public:
    // `crease`: per dual-graph link, optional; `roughness`: per face (Features::roughness),
    // optional (no hand-over without it); `noisy`: the mesh is (its model selections see
    // the regions' noise, as the refit's do); `may_change` (per region, optional): the
    // regions that may give or take faces (all when null).
    SeamSimplifier(const Model& model, std::vector<int>& labels, std::vector<Proxy>& proxies,
                   std::vector<ModelChoice>& choices, const std::vector<char>* crease,
                   const std::vector<double>* roughness, bool noisy, const SeamOptions& options,
                   const std::vector<char>* may_change = nullptr);
    ~SeamSimplifier();
    bool step();  // false once every region is done
    double fraction() const;

private:
    void simplify(int a);
    // The best hand-over from region a to its neighbour b, if one pays (the partition is
    // left as it was).
    struct HandOver;
    std::optional<HandOver> hand_over(int a, int b);
    // Whether the faces labelled r (`faces` of them) are all reached from those of `before`
    // still labelled r, across links that are no crease, without leaving r.
    bool reached_without_creases(int r, const std::vector<int>& before, std::size_t faces);
    // Of a strip of faces next to region b (b being no exact surface: a band of a torus
    // fillet), those with a vertex off `surface` (the giving region's exact surface without
    // them), if b, refitted with them, holds its own faces within the tolerance; else none.
    std::vector<int> refitted_strip(int b, const std::vector<int>& strip, const Quadric& surface) const;
    // Region r becomes these faces, of these moments, typed as `choice` says.
    void commit(int r, std::vector<int> faces, const Moments& moments, const ModelChoice& choice);
    void measure(int r);  // regions_[r].error from evaluator_
    bool may_change(int r) const;
    Samples samples_of(const std::vector<int>& faces) const;  // what model selection sees
    // Σ A (noise_factor · roughness)² over the faces: the error their noise explains, as
    // the Lloyd stage counts it (Lloyd::noise_energy).
    double noise_energy(const std::vector<int>& faces) const;

    struct Region;
    const Model& model_;
    std::vector<int>& labels_;
    std::vector<Proxy>& proxies_;
    std::vector<ModelChoice>& choices_;
    const std::vector<char>* crease_;
    const std::vector<double>* roughness_;
    const std::vector<double>* selection_roughness_;  // roughness_ on a noisy mesh, else null
    const std::vector<char>* may_change_;
    SeamOptions options_;
    FaceErrors evaluator_;
    std::vector<Region> regions_;
    std::vector<char> in_strip_;     // scratch, per face
    std::vector<char> vertex_kept_;  // scratch, per vertex
    std::vector<int> depth_;         // scratch, per face (-1: unreached)
    std::vector<int> queue_;  // regions to simplify, in turn; a hand-over's b again
    std::size_t next_ = 0;
};

}  // namespace vqsa
