#include "pipeline/pipeline.h"

#include "edit/apply_edit.h"
#include "fitting/model_selection.h"
#include "fitting/special_fit.h"
#include "lloyd/local_lloyd.h"
#include "lloyd/lloyd.h"
#include "post/graph_cut.h"
#include "post/project.h"
#include "post/seams.h"

#include <chrono>
#include <cmath>
#include <stdexcept>
#include <tuple>

namespace vqsa {

const char* stage_name(Stage stage) {
    switch (stage) {
        case Stage::lloyd: return "lloyd";
        case Stage::smooth: return "smooth";
        case Stage::refit: return "refit";
        case Stage::project: return "project";
        case Stage::measure: return "measure";
        case Stage::done: return "done";
    }
    return "unknown";
}

// One stage of the run: step() does a bounded piece of it, false once it is finished.
class PipelineStage {
public:
    virtual ~PipelineStage() = default;
    virtual Stage id() const = 0;
    virtual bool step() = 0;
    virtual double fraction() const = 0;
};

namespace {

using State = Pipeline::State;

// The Lloyd engine is built at the stage's first step (feature detection and the first
// fits: a piece of its own), so constructing a pipeline costs little.
class LloydStage : public PipelineStage {
public:
    LloydStage(const Model& model, const LloydOptions& options, State& state)
        : model_(model), options_(options), state_(state) {}
    Stage id() const override { return Stage::lloyd; }
    double fraction() const override { return lloyd_ ? lloyd_->fraction() : 0; }
    const Lloyd* lloyd() const { return lloyd_.get(); }
    void cancel() {
        if (lloyd_) lloyd_->cancel();
    }

    bool step() override {
        if (!lloyd_) {
            lloyd_ = std::make_unique<Lloyd>(model_, options_);
            return true;
        }
        const bool more = lloyd_->step();
        state_.phase = operation_name(lloyd_->last_operation());
        state_.iterations = lloyd_->iterations();
        if (more) return true;
        state_.stop_reason = lloyd_->stop_reason();
        state_.labels = state_.lloyd_labels = lloyd_->labels();
        state_.proxies = lloyd_->proxies();
        state_.energy = lloyd_->energy();
        state_.settled = lloyd_->settled();
        if (options_.init == Initialization::features) state_.crease = lloyd_->features().crease;
        state_.roughness = std::make_shared<const std::vector<double>>(lloyd_->features().roughness);
        state_.noisy = lloyd_->noisy();
        lloyd_.reset();  // a finished stage's working memory goes (on large meshes, hundreds of MB)
        return false;
    }

private:
    const Model& model_;
    const LloydOptions& options_;
    State& state_;
    std::unique_ptr<Lloyd> lloyd_;
};

// An edit's Lloyd: iterations on the regions it touched and their neighbours, one per step.
// A split's or a seed's new region (the last) that Lloyd leaves a strip starts again from
// half of its old region (halve_for_new_region).
class EditLloydStage : public PipelineStage {
public:
    EditLloydStage(const Model& model, const Options& options, State& state, std::vector<char> regions, const char* phase,
                   bool divides)
        : model_(model), options_(options), state_(state), regions_(std::move(regions)), phase_(phase) {
        if (divides) start_ = {state.labels, state.proxies};
    }
    Stage id() const override { return Stage::lloyd; }
    double fraction() const override { return local_ ? local_->fraction() : 0; }

