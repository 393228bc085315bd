#include "lloyd/lloyd.h"

#include "geometry/rng.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace vqsa {

const char* operation_name(Operation operation) {
    switch (operation) {
        case Operation::initialize: return "initialize";
        case Operation::iterate: return "lloyd";
        case Operation::insert: return "insert";
        case Operation::split: return "split";
        case Operation::merge: return "merge";
        case Operation::teleport: return "teleport";
    }
    return "unknown";
}

const char* stop_reason_name(StopReason reason) {
    switch (reason) {
        case StopReason::none: return "none";
        case StopReason::proxies: return "proxies";
        case StopReason::tolerance: return "tolerance";
        case StopReason::max_iterations: return "max_iterations";
        case StopReason::cancelled: return "cancelled";
        case StopReason::exhausted: return "exhausted";
    }
    return "unknown";
}

void validate(const LloydOptions& o) {
    auto fail = [](const std::string& what) { throw std::invalid_argument(what); };
    if (o.proxies < 0 || !(o.tolerance >= 0) || o.max_iterations < 1) fail("proxies, tolerance or max-iterations out of range");
    if (o.stage_iterations < 1) fail("stage iterations must be at least 1");
    if (!(o.convergence >= 0 && o.convergence < 1)) fail("convergence must be in [0, 1)");
    if (o.teleports < 0) fail("teleports must be non-negative");
    if (!(o.split_fraction > 0 && o.split_fraction < 0.5)) fail("split fraction must be in (0, 0.5)");
}

Fit fit_proxy(const Moments& moments, int faces, const LloydOptions& options) {
    return faces < options.min_quadric_faces ? fit_plane(moments) : fit_region(moments, options.fit);
}

void refit_regions(const Model& model, const std::vector<int>& labels, const LloydOptions& options,
                   std::vector<Proxy>& proxies, const std::vector<char>& changed) {
    auto is_changed = [&](int i) { return changed.empty() || changed[i]; };
    for (std::size_t i = 0; i < proxies.size(); ++i)
        if (is_changed(i)) {
            proxies[i].moments.fill(0.0);
            proxies[i].faces = 0;
        }
    for (int f = 0; f < model.face_count(); ++f) {
        if (!is_changed(labels[f])) continue;
        Proxy& p = proxies[labels[f]];
        add_to(p.moments, model.moments[f]);
        ++p.faces;
    }
    for (std::size_t i = 0; i < proxies.size(); ++i) {
        if (!is_changed(i)) continue;
        Proxy& p = proxies[i];
        p.area = p.moments[0];
        if (!(p.area > 0)) continue;  // faces too small to measure (underflow): keep the seed plane
        const Fit fit = fit_proxy(p.moments, p.faces, options);
        p.quadric = fit.quadric;
        p.fit_error = fit.mean_squared;
        p.fitted = true;
    }
}

double evaluate_regions(const Model& model, const std::vector<int>& labels, std::vector<Proxy>& proxies,
                        std::vector<double>& errors, FaceErrors& evaluator, const std::vector<char>* changed) {
    std::vector<double> best(proxies.size(), std::numeric_limits<double>::infinity());
    for (Proxy& p : proxies) p.error = 0, p.seed = -1;
    errors.resize(model.face_count());
    double energy = 0;
    evaluator.reset(model, quadrics_of(proxies));
    for (int f = 0; f < model.face_count(); ++f) {
        const int l = labels[f];
        // An unchanged region kept its faces and its quadric: their errors stand.
        const double e = changed && !(*changed)[l] ? errors[f] : evaluator(f, l);
        errors[f] = e;
        proxies[l].error += e;
        energy += e;
        if (e < best[l]) best[l] = e, proxies[l].seed = f;
    }
    return energy;
}

std::vector<Quadric> quadrics_of(const std::vector<Proxy>& proxies) {
    std::vector<Quadric> out;
    out.reserve(proxies.size());
    for (const Proxy& p : proxies) out.push_back(p.quadric);
    return out;
}

