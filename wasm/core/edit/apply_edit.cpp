#include "edit/apply_edit.h"

#include "fitting/face_errors.h"
#include "fitting/samples.h"
#include "lloyd/lloyd.h"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace vqsa {

namespace {

// The region's face farthest from its surface (the first of equals).
int worst_face(const Model& model, const std::vector<int>& labels, const Proxy& proxy, int region) {
    FaceErrors errors;
    errors.reset(model, {proxy.quadric});
    int worst = -1;
    double largest = -1;
    for (int f = 0; f < model.face_count(); ++f) {
        if (labels[f] != region) continue;
        // Per unit area: a large face is not worse for being large.
        const double e = errors(f, 0) / std::max(model.areas[f], 1e-300);
        if (e > largest) largest = e, worst = f;
    }
    return worst;
}

// A new region seeded at `face`, taken from its region.
int add_region(const Model& model, int face, Pipeline::State& s) {
    const int added = static_cast<int>(s.proxies.size());
    Proxy p;
    p.quadric = plane_through(model, face);
    p.seed = face;
    s.proxies.push_back(p);
    if (!s.choices.empty()) s.choices.emplace_back();
    s.locked.push_back(0);
    s.imposed.push_back(ImposedType::none);
    s.labels[face] = added;
    return added;
}

// Steps across edges from `from` to every face of `region` (-1 elsewhere), breadth first.
std::vector<int> steps_within(const Model& model, const std::vector<int>& labels, int region, int from) {
    std::vector<int> steps(labels.size(), -1), queue{from};
    steps[from] = 0;
    for (std::size_t i = 0; i < queue.size(); ++i) {
        const int f = queue[i];
        for (int e = model.graph.begin(f); e < model.graph.end(f); ++e) {
            const int n = model.graph.neighbor[e];
            if (labels[n] == region && steps[n] < 0) steps[n] = steps[f] + 1, queue.push_back(n);
        }
    }
    return steps;
}

void remove_region(int gone, Pipeline::State& s) {
    s.proxies.erase(s.proxies.begin() + gone);
    if (!s.choices.empty()) s.choices.erase(s.choices.begin() + gone);
    s.locked.erase(s.locked.begin() + gone);
    s.imposed.erase(s.imposed.begin() + gone);
    for (int& l : s.labels)
        if (l > gone) --l;
}

}  // namespace

void halve_for_new_region(const Model& model, std::vector<int>& labels, int added) {
    int face = -1;
    for (int f = 0; f < model.face_count() && face < 0; ++f)
        if (labels[f] == added) face = f;
    if (face < 0) return;
    // The region it was taken from: where its face's neighbours lie.
    int from = -1;
    for (int e = model.graph.begin(face); e < model.graph.end(face) && from < 0; ++e)
        if (labels[model.graph.neighbor[e]] != added) from = labels[model.graph.neighbor[e]];
    if (from < 0) return;
    for (int& l : labels)
        if (l == added) l = from;
    const std::vector<int> from_face = steps_within(model, labels, from, face);
    const int far = static_cast<int>(std::max_element(from_face.begin(), from_face.end()) - from_face.begin());
    const std::vector<int> from_far = steps_within(model, labels, from, far);
    for (int f = 0; f < model.face_count(); ++f)
        if (from_face[f] >= 0 && from_face[f] < from_far[f]) labels[f] = added;
}

std::vector<char> apply_edit(const Model& model, const LloydOptions& options, const Edit& e, Pipeline::State& s) {
    // Every check comes before the first change (sizing the per-region flags changes nothing).
    const int count = static_cast<int>(s.proxies.size());
    s.locked.resize(count, 0);
    s.imposed.resize(count, ImposedType::none);
    auto region_name = [](int r) { return "region " + std::to_string(r); };
    auto check_region = [&](int r) {
        if (r < 0 || r >= count)
            throw std::invalid_argument(region_name(r) + " does not exist (the result has " + std::to_string(count) +
                                        " regions)");
    };
    auto check_unlocked = [&](int r) {
        check_region(r);
        if (s.locked[r]) throw std::invalid_argument(region_name(r) + " is locked: unlock it first");
    };
    auto check_divisible = [&](int r) {
        if (faces_of(s.labels, r).size() < 2)
            throw std::invalid_argument(region_name(r) + " has a single face");
    };

    std::vector<char> touched;
    auto touch = [&](std::initializer_list<int> regions) {
        touched.assign(s.proxies.size(), 0);
        for (int r : regions) touched[r] = 1;
    };
    switch (e.kind) {
        case EditKind::lock:
        case EditKind::unlock:
            check_region(e.region);
            s.locked[e.region] = e.kind == EditKind::lock;
            return {};
        case EditKind::set_type: {
            check_unlocked(e.region);
            ModelSelectionOptions selection;
            selection.classify = options.classify;
            selection.imposed = e.type;
            if (e.type != ImposedType::none) {
                try {
                    select_model(region_samples(model, faces_of(s.labels, e.region)),
                                 s.proxies[e.region].quadric, selection);
                } catch (const std::invalid_argument&) {
                    throw std::invalid_argument(std::string("no ") + imposed_type_name(e.type) + " fits " +
                                                region_name(e.region));
                }
            }
            s.imposed[e.region] = e.type;
            touch({e.region});
            break;
        }
        case EditKind::merge: {
            check_unlocked(e.region);
            check_unlocked(e.other);
            if (e.region == e.other) throw std::invalid_argument("merge needs two different regions");
            const auto pairs = adjacent_regions(model, s.labels);
            if (!std::binary_search(pairs.begin(), pairs.end(), std::pair<int, int>(std::minmax(e.region, e.other))))
                throw std::invalid_argument(region_name(e.region) + " and " + region_name(e.other) + " are not adjacent");
            for (int& l : s.labels)
                if (l == e.other) l = e.region;
            remove_region(e.other, s);
            touch({e.region > e.other ? e.region - 1 : e.region});
            break;
        }
        case EditKind::split: {
            check_unlocked(e.region);
            check_divisible(e.region);
            int face = e.face;
            if (face >= 0 && (face >= model.face_count() || s.labels[face] != e.region))
                throw std::invalid_argument("face " + std::to_string(face) + " is not in " + region_name(e.region));
            if (face < 0) face = worst_face(model, s.labels, s.proxies[e.region], e.region);
            const int added = add_region(model, face, s);
            touch({e.region, added});
            break;
        }
        case EditKind::add_seed: {
            if (e.face < 0 || e.face >= model.face_count())
                throw std::invalid_argument("face " + std::to_string(e.face) + " does not exist");
            const int region = s.labels[e.face];
            if (s.locked[region])
                throw std::invalid_argument("face " + std::to_string(e.face) + " lies in " + region_name(region) +
                                            ", which is locked");
            check_divisible(region);
            const int added = add_region(model, e.face, s);
            touch({region, added});
            break;
        }
    }
    // A merge or a split divides exactly the faces of the regions it names; an imposed type
    // moves the boundaries with the unlocked neighbours as well, towards its surface.
    std::vector<char> active = touched;
    if (e.kind == EditKind::set_type)
        for (const auto& [a, b] : adjacent_regions(model, s.labels)) {
            if (touched[a] && !s.locked[b]) active[b] = 1;
            if (touched[b] && !s.locked[a]) active[a] = 1;
        }
    return active;
}

}  // namespace vqsa