    bool step() override {
        state_.phase = phase_;
        if (!local_) {
            local_ = std::make_unique<LocalLloyd>(model_, options_.lloyd, state_.labels, state_.proxies, regions_,
                                                  state_.imposed, state_.crease.empty() ? nullptr : &state_.crease);
            state_.energy = local_->energy();
            return true;
        }
        const bool more = local_->step();
        state_.energy = local_->energy();
        if (more) return true;
        local_.reset();
        const int added = static_cast<int>(state_.proxies.size()) - 1;
        if (!start_.first.empty() &&
            is_strip(model_, state_.labels, faces_of(state_.labels, added), options_.lloyd.min_quadric_faces)) {
            state_.labels = std::move(start_.first);
            state_.proxies = std::move(start_.second);
            start_ = {};
            halve_for_new_region(model_, state_.labels, added);
            return true;
        }
        state_.lloyd_labels = state_.labels;
        return false;
    }

private:
    const Model& model_;
    const Options& options_;
    State& state_;
    std::vector<char> regions_;
    const char* phase_;
    std::pair<std::vector<int>, std::vector<Proxy>> start_;  // labels and proxies as the edit left them
    std::unique_ptr<LocalLloyd> local_;
};

// Graph-cut smoothing, one boundary per step; then every region is refitted. With
// `regions` (an edit's), only boundaries between two of them, and only they are refitted.
class SmoothStage : public PipelineStage {
public:
    SmoothStage(const Model& model, const Options& options, State& state, std::vector<char> regions)
        : model_(model), options_(options), state_(state), regions_(std::move(regions)) {}
    Stage id() const override { return Stage::smooth; }
    double fraction() const override {
        return smoother_ && smoother_->pair_count() > 0 ? double(smoother_->pairs_done()) / smoother_->pair_count() : 0;
    }

    bool step() override {
        state_.phase = "smooth";
        if (!smoother_)
            smoother_ = std::make_unique<BoundarySmoother>(model_, quadrics_of(state_.proxies), state_.labels,
                                                           seeds_of(state_.proxies), options_.smoothing,
                                                           state_.crease.empty() ? nullptr : &state_.crease,
                                                           regions_.empty() ? nullptr : &regions_);
        if (smoother_->step()) return true;
        smoother_.reset();
        // Straighter boundaries are worth a little distance, not a worse fit: when the
        // regions refitted to their new faces lie farther from them by more than a tenth,
        // the Lloyd boundaries stay.
        const std::vector<Proxy> before = state_.proxies;
        refit_regions(model_, state_.labels, options_.lloyd, state_.proxies, regions_);
        FaceErrors evaluator;
        std::vector<double> errors;
        const double energy = evaluate_regions(model_, state_.labels, state_.proxies, errors, evaluator);
        if (energy <= 1.1 * state_.energy + 1e-300) {
            state_.energy = energy;
        } else {
            state_.labels = state_.lloyd_labels;
            state_.proxies = before;
        }
        return false;
    }

private:
    const Model& model_;
    const Options& options_;
    State& state_;
    std::vector<char> regions_;
    std::unique_ptr<BoundarySmoother> smoother_;
};

// Each region's type by model selection over its vertices (the imposed one, if any), one
// region per step; then the tangent seams, one region per step. With `regions` (an edit's),
// only those. Without the refit option, each region's own quadric typed, one per step.
class RefitStage : public PipelineStage {
public:
    RefitStage(const Model& model, const Options& options, State& state, std::vector<char> regions)
        : model_(model), options_(options), state_(state), regions_(std::move(regions)) {
        // One selection for every region and for the seams between them.
        seams_.selection.classify = options.lloyd.classify;
        seams_.lloyd = options.lloyd;
    }
    Stage id() const override { return Stage::refit; }
    double fraction() const override {
        const double count = state_.proxies.empty() ? 1 : double(state_.proxies.size());
        if (!options_.refit) return next_ / count;
        const double seams = descending_ ? 1 : simplifier_ ? simplifier_->fraction() : 0;
        return 0.4 * (next_ / count) + 0.4 * seams + 0.2 * (descended_ / count);
    }

