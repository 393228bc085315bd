// Lloyd iterations confined to some regions: what an edit re-runs (docs/METHOD.md §11).
#pragma once

#include "fitting/face_errors.h"
#include "fitting/model_selection.h"
#include "geometry/model.h"
#include "lloyd/flooding.h"
#include "lloyd/lloyd.h"

#include <vector>

namespace vqsa {

// Each iteration floods the faces of the `active` regions anew from their seeds (their
// faces of least error) while every other face keeps its region, then refits the active
// regions: by the options' fit, or, for a region with an imposed type, by that type's fit
// to its vertices. Stops when the energy falls by less than options.convergence, or after
// `max_iterations`. `labels` and `proxies` (model order, unit frame) are updated in place
// and must outlive the object.
class LocalLloyd {
public:
    // `imposed`: per region (may be shorter: none); `crease`: per dual-graph link, optional.
    LocalLloyd(const Model& model, const LloydOptions& options, std::vector<int>& labels, std::vector<Proxy>& proxies,
               std::vector<char> active, std::vector<ImposedType> imposed, const std::vector<char>* crease,
               int max_iterations = 10);
    bool step();  // one iteration; false once settled
    double fraction() const { return double(iterations_) / max_iterations_; }
    double energy() const { return energy_; }

private:
    void refit();

    const Model& model_;
    const LloydOptions& options_;
    std::vector<int>& labels_;
    std::vector<Proxy>& proxies_;
    std::vector<char> active_;
    std::vector<ImposedType> imposed_;
    const std::vector<char>* crease_;
    int max_iterations_;
    int iterations_ = 0;
    bool settled_ = false;
    std::vector<double> errors_;
    std::vector<int> flooded_;
    double energy_ = 0;
    FaceErrors face_errors_;
    Flooding flooding_;
};

}  // namespace vqsa