std::vector<int> seeds_of(const std::vector<Proxy>& proxies) {
    std::vector<int> out;
    out.reserve(proxies.size());
    for (const Proxy& p : proxies) out.push_back(p.seed);
    return out;
}

Lloyd::Lloyd(const Model& model, const LloydOptions& options) : model_(model), options_(options) {
    validate(options_);
    if (model.face_count() == 0) throw std::invalid_argument("the mesh has no faces");
    if (options_.proxies > model.face_count())
        throw std::invalid_argument("proxies (" + std::to_string(options_.proxies) + ") exceeds the number of faces (" +
                                    std::to_string(model.face_count()) + ")");
    initialize();
}

void Lloyd::initialize() {
    const int n = model_.face_count();
    // One seed per connected component, drawn reproducibly from `seed`.
    std::vector<int> size(model_.component_count, 0), pick(model_.component_count);
    for (int f = 0; f < n; ++f) ++size[model_.component[f]];
    SplitMix64 rng(options_.seed);
    for (int c = 0; c < model_.component_count; ++c) pick[c] = static_cast<int>(rng.below(size[c]));
    std::vector<int> component_seeds(model_.component_count, -1);
    for (int f = 0; f < n; ++f) {
        int& k = pick[model_.component[f]];
        if (k-- == 0) component_seeds[model_.component[f]] = f;
    }
    for (int s : component_seeds) add_proxy(s);
    labels_.assign(n, -1);
    errors_.assign(n, 0.0);
    teleports_left_ = options_.teleports;
    splits_left_ = 2 * std::max(options_.proxies, 16);
    iterating_ = true;
    stage_iteration_ = 0;
    previous_energy_ = std::numeric_limits<double>::infinity();
}

double Lloyd::rms() const { return model_.total_area > 0 ? std::sqrt(std::max(0.0, energy_) / model_.total_area) : 0; }

double Lloyd::fraction() const {
    if (done()) return 1;
    if (options_.proxies > 0) return std::min(1.0, double(proxies_.size()) / options_.proxies);
    if (options_.tolerance > 0 && rms() > 0) return std::clamp(std::log(rms()) / std::log(options_.tolerance), 0.0, 1.0);
    return 0;
}

Classification Lloyd::classify_proxy(int proxy) const {
    const RegionFrame region = region_frame(proxies_[proxy].moments);
    return classify(proxies_[proxy].quadric, region.center, region.radius, options_.classify);
}

void Lloyd::stop(StopReason reason) { stop_reason_ = reason; }

bool Lloyd::step() {
    if (done()) return false;
    if (cancel_requested_) {
        // A run cancelled right after an operation still needs one flood to be consistent.
        if (stage_iteration_ == 0 && iterating_) iterate();
        stop(StopReason::cancelled);
        return false;
    }
    if (iterating_) {
        if (iterations_ >= options_.max_iterations && stage_iteration_ > 0) {
            stop(StopReason::max_iterations);
            return false;
        }
        iterate();
        last_operation_ = Operation::iterate;
        const bool settled = stage_iteration_ >= 2 && energy_ >= previous_energy_ * (1 - options_.convergence);
        if (settled || stage_iteration_ >= options_.stage_iterations) iterating_ = false;
        previous_energy_ = energy_;
        return true;
    }
    decide();
    return !done();
}

void Lloyd::iterate() {
    // errors_ holds d(f, P) for the current labels and quadrics: most faces end up in
    // the same region again and need no new evaluation.
    previous_labels_.swap(labels_);
    labels_.assign(previous_labels_.size(), -1);
    face_errors_.reset(model_, quadrics_of(proxies_));
    face_errors_.know(previous_labels_, errors_);
    flooding_.run(model_, face_errors_, seeds_of(proxies_), labels_);
    changed_.assign(proxies_.size(), 0);
    for (std::size_t i = 0; i < proxies_.size(); ++i) changed_[i] = !proxies_[i].fitted;
    for (int f = 0; f < model_.face_count(); ++f)
        if (labels_[f] != previous_labels_[f]) {
            changed_[labels_[f]] = 1;
            if (previous_labels_[f] >= 0) changed_[previous_labels_[f]] = 1;
        }
    refit_regions(model_, labels_, options_, proxies_, changed_);
    evaluate(&changed_);
    ++iterations_;
    ++stage_iteration_;
}