    bool step() override {
        state_.phase = "refit";
        const int count = static_cast<int>(state_.proxies.size());
        auto refitted = [&](int r) { return regions_.empty() || regions_[r]; };
        if (!started_) {
            started_ = true;
            if (regions_.empty()) state_.choices.clear();
            state_.choices.resize(count);
            region_faces_.assign(count, {});
            for (int f = 0; f < model_.face_count(); ++f)
                if (refitted(state_.labels[f])) region_faces_[state_.labels[f]].push_back(f);
        }
        while (next_ < count && !refitted(next_)) ++next_;
        if (!options_.refit) {
            if (next_ < count) {
                type_without_refit(next_);
                region_faces_[next_] = {};
                ++next_;
                return true;
            }
            if (retyped_) finish();
            return false;
        }
        if (next_ < count) {
            Proxy& p = state_.proxies[next_];
            const Samples vertices = typing_samples(next_);
            state_.choices[next_] = choose(next_, vertices);
            TypedFit& chosen = state_.choices[next_].chosen;
            // The type is chosen on the vertices one each; a plane's place, off a noisy mesh,
            // is fitted to them weighed by area. There the vertices lie on the part's faces,
            // so a plane through all of them is the same either way; but where a region holds
            // a face and the densely meshed first facets of a chamfer, countersink or fillet
            // beside it, vertices one each tilt the plane off the face toward them (Voron
            // Trident's z carriage: 0.2°, its median vertex 1.2e-3 of the size away). Under
            // noise each vertex is one measurement.
            if (!state_.noisy && chosen.type == QuadricType::plane)
                if (const auto plane = fit_plane_geometric(
                        vertex_samples(model_.points, model_.triangles, region_faces_[next_], VertexWeight::area)))
                    chosen.quadric = plane->quadric, chosen.shape = plane->shape,
                    chosen.rms = selection_rms(vertices, chosen.quadric);
            p.quadric = chosen.quadric;
            region_faces_[next_] = {};
            ++next_;
            return true;
        }
        if (!simplifier_) {
            // Regions with a type imposed keep their faces: the seams serve the data's choices.
            may_change_.assign(count, 1);
            for (int r = 0; r < count; ++r) may_change_[r] = refitted(r) && imposed(r) == ImposedType::none;
            simplifier_ = std::make_unique<SeamSimplifier>(model_, state_.labels, state_.proxies, state_.choices,
                                                           state_.crease.empty() ? nullptr : &state_.crease,
                                                           state_.roughness.get(), state_.noisy, seams_, &may_change_);
        }
        if (!descending_) {
            if (simplifier_->step()) return true;
            descending_ = true;
            // Last, once the seams have settled the faces: each general quadric descended to
            // its vertices' distances, each weighted by its share of the area (descend), which
            // the projection then follows. Only the regions that descend get their faces; no
            // region is without faces.
            std::vector<char> descending(count);
            for (int r = 0; r < count; ++r) descending[r] = may_change_[r] && descends(state_.choices[r].chosen);
            region_faces_.assign(count, {});
            for (int f = 0; f < model_.face_count(); ++f)
                if (descending[state_.labels[f]]) region_faces_[state_.labels[f]].push_back(f);
        }
        while (descended_ < count && region_faces_[descended_].empty()) ++descended_;
        if (descended_ < count) {
            const std::vector<int>& faces = region_faces_[descended_];
            const std::vector<double>* roughness = state_.noisy ? state_.roughness.get() : nullptr;
            ModelChoice& choice = state_.choices[descended_];
            choice = descend(region_samples(model_, faces, roughness, VertexWeight::area), choice, seams_.selection);
            // Reported as every type was scored, by its vertices alike.
            const Samples vertices = region_samples(model_, faces, roughness);
            choice.chosen.rms = selection_rms(vertices, choice.chosen.quadric);
            if (choice.runner_up) choice.runner_up->rms = selection_rms(vertices, choice.runner_up->quadric);
            state_.proxies[descended_].quadric = choice.chosen.quadric;
            region_faces_[descended_] = {};
            ++descended_;
            return true;
        }
        simplifier_.reset();
        finish();
        return false;
    }

private:
    void finish() {
        FaceErrors evaluator;
        std::vector<double> errors;
        state_.energy = evaluate_regions(model_, state_.labels, state_.proxies, errors, evaluator);
    }

    Samples typing_samples(int region) const {
        Samples vertices = region_samples(model_, region_faces_[region], state_.noisy ? state_.roughness.get() : nullptr);
        // The refit alone types by the scatter: the seam simplifier weighs types to move
        // faces, and a facet row along a tangent seam lies within the noise of both sides.
        if (state_.roughness)
            vertices.scatter = region_scatter(region_faces_[region], *state_.roughness, vertices.tolerance);
        return vertices;
    }

    // Without the refit a region keeps the quadric Lloyd fitted, typed by its affine type.
    // But Lloyd lets a region lie on a second part of its quadric by less than its split
    // threshold, and on one plane of a pair: such a quadric names no surface of the region,
    // which is then typed as the refit would type it. So a result names one surface per
    // region whatever the options.
    void type_without_refit(int region) {
        const Samples vertices = typing_samples(region);
        Proxy& p = state_.proxies[region];
        ModelChoice& choice = state_.choices[region];
        if (auto general = general_fit(p.quadric, vertices, seams_.selection.classify)) {
            choice = {*general, std::nullopt};
            return;
        }
        choice = choose(region, vertices);
        p.quadric = choice.chosen.quadric;
        retyped_ = true;
    }

