#include "lloyd/local_lloyd.h"

#include "fitting/samples.h"

#include <stdexcept>

namespace vqsa {

LocalLloyd::LocalLloyd(const Model& model, const LloydOptions& options, std::vector<int>& labels,
                       std::vector<Proxy>& proxies, std::vector<char> active, std::vector<ImposedType> imposed,
                       const std::vector<char>* crease, int max_iterations)
    : model_(model), options_(options), labels_(labels), proxies_(proxies), active_(std::move(active)),
      imposed_(std::move(imposed)), crease_(crease), max_iterations_(std::max(1, max_iterations)) {
    active_.resize(proxies_.size(), 0);
    imposed_.resize(proxies_.size(), ImposedType::none);
    refit();
    energy_ = evaluate_regions(model_, labels_, proxies_, errors_, face_errors_);
}

void LocalLloyd::refit() {
    refit_regions(model_, labels_, options_, proxies_, active_);
    bool any = false;
    for (std::size_t i = 0; i < proxies_.size(); ++i) any |= active_[i] && imposed_[i] != ImposedType::none;
    if (!any) return;
    std::vector<std::vector<int>> faces(proxies_.size());
    for (int f = 0; f < model_.face_count(); ++f)
        if (imposed_[labels_[f]] != ImposedType::none) faces[labels_[f]].push_back(f);
    ModelSelectionOptions selection;
    selection.classify = options_.classify;
    selection.rivals = false;
    for (std::size_t i = 0; i < proxies_.size(); ++i) {
        if (!active_[i] || imposed_[i] == ImposedType::none) continue;
        selection.imposed = imposed_[i];
        try {
            proxies_[i].quadric =
                select_model(region_samples(model_, faces[i]), proxies_[i].quadric, selection)
                    .chosen.quadric;
        } catch (const std::invalid_argument&) {
            // The region's faces no longer admit the type (too few, or degenerate): it keeps
            // the options' fit until they do again.
        }
    }
}

bool LocalLloyd::step() {
    if (settled_ || iterations_ >= max_iterations_) return false;
    flooded_ = labels_;
    std::vector<int> seeds(proxies_.size(), -1);
    for (std::size_t i = 0; i < proxies_.size(); ++i)
        if (active_[i]) seeds[i] = proxies_[i].seed;
    for (int& l : flooded_)
        if (active_[l]) l = -1;
    face_errors_.reset(model_, quadrics_of(proxies_));
    face_errors_.know(labels_, errors_);
    flooding_.run(model_, face_errors_, seeds, flooded_, crease_);
    // A face no seed reached (cut off from its region's seed by a fixed region) stays.
    for (int f = 0; f < model_.face_count(); ++f)
        if (flooded_[f] < 0) flooded_[f] = labels_[f];
    labels_.swap(flooded_);
    refit();
    const double before = energy_;
    // The other regions kept their faces and quadrics: their errors stand.
    energy_ = evaluate_regions(model_, labels_, proxies_, errors_, face_errors_, &active_);
    ++iterations_;
    settled_ = !(before - energy_ > options_.convergence * before);
    return !settled_ && iterations_ < max_iterations_;
}

}  // namespace vqsa
