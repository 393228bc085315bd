#include "lloyd/engine.h"

#include "geometry/rng.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace vqsa {

const char* phase_name(Phase phase) {
    switch (phase) {
        case Phase::initialize: return "initialize";
        case Phase::lloyd: return "lloyd";
        case Phase::insert: return "insert";
        case Phase::split: return "split";
        case Phase::merge: return "merge";
        case Phase::teleport: return "teleport";
        case Phase::smooth: return "smooth";
        case Phase::classify: return "classify";
        case Phase::project: return "project";
        case Phase::measure: return "measure";
        case Phase::done: return "done";
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

void validate(const EngineOptions& o) {
    auto fail = [](const std::string& what) { throw std::invalid_argument(what); };
    if (o.proxies < 0) fail("proxies must be at least 1 (or 0 for no count target), not " + std::to_string(o.proxies));
    if (!(o.tolerance >= 0) || !std::isfinite(o.tolerance))
        fail("tolerance must be a non-negative number, not " + std::to_string(o.tolerance));
    if (o.proxies == 0 && o.tolerance == 0) fail("give a proxy count, a tolerance, or both");
    if (o.max_iterations < 1) fail("max-iterations must be at least 1");
    if (o.stage_iterations < 1) fail("stage iterations must be at least 1");
    if (!(o.convergence >= 0 && o.convergence < 1)) fail("convergence must be in [0, 1)");
    if (o.teleports < 0) fail("teleports must be non-negative");
    if (!(o.split_fraction > 0 && o.split_fraction < 0.5)) fail("split fraction must be in (0, 0.5)");
    if (o.smoothing.rings < 1 || o.smoothing.rings > 100) fail("rings must be between 1 and 100");
    if (!(o.smoothing.lambda >= 0) || !std::isfinite(o.smoothing.lambda)) fail("lambda must be a non-negative number");
    if (!(o.max_projection_distance > 0)) fail("the projection distance guard must be positive");
}

Engine::Engine(const Mesh& mesh, const EngineOptions& options)
    : source_face_(mesh.source_face), input_face_count_(mesh.input_face_count), options_(options) {
    validate(options_);
    if (mesh.triangles.empty()) throw std::invalid_argument("the mesh has no faces");
    if (options_.proxies > static_cast<int>(mesh.triangles.size()))
        throw std::invalid_argument("proxies (" + std::to_string(options_.proxies) + ") exceeds the number of faces (" +
                                    std::to_string(mesh.triangles.size()) + ")");
    model_ = make_model(mesh);
    initialize();
}

void Engine::initialize() {
    const int n = model_.face_count();
    // One seed per connected component, drawn reproducibly from `seed`.
    std::vector<int> size(model_.component_count, 0), pick(model_.component_count);
    for (int f = 0; f < n; ++f) ++size[model_.component[f]];
    SplitMix64 rng(options_.seed);
    for (int c = 0; c < model_.component_count; ++c) pick[c] = static_cast<int>(rng.below(size[c]));
    seeds_.assign(model_.component_count, -1);
    for (int f = 0; f < n; ++f) {
        int& k = pick[model_.component[f]];
        if (k-- == 0) seeds_[model_.component[f]] = f;
    }
    const std::vector<int> component_seeds = std::move(seeds_);
    seeds_.clear();
    for (int s : component_seeds) add_proxy(s);
    labels_.assign(n, -1);
    errors_.assign(n, 0.0);
    teleports_left_ = options_.teleports;
    splits_left_ = 2 * std::max(options_.proxies, 16);
    in_lloyd_ = true;
    stage_iteration_ = 0;
    previous_energy_ = std::numeric_limits<double>::infinity();
}

double Engine::rms() const { return model_.total_area > 0 ? std::sqrt(std::max(0.0, energy_) / model_.total_area) : 0; }

std::vector<int> Engine::labels() const {
    std::vector<int> out(input_face_count_, -1);
    for (std::size_t f = 0; f < labels_.size(); ++f) out[source_face_[f]] = labels_[f];
    return out;
}

std::vector<int> Engine::lloyd_labels() const {
    const std::vector<int>& model_order = lloyd_face_labels();
    std::vector<int> out(input_face_count_, -1);
    for (std::size_t f = 0; f < model_order.size(); ++f) out[source_face_[f]] = model_order[f];
    return out;
}

std::vector<Vec3> Engine::projected_vertices() const {
    std::vector<Vec3> out;
    out.reserve(projected_.size());
    for (const Vec3& p : projected_) out.push_back(model_.frame.to_input(p));
    return out;
}

Quadric Engine::input_quadric(int proxy) const {
    return normalized(change_frame(proxies_.at(proxy).quadric, model_.frame.scale, model_.frame.translation));
}

Classification Engine::classify_unit(int proxy) const {
    const RegionFrame region = region_frame(proxies_[proxy].moments);
    return classify(proxies_[proxy].quadric, region.center, region.radius, options_.classify);
}

Classification Engine::classification(int proxy) const {
    const Classification unit = is_special(proxy) ? *special_[proxy] : classify_unit(proxy);
    return change_frame(unit, model_.frame.scale, model_.frame.translation);
}

void Engine::cancel() { cancel_requested_ = true; }

void Engine::end_lloyd(StopReason reason) {
    stop_reason_ = reason;
    lloyd_labels_ = labels_;
    last_phase_ = Phase::done;
    if (reason == StopReason::cancelled) stage_ = Stage::done;
    else next_stage();
}

// Moves to the next enabled post-processing stage.
void Engine::next_stage() {
    const bool enabled[] = {true, options_.smooth, true, options_.project, options_.project && options_.measure, true};
    int s = static_cast<int>(stage_) + 1;
    while (!enabled[s]) ++s;
    stage_ = static_cast<Stage>(s);
}

bool Engine::step() {
    if (done()) return false;
    if (cancel_requested_) {
        if (stage_ == Stage::lloyd) {
            // A run cancelled right after an operation still needs one flood to be consistent.
            if (stage_iteration_ == 0 && in_lloyd_) lloyd_iteration();
            end_lloyd(StopReason::cancelled);
        } else {
            // Post-processing stops where it is; the Lloyd labels stay those of the Lloyd stage.
            stop_reason_ = StopReason::cancelled;
            stage_ = Stage::done;
            last_phase_ = Phase::done;
        }
        return false;
    }
    if (stage_ != Stage::lloyd) {
        post_step();
        return !done();
    }
    if (in_lloyd_) {
        if (iterations_ >= options_.max_iterations && stage_iteration_ > 0) {
            end_lloyd(StopReason::max_iterations);
            return !done();
        }
        lloyd_iteration();
        last_phase_ = Phase::lloyd;
        const bool settled = stage_iteration_ >= 2 && energy_ >= previous_energy_ * (1 - options_.convergence);
        if (settled || stage_iteration_ >= options_.stage_iterations) in_lloyd_ = false;
        previous_energy_ = energy_;
        return true;
    }
    decide();
    return !done();
}

void Engine::post_step() {
    switch (stage_) {
        case Stage::smooth:
            last_phase_ = Phase::smooth;
            if (!smoother_) smoother_ = std::make_unique<BoundarySmoother>(model_, quadrics_, labels_, seeds_, options_.smoothing);
            if (smoother_->step()) return;
            smoother_.reset();
            // Regions changed: refit every proxy to its new faces.
            changed_.assign(proxies_.size(), 1);
            refit(changed_);
            evaluate();
            next_stage();
            return;
        case Stage::classify:
            last_phase_ = Phase::classify;
            special_.assign(proxies_.size(), std::nullopt);
            if (options_.refit) {
                for (int i = 0; i < static_cast<int>(proxies_.size()); ++i) {
                    const Proxy& p = proxies_[i];
                    if (p.faces < 2) continue;
                    const std::optional<SpecialFit> fit =
                        best_special_fit(region_samples(i), p.quadric, std::sqrt(p.error / p.area), options_.special);
                    if (!fit) continue;
                    special_[i] = fit->shape;
                    proxies_[i].quadric = quadrics_[i] = fit->quadric;
                }
                evaluate();
            }
            next_stage();
            return;
        case Stage::project: {
            last_phase_ = Phase::project;
            std::vector<ProjectionTarget> targets;
            for (std::size_t i = 0; i < proxies_.size(); ++i) targets.push_back({proxies_[i].quadric, special_[i]});
            projected_ = project_vertices(model_, labels_, targets, options_.max_projection_distance);
            next_stage();
            return;
        }
        case Stage::measure:
            last_phase_ = Phase::measure;
            metrics_ = measure(model_.points, projected_, model_.triangles, labels_, static_cast<int>(proxies_.size()),
                               options_.metrics);
            next_stage();
            return;
        default: return;
    }
}

Samples Engine::region_samples(int proxy) const {
    Samples s;
    for (int f = 0; f < model_.face_count(); ++f) {
        if (labels_[f] != proxy) continue;
        const double w = 0.25 * model_.areas[f];
        for (int v : model_.triangles[f]) s.add(model_.points[v], w);
        s.add(model_.barycentres[f], w);
    }
    return s;
}

void Engine::run(const ProgressCallback& progress) {
    while (!done()) {
        step();
        if (progress && !progress({last_phase_, static_cast<int>(proxies_.size()), iterations_, rms()}, *this)) {
            cancel();
            step();
        }
    }
}

void Engine::lloyd_iteration() {
    // errors_ holds d(f, P) for the current labels and quadrics: most faces end up in
    // the same region again and need no new evaluation.
    previous_labels_.swap(labels_);
    labels_.assign(previous_labels_.size(), -1);
    face_errors_.reset(model_, quadrics_);
    face_errors_.know(previous_labels_, errors_);
    flooding_.run(model_, face_errors_, seeds_, labels_);
    changed_.assign(proxies_.size(), 0);
    for (std::size_t i = 0; i < proxies_.size(); ++i) changed_[i] = !proxies_[i].fitted;
    for (int f = 0; f < model_.face_count(); ++f)
        if (labels_[f] != previous_labels_[f]) {
            changed_[labels_[f]] = 1;
            if (previous_labels_[f] >= 0) changed_[previous_labels_[f]] = 1;
        }
    refit(changed_);
    evaluate(&changed_);
    ++iterations_;
    ++stage_iteration_;
}

void Engine::refit(const std::vector<char>& changed) {
    for (std::size_t i = 0; i < proxies_.size(); ++i)
        if (changed[i]) {
            proxies_[i].moments.fill(0.0);
            proxies_[i].faces = 0;
        }
    for (int f = 0; f < model_.face_count(); ++f) {
        if (!changed[labels_[f]]) continue;
        Proxy& p = proxies_[labels_[f]];
        add_to(p.moments, model_.moments[f]);
        ++p.faces;
    }
    for (std::size_t i = 0; i < proxies_.size(); ++i) {
        if (!changed[i]) continue;
        Proxy& p = proxies_[i];
        p.area = p.moments[0];
        if (!(p.area > 0)) continue;  // faces too small to measure (underflow): keep the seed plane
        const Fit fit = p.faces < options_.min_quadric_faces ? fit_plane(p.moments) : fit_region(p.moments, options_.fit);
        p.quadric = fit.quadric;
        p.fit_error = fit.mean_squared;
        p.fitted = true;
        quadrics_[i] = p.quadric;
    }
}

void Engine::evaluate(const std::vector<char>* changed) {
    std::vector<double> best(proxies_.size(), std::numeric_limits<double>::infinity());
    for (Proxy& p : proxies_) p.error = 0, p.seed = -1;
    energy_ = 0;
    face_errors_.reset(model_, quadrics_);
    for (int f = 0; f < model_.face_count(); ++f) {
        const int l = labels_[f];
        // An unchanged region kept its faces and its quadric: their errors stand.
        const double e = changed && !(*changed)[l] ? errors_[f] : face_errors_(f, l);
        errors_[f] = e;
        proxies_[l].error += e;
        energy_ += e;
        if (e < best[l]) best[l] = e, proxies_[l].seed = f;
    }
    for (std::size_t i = 0; i < proxies_.size(); ++i) seeds_[i] = proxies_[i].seed;
}

void Engine::decide() {
    if (teleport_pending_) {
        teleport_pending_ = false;
        if (!(energy_ < snapshot_.energy * (1 - options_.convergence))) {
            // The teleport did not pay: go back, and stop trying (the same move would be chosen again).
            labels_ = snapshot_.labels;
            errors_ = snapshot_.errors;
            proxies_ = snapshot_.proxies;
            energy_ = snapshot_.energy;
            quadrics_.resize(proxies_.size());
            seeds_.resize(proxies_.size());
            for (std::size_t i = 0; i < proxies_.size(); ++i) quadrics_[i] = proxies_[i].quadric, seeds_[i] = proxies_[i].seed;
            teleports_left_ = 0;
        }
    }

    auto start_stage = [&](Phase phase) {
        last_phase_ = phase;
        in_lloyd_ = true;
        stage_iteration_ = 0;
        previous_energy_ = energy_;
    };

    const int count = static_cast<int>(proxies_.size());
    const int target = options_.proxies;
    if (options_.tolerance > 0 && rms() <= options_.tolerance && (target == 0 || count <= target))
        return end_lloyd(StopReason::tolerance);
    if (target > 0 && count > target) {
        if (merge_cheapest(false)) return start_stage(Phase::merge);
        return end_lloyd(StopReason::proxies);
    }
    if (target > 0 && count == target) {
        if (teleports_left_ > 0) {
            snapshot_ = {labels_, errors_, proxies_, energy_};
            if (merge_cheapest(true)) {
                insert_farthest(1);
                --teleports_left_;
                teleport_pending_ = true;
                return start_stage(Phase::teleport);
            }
        }
        return end_lloyd(StopReason::proxies);
    }
    if (count >= model_.face_count()) return end_lloyd(StopReason::exhausted);
    // Growing: an invalid region is split instead of inserting elsewhere.
    if (splits_left_ > 0 && split_invalid()) {
        --splits_left_;
        return start_stage(Phase::split);
    }
    // Far from the target, several proxies go in at once (into distinct regions): Lloyd
    // then runs once per batch rather than once per proxy.
    int batch = std::max(1, static_cast<int>(count * options_.insertion_batch));
    if (target > 0) batch = std::min(batch, target - count);
    insert_farthest(batch);
    if (static_cast<int>(proxies_.size()) == count) return end_lloyd(StopReason::exhausted);
    start_stage(Phase::insert);
}

void Engine::insert_farthest(int count) {
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
            if (labels_[f] != region || f == seeds_[region]) continue;
            double e = errors_[f];
            for (int k = g.begin(f); k < g.end(f); ++k)
                if (labels_[g.neighbor[k]] == region) e += errors_[g.neighbor[k]];
            if (e > worst_error) worst_error = e, worst = f;
        }
        add_proxy(worst);
        --count;
    }
}