    ImposedType imposed(int region) const {
        return region < static_cast<int>(state_.imposed.size()) ? state_.imposed[region] : ImposedType::none;
    }

    // Model selection over the region's vertices, of the type an edit imposed if it still fits.
    ModelChoice choose(int region, const Samples& vertices) const {
        const Quadric& general = state_.proxies[region].quadric;
        ModelSelectionOptions selection = seams_.selection;
        selection.imposed = imposed(region);
        try {
            return select_model(vertices, general, selection);
        } catch (const std::invalid_argument&) {  // the imposed type no longer fits: the data choose
            return select_model(vertices, general, seams_.selection);
        }
    }

    const Model& model_;
    const Options& options_;
    State& state_;
    std::vector<char> regions_;
    SeamOptions seams_;
    std::vector<char> may_change_;
    std::vector<std::vector<int>> region_faces_;
    std::unique_ptr<SeamSimplifier> simplifier_;
    bool started_ = false;
    int next_ = 0;
    bool descending_ = false;
    int descended_ = 0;
    bool retyped_ = false;
};

class ProjectStage : public PipelineStage {
public:
    ProjectStage(const Model& model, const Options& options, State& state)
        : model_(model), options_(options), state_(state) {}
    Stage id() const override { return Stage::project; }
    double fraction() const override { return projector_ ? projector_->fraction() : 0; }
    bool step() override {
        state_.phase = "project";
        if (!projector_) {
            std::vector<ProjectionTarget> targets;
            for (std::size_t i = 0; i < state_.proxies.size(); ++i) {
                std::optional<Classification> closed;
                if (i < state_.choices.size() && has_closed_form(state_.choices[i].chosen.type) &&
                    state_.choices[i].chosen.special)
                    closed = state_.choices[i].chosen.shape;
                targets.push_back({state_.proxies[i].quadric, closed});
            }
            projector_ = std::make_unique<Projector>(model_, state_.labels, targets, options_.max_projection_distance);
            return true;
        }
        if (projector_->step()) return true;
        state_.projected = projector_->take();
        projector_.reset();
        return false;
    }

private:
    const Model& model_;
    const Options& options_;
    State& state_;
    std::unique_ptr<Projector> projector_;
};

class MeasureStage : public PipelineStage {
public:
    MeasureStage(const Model& model, const Options& options, State& state)
        : model_(model), options_(options), state_(state) {}
    Stage id() const override { return Stage::measure; }
    double fraction() const override { return measurement_ ? measurement_->fraction() : 0; }
    bool step() override {
        state_.phase = "measure";
        if (!measurement_)
            measurement_ = std::make_unique<Measurement>(model_.points, state_.projected, model_.triangles, state_.labels,
                                                         static_cast<int>(state_.proxies.size()), options_.metrics);
        if (measurement_->step()) return true;
        state_.metrics = measurement_->result();
        measurement_.reset();
        return false;
    }

private:
    const Model& model_;
    const Options& options_;
    State& state_;
    std::unique_ptr<Measurement> measurement_;
};

double elapsed(std::chrono::steady_clock::time_point since) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - since).count();
}

}  // namespace

Pipeline::Pipeline(const Mesh& mesh, const Options& options) : Pipeline(mesh, nullptr, options) {}

Pipeline::Pipeline(const Mesh& mesh, std::shared_ptr<const Model> shared, const Options& options)
    : source_face_(mesh.source_face), options_(options) {
    validate(options_);
    if (mesh.triangles.empty()) throw std::invalid_argument("the mesh has no faces");
    if (shared && shared->face_count() != static_cast<int>(mesh.triangles.size()))
        throw std::invalid_argument("the model was not made from this mesh");
    shared_model_ = shared ? std::move(shared) : std::make_shared<const Model>(make_model(mesh));
    check_proxy_count(model(), options_.lloyd);
    input_ = {mesh.input_vertex_count,      mesh.input_face_count,    static_cast<int>(mesh.triangles.size()),
              model().component_count,       bounding_box(mesh).diagonal(), model().frame.scale};
    stages_.push_back(std::make_unique<LloydStage>(model(), options_.lloyd, state_));
    add_stages({});
}