void Lloyd::evaluate(const std::vector<char>* changed) {
    energy_ = evaluate_regions(model_, labels_, proxies_, errors_, face_errors_, changed);
}

void Lloyd::start_operation(Operation operation) {
    last_operation_ = operation;
    iterating_ = true;
    stage_iteration_ = 0;
    previous_energy_ = energy_;
}

void Lloyd::decide() {
    if (teleport_pending_) {
        teleport_pending_ = false;
        if (!(energy_ < snapshot_.energy * (1 - options_.convergence))) {
            // The teleport did not pay: go back, and stop trying (the same move would be chosen again).
            labels_ = snapshot_.labels;
            errors_ = snapshot_.errors;
            proxies_ = snapshot_.proxies;
            energy_ = snapshot_.energy;
            teleports_left_ = 0;
        }
    }

    const int count = static_cast<int>(proxies_.size());
    const int target = options_.proxies;
    if (options_.tolerance > 0 && rms() <= options_.tolerance && (target == 0 || count <= target))
        return stop(StopReason::tolerance);
    if (target > 0 && count > target) {
        if (merge_cheapest(false)) return start_operation(Operation::merge);
        return stop(StopReason::proxies);
    }
    if (target > 0 && count == target) {
        if (teleports_left_ > 0) {
            snapshot_ = {labels_, errors_, proxies_, energy_};
            if (merge_cheapest(true)) {
                insert_farthest(1);
                --teleports_left_;
                teleport_pending_ = true;
                return start_operation(Operation::teleport);
            }
        }
        return stop(StopReason::proxies);
    }
    if (count >= model_.face_count()) return stop(StopReason::exhausted);
    // Growing: an invalid region is split instead of inserting elsewhere.
    if (splits_left_ > 0 && split_invalid()) {
        --splits_left_;
        return start_operation(Operation::split);
    }
    // Far from the target, several proxies go in at once (into distinct regions): Lloyd
    // then runs once per batch rather than once per proxy.
    int batch = std::max(1, static_cast<int>(count * options_.insertion_batch));
    if (target > 0) batch = std::min(batch, target - count);
    insert_farthest(batch);
    if (static_cast<int>(proxies_.size()) == count) return stop(StopReason::exhausted);
    start_operation(Operation::insert);
}

void Lloyd::insert_farthest(int count) {
    // The regions of largest total error, and in each the face of largest error.
    std::vector<int> order(proxies_.size());
    for (std::size_t i = 0; i < order.size(); ++i) order[i] = static_cast<int>(i);
    std::sort(order.begin(), order.end(), [&](int a, int b) {
        return proxies_[a].error != proxies_[b].error ? proxies_[a].error > proxies_[b].error : a < b;
    });
    for (int region : order) {
        if (count == 0) return;
        if (proxies_[region].faces < 2 || !(proxies_[region].error > 0)) continue;
        // The worst face counted with its neighbours: a lone outlier face (a sliver, a
        // spike) would seed a proxy that never grows.
        int worst = -1;
        double worst_error = -1;
        const DualGraph& g = model_.graph;
        for (int f = 0; f < model_.face_count(); ++f) {
            if (labels_[f] != region || f == proxies_[region].seed) continue;
            double e = errors_[f];
            for (int k = g.begin(f); k < g.end(f); ++k)
                if (labels_[g.neighbor[k]] == region) e += errors_[g.neighbor[k]];
            if (e > worst_error) worst_error = e, worst = f;
        }
        add_proxy(worst);
        --count;
    }
}