bool Engine::split_invalid() {
    // The invalid region of largest error is split; one per decision, like an insertion.
    int chosen = -1, best[2] = {-1, -1};
    const int count = static_cast<int>(proxies_.size());
    for (int i = 0; i < count; ++i) {
        if (proxies_[i].faces < 2 * options_.min_quadric_faces) continue;
        if (chosen >= 0 && proxies_[i].error <= proxies_[chosen].error) continue;
        const Classification c = classify_unit(i);
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
    proxies_[chosen].quadric = quadrics_[chosen] = plane_through(best[0]);
    proxies_[chosen].fitted = false;
    evaluate();
    proxies_[chosen].seed = seeds_[chosen] = best[0];
    add_proxy(best[1]);
    return true;
}

bool Engine::merge_cheapest(bool gated) {
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
        const Fit fit = a.faces + b.faces < options_.min_quadric_faces ? fit_plane(united) : fit_region(united, options_.fit);
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
    p.quadric = quadrics_[keep] = best_fit.quadric;
    p.fit_error = best_fit.mean_squared;
    p.fitted = true;
    for (int& l : labels_)
        if (l == gone) l = keep;
    remove_proxy(gone);
    evaluate();
    return true;
}

Quadric Engine::plane_through(int face) const {
    const Triangle& t = model_.triangles[face];
    const Vec3 normal =
        (model_.points[t[1]] - model_.points[t[0]]).cross(model_.points[t[2]] - model_.points[t[0]]).normalized();
    return normalized(Quadric::plane(normal, model_.barycentres[face]));
}

void Engine::add_proxy(int seed) {
    Proxy p;
    p.quadric = plane_through(seed);
    p.seed = seed;
    proxies_.push_back(p);
    quadrics_.push_back(p.quadric);
    seeds_.push_back(seed);
}

void Engine::remove_proxy(int index) {
    proxies_.erase(proxies_.begin() + index);
    quadrics_.erase(quadrics_.begin() + index);
    seeds_.erase(seeds_.begin() + index);
    for (int& l : labels_)
        if (l > index) --l;
}

}  // namespace vqsa