void Pipeline::add_stages(const std::vector<char>& regions) {
    if (options_.smooth) stages_.push_back(std::make_unique<SmoothStage>(model(), options_, state_, regions));
    stages_.push_back(std::make_unique<RefitStage>(model(), options_, state_, regions));
    if (options_.project) {
        stages_.push_back(std::make_unique<ProjectStage>(model(), options_, state_));
        if (options_.measure) stages_.push_back(std::make_unique<MeasureStage>(model(), options_, state_));
    }
}

void Pipeline::edit(const Edit& edit) {
    if (!done() || editing_) throw std::invalid_argument("an edit needs a finished run");
    Edit in_model = edit;
    if (edit.face >= 0) {
        if (edit.face >= input_.faces) throw std::invalid_argument("face " + std::to_string(edit.face) + " does not exist");
        const auto kept = std::find(source_face_.begin(), source_face_.end(), edit.face);
        if (kept == source_face_.end())
            throw std::invalid_argument("face " + std::to_string(edit.face) + " was dropped (zero area)");
        in_model.face = static_cast<int>(kept - source_face_.begin());
    }
    State before = state_;
    const std::vector<char> regions = apply_edit(model(), options_.lloyd, in_model, state_);
    undo_.push_back(std::move(before));
    if (undo_.size() > kMaxUndo) undo_.erase(undo_.begin());
    redo_.clear();
    state_.edits.push_back(edit);
    state_.edit_seconds.push_back(0);
    stages_.clear();
    current_ = 0;
    cancel_requested_ = false;
    if (regions.empty()) return;  // lock, unlock: nothing moves
    editing_ = true;
    stages_.push_back(std::make_unique<EditLloydStage>(model(), options_, state_, regions, edit_kind_name(edit.kind),
                                                       edit.kind == EditKind::split || edit.kind == EditKind::add_seed));
    add_stages(regions);
}

bool Pipeline::undo() {
    if (!can_undo()) return false;
    redo_.push_back(std::move(state_));
    state_ = std::move(undo_.back());
    undo_.pop_back();
    return true;
}

bool Pipeline::redo() {
    if (!can_redo()) return false;
    undo_.push_back(std::move(state_));
    state_ = std::move(redo_.back());
    redo_.pop_back();
    return true;
}

Pipeline::~Pipeline() = default;

Stage Pipeline::stage() const { return current_ < stages_.size() ? stages_[current_]->id() : Stage::done; }

const Lloyd* Pipeline::running_lloyd() const {
    return current_ == 0 && !editing_ && !stages_.empty() ? static_cast<const LloydStage&>(*stages_[0]).lloyd() : nullptr;
}

const std::vector<int>& Pipeline::face_labels() const {
    return running_lloyd() ? running_lloyd()->labels() : state_.labels;
}

bool Pipeline::step() {
    if (done()) return false;
    const auto start = std::chrono::steady_clock::now();
    double& seconds = editing_ ? state_.edit_seconds.back() : seconds_[static_cast<int>(stage())];
    if (cancel_requested_ && editing_) {
        // A cancelled edit never happened.
        cancel_requested_ = false;
        editing_ = false;
        state_ = std::move(undo_.back());
        undo_.pop_back();
        current_ = stages_.size();
        return false;
    }
    if (cancel_requested_) {
        if (current_ == 0) {
            // The Lloyd stage ends with a consistent partition; nothing runs after it.
            auto& lloyd = static_cast<LloydStage&>(*stages_[0]);
            if (lloyd.lloyd()) {
                lloyd.cancel();
                lloyd.step();
            }
        }
        state_.stop_reason = StopReason::cancelled;
        state_.phase = "done";
        current_ = stages_.size();
        seconds += elapsed(start);
        return false;
    }
    const bool more = stages_[current_]->step();
    if (!more) {
        ++current_;
        if (current_ == 1 && !editing_ && state_.stop_reason == StopReason::cancelled) current_ = stages_.size();
        if (done()) state_.phase = "done", editing_ = false;
    }
    seconds += elapsed(start);
    return !done();
}