bool Lloyd::split_invalid() {
    // The invalid region of largest error is split; one per decision, like an insertion.
    int chosen = -1, best[2] = {-1, -1};
    const int count = static_cast<int>(proxies_.size());
    for (int i = 0; i < count; ++i) {
        if (proxies_[i].faces < 2 * options_.min_quadric_faces) continue;
        if (chosen >= 0 && proxies_[i].error <= proxies_[chosen].error) continue;
        const Classification c = classify_proxy(i);
        if (!has_two_parts(c.type)) continue;
        double part_area[2] = {0, 0};
        int part_best[2] = {-1, -1};
        for (int f = 0; f < model_.face_count(); ++f) {
            if (labels_[f] != i) continue;
            const int part = part_of(c, model_.barycentres[f]);
            if (part == 0) continue;
            const int k = part > 0 ? 0 : 1;
            part_area[k] += model_.areas[f];
            if (part_best[k] < 0 || errors_[f] < errors_[part_best[k]]) part_best[k] = f;
        }
        if (std::min(part_area[0], part_area[1]) < options_.split_fraction * proxies_[i].area) continue;
        chosen = i;
        best[0] = part_best[0], best[1] = part_best[1];
    }
    if (chosen < 0) return false;
    // Each part restarts from a plane through its best face.
    proxies_[chosen].quadric = plane_through(best[0]);
    proxies_[chosen].fitted = false;
    evaluate();
    proxies_[chosen].seed = best[0];
    add_proxy(best[1]);
    return true;
}

bool Lloyd::merge_cheapest(bool gated) {
    const std::vector<std::pair<int, int>> pairs = adjacent_regions(model_, labels_);

    // Gates: the paper's |Et - (Ei + Ej)| < 0.5 max Ek on mean squared errors, or, as
    // in planar VSA's teleportation, a merge that costs less than half the error of
    // the worst region (which the freed proxy will then be inserted into).
    double largest = 0, worst_region = 0;
    for (const Proxy& p : proxies_) largest = std::max(largest, p.fit_error), worst_region = std::max(worst_region, p.area * p.fit_error);
    double best_cost = std::numeric_limits<double>::infinity();
    int best_pair = -1;
    Fit best_fit;
    for (std::size_t k = 0; k < pairs.size(); ++k) {
        const Proxy &a = proxies_[pairs[k].first], &b = proxies_[pairs[k].second];
        Moments united = a.moments;
        add_to(united, b.moments);
        const Fit fit = fit_proxy(united, a.faces + b.faces, options_);
        const double cost = united[0] * fit.mean_squared - a.area * a.fit_error - b.area * b.fit_error;
        if (gated && !(std::abs(fit.mean_squared - (a.fit_error + b.fit_error)) < 0.5 * largest) &&
            !(cost < 0.5 * worst_region))
            continue;
        if (cost >= best_cost) continue;
        const RegionFrame region = region_frame(united);
        const QuadricType type = classify(fit.quadric, region.center, region.radius, options_.classify).type;
        if (has_two_parts(type)) continue;
        best_cost = cost, best_pair = static_cast<int>(k), best_fit = fit;
    }
    if (best_pair < 0) return false;
    const auto [keep, gone] = pairs[best_pair];
    Proxy& p = proxies_[keep];
    add_to(p.moments, proxies_[gone].moments);
    p.area = p.moments[0];
    p.faces += proxies_[gone].faces;
    p.quadric = best_fit.quadric;
    p.fit_error = best_fit.mean_squared;
    p.fitted = true;
    for (int& l : labels_)
        if (l == gone) l = keep;
    remove_proxy(gone);
    evaluate();
    return true;
}

Quadric Lloyd::plane_through(int face) const {
    const Triangle& t = model_.triangles[face];
    const Vec3 normal =
        (model_.points[t[1]] - model_.points[t[0]]).cross(model_.points[t[2]] - model_.points[t[0]]).normalized();
    return normalized(Quadric::plane(normal, model_.barycentres[face]));
}

void Lloyd::add_proxy(int seed) {
    Proxy p;
    p.quadric = plane_through(seed);
    p.seed = seed;
    proxies_.push_back(p);
}

void Lloyd::remove_proxy(int index) {
    proxies_.erase(proxies_.begin() + index);
    for (int& l : labels_)
        if (l > index) --l;
}

}  // namespace vqsa
