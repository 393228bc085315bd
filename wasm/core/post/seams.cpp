#include "post/seams.h"

#include "fitting/distance.h"
#include "fitting/face_errors.h"
#include "fitting/least_squares.h"
#include "geometry/features.h"

#include <algorithm>
#include <optional>
#include <set>

namespace vqsa {

struct SeamSimplifier::Region {
    std::vector<int> faces;
    double error = 0;  // Σ d(t, P) under its chosen surface
};

struct SeamSimplifier::HandOver {
    int region[2];  // the plane's, the other's
    std::vector<int> faces[2];
    Moments moments[2];
    ModelChoice choice[2];
    int parameters = 0;
    double error = 0;
    bool better_than(const HandOver& o) const {
        return parameters != o.parameters ? parameters < o.parameters : error < o.error;
    }
};

SeamSimplifier::SeamSimplifier(const Model& model, std::vector<int>& labels, std::vector<Proxy>& proxies,
                               std::vector<ModelChoice>& choices, const std::vector<char>* crease,
                               const std::vector<double>* roughness, bool noisy, const SeamOptions& options,
                               const std::vector<char>* may_change)
    : model_(model), labels_(labels), proxies_(proxies), choices_(choices), crease_(crease), roughness_(roughness),
      selection_roughness_(noisy ? roughness : nullptr),
      may_change_(may_change),
      options_(options),
      regions_(proxies.size()), in_strip_(model.face_count(), 0), vertex_kept_(model.points.size(), 0),
      depth_(model.face_count(), -1) {
    for (int r = 0; r < static_cast<int>(proxies.size()); ++r) queue_.push_back(r);
    evaluator_.reset(model, quadrics_of(proxies));
    for (int f = 0; f < model.face_count(); ++f) {
        regions_[labels[f]].faces.push_back(f);
        regions_[labels[f]].error += evaluator_(f, labels[f]);
    }
}

SeamSimplifier::~SeamSimplifier() = default;

bool SeamSimplifier::step() {
    if (next_ >= queue_.size()) return false;
    simplify(queue_[next_++]);
    return next_ < queue_.size();
}

Samples SeamSimplifier::samples_of(const std::vector<int>& faces) const {
    return region_samples(model_, faces, selection_roughness_);
}

double SeamSimplifier::fraction() const { return queue_.empty() ? 1 : double(next_) / queue_.size(); }

void SeamSimplifier::simplify(int a) {
    const DualGraph& g = model_.graph;
    auto link_open = [&](int e) { return !crease_ || !(*crease_)[e]; };
    const int plane_parameters = degrees_of_freedom(QuadricType::plane);
    auto faces_without = [&](int r, const std::vector<int>& strip) {
        for (int f : strip) in_strip_[f] = 1;
        std::vector<int> rest;
        for (int f : regions_[r].faces)
            if (!in_strip_[f]) rest.push_back(f);
        for (int f : strip) in_strip_[f] = 0;
        return rest;
    };
    // A first look at a region without a strip (`rest`), on a few hundred of its vertices:
    // most seams of a free-form surface change no type, and this tells them cheaply.
    auto screen = [&](const std::vector<int>& rest) {
        return select_model(thinned(samples_of(rest), options_.screening_samples),
                            fit_region(moments_of(model_, rest), options_.lloyd.fit).quadric, options_.selection);
    };
    // Whether every vertex of the strip is also one of `rest`.
    auto keeps_every_vertex = [&](const std::vector<int>& rest, const std::vector<int>& strip) {
        for (int f : rest)
            for (int v : model_.triangles[f]) vertex_kept_[v] = 1;
        bool all = true;
        for (int f : strip)
            for (int v : model_.triangles[f]) all = all && vertex_kept_[v];
        for (int f : rest)
            for (int v : model_.triangles[f]) vertex_kept_[v] = 0;
        return all;
    };
    if (choices_[a].chosen.parameters <= plane_parameters || !may_change(a)) return;
    std::set<int> neighbours;
    for (int f : regions_[a].faces)
        for (int e = g.begin(f); e < g.end(f); ++e)
            if (labels_[g.neighbor[e]] != a && link_open(e) && may_change(labels_[g.neighbor[e]]))
                neighbours.insert(labels_[g.neighbor[e]]);
    for (int b : neighbours) {
        if (!(proxies_[b].area > 0)) continue;
        const double mse = regions_[b].error / proxies_[b].area;
        auto explained = [&](int f) { return evaluator_(f, b) <= options_.tolerance * mse * model_.areas[f]; };
        // The faces of a reached from b across open edges, flooding while `joins` them, up
        // to `rings` faces deep; empty when it grows beyond max_fraction of a.
        auto strip_from_b = [&](const auto& joins) {
            std::vector<int> strip, depth;
            double strip_area = 0;
            bool too_large = false;
            for (int f : regions_[a].faces)
                for (int e = g.begin(f); e < g.end(f); ++e)
                    if (labels_[g.neighbor[e]] == b && link_open(e) && !in_strip_[f] && joins(f)) {
                        in_strip_[f] = 1, strip.push_back(f), depth.push_back(1);
                        break;
                    }
            for (std::size_t k = 0; k < strip.size() && !too_large; ++k) {
                strip_area += model_.areas[strip[k]];
                too_large = strip_area > options_.max_fraction * proxies_[a].area;
                for (int e = g.begin(strip[k]); e < g.end(strip[k]); ++e) {
                    const int h = g.neighbor[e];
                    if (labels_[h] != a || in_strip_[h] || !link_open(e) || !joins(h)) continue;
                    if (depth[k] == options_.rings) continue;
                    in_strip_[h] = 1, strip.push_back(h), depth.push_back(depth[k] + 1);
                }
            }
            for (int f : strip) in_strip_[f] = 0;
            if (too_large) strip.clear();
            return strip;
        };
        std::vector<int> strip = strip_from_b(explained);
        // b may be no exact surface itself (a band of a torus fillet, which no quadric
        // holds): then its surface explains none of a's faces. The strip is then a's faces
        // next to b, judged below by b's surface refitted with them.
        const bool by_refit = strip.empty();
        if (by_refit) strip = strip_from_b([](int) { return true; });
        if (strip.empty()) continue;
        // A strip that takes none of a's vertices leaves the vertices its selection judges
        // as they are: no simpler type (on coarse meshes, most one-face-deep strips).
        const std::vector<int> without_strip = faces_without(a, strip);
        if (keeps_every_vertex(without_strip, strip)) continue;
        // By its refit only for a region that is, without the strip, exactly a quadric
        // through its vertices (an exact CAD face): a free-form region never is, and the
        // selections below are not spent on it.
        if (by_refit) {
            const Samples vertices = vertex_samples(model_.points, model_.triangles, without_strip);
            if (!(taubin_rms(vertices, fit_taubin(moments_of(vertices)).quadric) <= kStoredPrecision)) continue;
        }
        // Of those, the faces b explains better than a's surface without them does: a
        // band of a's own faces near the seam, within b's error, stays.
        const ModelChoice without = screen(without_strip);
        if (without.chosen.parameters >= choices_[a].chosen.parameters) continue;
        if (by_refit && !elementary(without.chosen)) continue;
        std::vector<int> kept_strip;
        if (by_refit) {
            kept_strip = refitted_strip(b, strip, without.chosen.quadric);
        } else {
            FaceErrors rival;
            rival.reset(model_, {without.chosen.quadric});
            for (int f : strip)
                if (evaluator_(f, b) < rival(f, 0)) kept_strip.push_back(f);
        }
        if (kept_strip.empty()) continue;
        strip = std::move(kept_strip);
        std::vector<int> rest = faces_without(a, strip);
        if (rest.size() < 3) continue;
        const Moments rest_moments = moments_of(model_, rest);
        const ModelChoice simpler =
            select_model(samples_of(rest), fit_region(rest_moments, options_.lloyd.fit).quadric, options_.selection);
        if (simpler.chosen.parameters >= choices_[a].chosen.parameters) continue;
        std::vector<int> grown = regions_[b].faces;
        grown.insert(grown.end(), strip.begin(), strip.end());
        Moments grown_moments = proxies_[b].moments;
        for (int f : strip) add_to(grown_moments, model_.moments[f]);
        const ModelChoice kept =
            select_model(samples_of(grown), fit_region(grown_moments, options_.lloyd.fit).quadric, options_.selection);
        if (kept.chosen.type != choices_[b].chosen.type) continue;

        for (int f : strip) labels_[f] = b;
        commit(a, std::move(rest), rest_moments, simpler);
        commit(b, std::move(grown), grown_moments, kept);
        evaluator_.reset(model_, quadrics_of(proxies_));
        measure(a), measure(b);
        // a changed: its other seams are judged anew, if it is still not a plane.
        if (choices_[a].chosen.parameters <= plane_parameters) return;
    }
    // Both ways: a's half fillet may lie on a plane within the noise as well.
    for (int b : neighbours) {
        std::optional<HandOver> best = hand_over(a, b);
        if (std::optional<HandOver> back = hand_over(b, a); back && (!best || back->better_than(*best))) best = back;
        if (!best) continue;
        for (int i : {0, 1}) {
            for (int f : best->faces[i]) labels_[f] = best->region[i];
            commit(best->region[i], std::move(best->faces[i]), best->moments[i], best->choice[i]);
        }
        evaluator_.reset(model_, quadrics_of(proxies_));
        measure(a), measure(b);
        // The other region's seams are judged anew (each hand-over takes parameters away:
        // this ends).
        queue_.push_back(b);
        if (choices_[a].chosen.parameters <= plane_parameters) return;
    }
}

std::vector<int> SeamSimplifier::refitted_strip(int b, const std::vector<int>& strip, const Quadric& surface) const {
    // The strip's faces with a vertex off the giving region's exact surface: not of it.
    const double hessian_norm = surface.hessian_norm();
    std::vector<int> kept;
    for (int f : strip)
        for (int v : model_.triangles[f])
            if (taubin_distance(surface, hessian_norm, model_.points[v]) > kStoredPrecision) {
                kept.push_back(f);
                break;
            }
    if (kept.empty()) return kept;
    Moments m = proxies_[b].moments;
    for (int f : kept) add_to(m, model_.moments[f]);
    FaceErrors grown;
    grown.reset(model_, {fit_region(m, options_.lloyd.fit).quadric});
    double own = 0;
    for (int f : regions_[b].faces) own += grown(f, 0);
    // b must hold its own faces about as well as before.
    if (!(own <= options_.tolerance * regions_[b].error)) kept.clear();
    return kept;
}

bool SeamSimplifier::reached_without_creases(int r, const std::vector<int>& before, std::size_t faces) {
    if (!crease_) return true;
    const DualGraph& g = model_.graph;
    std::vector<int> reached;
    for (int f : before)
        if (labels_[f] == r) depth_[f] = 0, reached.push_back(f);
    for (std::size_t k = 0; k < reached.size(); ++k)
        for (int e = g.begin(reached[k]); e < g.end(reached[k]); ++e) {
            const int h = g.neighbor[e];
            if (labels_[h] == r && depth_[h] < 0 && !(*crease_)[e]) depth_[h] = 0, reached.push_back(h);
        }
    for (int f : reached) depth_[f] = -1;
    return reached.size() == faces;
}

void SeamSimplifier::commit(int r, std::vector<int> faces, const Moments& moments, const ModelChoice& choice) {
    Proxy& p = proxies_[r];
    p.moments = moments;
    p.area = moments[0];
    p.faces = static_cast<int>(faces.size());
    p.quadric = choice.chosen.quadric;
    choices_[r] = choice;
    regions_[r].faces = std::move(faces);
}

bool SeamSimplifier::may_change(int r) const { return !may_change_ || (*may_change_)[r]; }

double SeamSimplifier::noise_energy(const std::vector<int>& faces) const {
    double noise = 0;
    for (int f : faces) noise += face_noise(model_, *roughness_, f);
    return options_.lloyd.noise_factor * options_.lloyd.noise_factor * noise;
}

void SeamSimplifier::measure(int r) {
    regions_[r].error = 0;
    for (int f : regions_[r].faces) regions_[r].error += evaluator_(f, r);
}

std::optional<SeamSimplifier::HandOver> SeamSimplifier::hand_over(int a, int b) {
    const DualGraph& g = model_.graph;
    auto link_open = [&](int e) { return !crease_ || !(*crease_)[e]; };
    if (!roughness_ || !may_change(a) || !may_change(b) || choices_[a].chosen.parameters <= degrees_of_freedom(QuadricType::plane) ||
        !(regions_[a].error <= noise_energy(regions_[a].faces)))
        return std::nullopt;
    // a's faces by their distance from b, in face rings across open links; the ones no
    // ring reaches (behind creases) count as farthest.
    std::vector<int> order;
    for (int f : regions_[a].faces)
        for (int e = g.begin(f); e < g.end(f); ++e)
            if (labels_[g.neighbor[e]] == b && link_open(e)) {
                depth_[f] = 0, order.push_back(f);
                break;
            }
    if (order.empty()) return std::nullopt;
    for (std::size_t k = 0; k < order.size(); ++k)
        for (int e = g.begin(order[k]); e < g.end(order[k]); ++e) {
            const int h = g.neighbor[e];
            if (labels_[h] == a && depth_[h] < 0 && link_open(e)) depth_[h] = depth_[order[k]] + 1, order.push_back(h);
        }
    for (int f : regions_[a].faces)
        if (depth_[f] < 0) order.push_back(f);
    for (int f : order) depth_[f] = -1;
    // The farther half, by area.
    std::vector<int> far, near;
    double far_area = 0;
    for (auto f = order.rbegin(); f != order.rend(); ++f)
        if (far_area < 0.5 * proxies_[a].area) far.push_back(*f), far_area += model_.areas[*f];
        else near.push_back(*f);
    if (static_cast<int>(far.size()) < options_.lloyd.min_quadric_faces || near.empty()) return std::nullopt;
    const Fit plane = fit_plane(moments_of(model_, far));
    if (!(plane.mean_squared * far_area <= noise_energy(far))) return std::nullopt;

    // The near half goes to b, a is the plane, and local Lloyd settles where the plane ends;
    // b free, then b as each type of fewer parameters than the free trial gave it (below).
    const std::vector<int> before_a = regions_[a].faces, before_b = regions_[b].faces;
    const std::vector<Proxy> saved = proxies_;  // local Lloyd re-evaluates every region
    const int parameters_before = choices_[a].chosen.parameters + choices_[b].chosen.parameters;
    const double error_before = regions_[a].error + regions_[b].error;
    std::optional<HandOver> best;
    auto restore = [&] {
        for (int f : before_a) labels_[f] = a;
        for (int f : before_b) labels_[f] = b;
        proxies_ = saved;
    };
    const std::pair<ImposedType, int> types[] = {{ImposedType::none, 0},
                                                 {ImposedType::sphere, degrees_of_freedom(QuadricType::sphere)},
                                                 {ImposedType::cylinder, degrees_of_freedom(QuadricType::cylinder)},
                                                 {ImposedType::cone, degrees_of_freedom(QuadricType::cone)}};
    // The imposed types follow a free trial that left no more error than the pair had (b
    // free fits its faces at least as closely as any imposed type does), each with fewer
    // parameters than the data chose for b there: whether or not that trial paid in
    // parameters (b free may bend over a leg as a hyperbolic cylinder, where a cylinder on
    // the fillet alone costs less).
    int free_parameters = 0;
    for (const auto& [type, parameters] : types) {
        if (type != ImposedType::none && parameters >= free_parameters) continue;
        for (int f : near) labels_[f] = b;
        std::vector<char> active(proxies_.size(), 0);
        active[a] = active[b] = 1;
        std::vector<ImposedType> imposed(proxies_.size(), ImposedType::none);
        imposed[a] = ImposedType::plane, imposed[b] = type;
        {
            LocalLloyd local(model_, options_.lloyd, labels_, proxies_, std::move(active), std::move(imposed), crease_,
                             options_.hand_over_iterations);
            while (local.step()) {
            }
        }
        HandOver t;
        t.region[0] = a, t.region[1] = b;
        for (const std::vector<int>* region : {&before_a, &before_b})
            for (int f : *region) t.faces[labels_[f] == a ? 0 : 1].push_back(f);
        // A hand-over moves faces across a tangent seam; local Lloyd may carry b across a
        // crease instead (on the noisy plate assembly, b over both faces of a plate: an
        // elliptic paraboloid thin enough to wrap it, one part, which no validity test sees).
        const bool across_a_crease = !reached_without_creases(b, before_b, t.faces[1].size());
        restore();
        if (across_a_crease || t.faces[0].size() < 3 || t.faces[1].size() < 3) continue;
        // a is the plane (no type has fewer parameters, so the data's choice would be the
        // plane or give way to it); b is the data's choice, or the imposed type where that has
        // fewer parameters: the pair is judged as a whole, below.
        for (int i : {0, 1}) {
            t.moments[i] = moments_of(model_, t.faces[i]);
            const Samples samples = samples_of(t.faces[i]);
            const Quadric general = fit_region(t.moments[i], options_.lloyd.fit).quadric;
            ModelSelectionOptions selection = options_.selection;
            if (i == 0) selection.imposed = ImposedType::plane, selection.rivals = false;
            t.choice[i] = select_model(samples, general, selection);
            if (i == 0 || type == ImposedType::none || t.choice[i].chosen.parameters <= parameters) continue;
            selection.imposed = type;
            try {
                t.choice[i] = select_model(samples, general, selection);
            } catch (const std::invalid_argument&) {  // no such fit: the data's choice stands
            }
        }
        t.parameters = t.choice[0].chosen.parameters + t.choice[1].chosen.parameters;
        FaceErrors after;
        after.reset(model_, {t.choice[0].chosen.quadric, t.choice[1].chosen.quadric});
        for (int i : {0, 1})
            for (int f : t.faces[i]) t.error += after(f, i);
        if (type == ImposedType::none && t.error <= error_before) free_parameters = t.choice[1].chosen.parameters;
        if (t.parameters >= parameters_before || !(t.error <= error_before)) continue;
        if (!best || t.better_than(*best)) best = std::move(t);
    }
    // The trials' plane skips the rivals (every trial would pay for their fits); the one
    // kept gets them, for the report's runner-up.
    if (best) {
        ModelSelectionOptions selection = options_.selection;
        selection.imposed = ImposedType::plane;
        best->choice[0] = select_model(samples_of(best->faces[0]),
                                       fit_region(best->moments[0], options_.lloyd.fit).quadric, selection);
    }
    return best;
}

}  // namespace vqsa