void Pipeline::run(const ProgressCallback& progress) {
    while (!done()) {
        step();
        if (progress && !progress(this->progress())) {
            cancel();
            step();
        }
    }
}

Progress Pipeline::progress() const {
    Progress p;
    p.stage = stage();
    p.phase = state_.phase;
    p.iterations = state_.iterations;
    const Lloyd* lloyd = running_lloyd();
    if (current_ == 0 && !editing_ && !done()) {
        p.proxies = lloyd ? static_cast<int>(lloyd->proxies().size()) : 0;
        p.rms = lloyd ? lloyd->rms() : 0;
    } else {
        p.proxies = static_cast<int>(state_.proxies.size());
        p.rms = model().total_area > 0 ? std::sqrt(std::max(0.0, state_.energy) / model().total_area) : 0;
    }
    std::tie(p.settled_proxies, p.settled_rms) = lloyd ? lloyd->settled() : state_.settled;
    p.fraction = done() ? 1 : stages_[current_]->fraction();
    return p;
}

Result Pipeline::result(double load_seconds) const {
    Result r;
    r.input = input_;
    r.options = options_;
    r.stop_reason = state_.stop_reason;
    r.iterations = state_.iterations;
    const Progress now = progress();
    r.rms_error_relative = now.rms;
    r.rms_error = now.rms * model().frame.scale;
    auto seconds = [&](Stage s) { return seconds_[static_cast<int>(s)]; };
    Timing& t = r.timing;
    t.load = load_seconds;
    t.lloyd = seconds(Stage::lloyd);
    t.smooth = seconds(Stage::smooth);
    t.refit = seconds(Stage::refit);
    t.project = seconds(Stage::project);
    t.measure = seconds(Stage::measure);
    t.postprocess = t.smooth + t.refit + t.project + t.measure;
    t.total = t.load + t.lloyd + t.postprocess;
    t.edits = state_.edit_seconds;
    r.edits = state_.edits;

    r.face_labels = face_labels();
    r.lloyd_face_labels = state_.lloyd_labels.empty() ? r.face_labels : state_.lloyd_labels;
    auto input_order = [&](const std::vector<int>& model_order) {
        std::vector<int> out(input_.faces, -1);
        for (std::size_t f = 0; f < model_order.size(); ++f) out[source_face_[f]] = model_order[f];
        return out;
    };
    r.labels = input_order(r.face_labels);
    r.lloyd_labels = input_order(r.lloyd_face_labels);

    const Frame& frame = model().frame;
    const Lloyd* lloyd = running_lloyd();
    const std::vector<Proxy>& proxies = lloyd ? lloyd->proxies() : state_.proxies;
    for (int i = 0; i < static_cast<int>(proxies.size()); ++i) {
        const Proxy& p = proxies[i];
        ProxyResult out;
        out.id = i;
        Classification unit;
        if (i < static_cast<int>(state_.choices.size())) {
            const ModelChoice& choice = state_.choices[i];
            unit = choice.chosen.shape;
            out.type = choice.chosen.type;
            out.special_fit = choice.chosen.special;
            out.type_rms = choice.chosen.rms * frame.scale;
            if (choice.runner_up) out.runner_up = {choice.runner_up->type, choice.runner_up->rms * frame.scale};
        } else {
            const RegionFrame region = region_frame(p.moments);
            unit = classify(p.quadric, region.center, region.radius, options_.lloyd.classify);
            out.type = p.quadric.is_plane() ? QuadricType::plane : unit.type;
        }
        out.shape = change_frame(unit, frame.scale, frame.translation);
        out.shape.type = out.type;
        out.quadric = normalized(change_frame(p.quadric, frame.scale, frame.translation));
        out.faces = p.faces;
        out.area = p.area * frame.scale * frame.scale;
        out.rms_error = p.area > 0 ? std::sqrt(p.error / p.area) * frame.scale : 0.0;
        out.locked = i < static_cast<int>(state_.locked.size()) && state_.locked[i];
        if (i < static_cast<int>(state_.imposed.size())) out.imposed = state_.imposed[i];
        r.proxies.push_back(out);
    }
    for (const Vec3& p : state_.projected) r.projected.push_back(frame.to_input(p));
    r.metrics = state_.metrics;
    return r;
}

}  // namespace vqsa
