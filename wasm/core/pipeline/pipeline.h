// A run from a mesh to its result, as a list of stages stepped one bounded piece at a
// time: Lloyd → smooth → refit → project → measure (docs/ARCHITECTURE.md).
#pragma once

#include "edit/edit.h"
#include "geometry/model.h"
#include "io/mesh.h"
#include "pipeline/options.h"
#include "fitting/model_selection.h"
#include "pipeline/result.h"

#include <functional>
#include <memory>
#include <utility>
#include <vector>

namespace vqsa {

enum class Stage { lloyd, smooth, refit, project, measure, done };
const char* stage_name(Stage stage);

struct Progress {
    Stage stage = Stage::lloyd;
    // What the last step did: the Lloyd operation (lloyd, insert, split, merge, teleport)
    // during the Lloyd stage, else the stage's name.
    const char* phase = "initialize";
    int proxies = 0;
    int iterations = 0;    // Lloyd iterations so far
    double rms = 0;        // RMS distance over the longest bounding-box side
    double fraction = 0;   // of the current stage, in [0, 1]
    // The count and RMS of the partition the run's Lloyd stage last settled on, before the
    // operation that followed (an operation reports its new count with the error of the
    // partition it started from): the points of the curve of error against count. After
    // the stage, its last; 0 before the first settle.
    int settled_proxies = 0;
    double settled_rms = 0;
};

// Return false to cancel.
using ProgressCallback = std::function<bool(const Progress&)>;

class PipelineStage;

class Pipeline {
public:
    // Checks the options (std::invalid_argument) and builds the model.
    Pipeline(const Mesh& mesh, const Options& options);
    // With the model made from `mesh` (make_model) by an earlier run: it depends on the
    // mesh alone, so runs with other options share it.
    Pipeline(const Mesh& mesh, std::shared_ptr<const Model> shared, const Options& options);
    ~Pipeline();

    // One bounded piece of work; false when the run is over.
    bool step();
    // Steps to the end, reporting after every step.
    void run(const ProgressCallback& progress = {});
    // Ends the run at the next step, leaving a consistent partition.
    void cancel() { cancel_requested_ = true; }

    bool done() const { return stage() == Stage::done; }
    Stage stage() const;
    Progress progress() const;
    const Model& model() const { return *shared_model_; }
    // The current region of every kept face (live during the run).
    const std::vector<int>& face_labels() const;
    // The run so far (complete once done()). `load_seconds` goes into its timing.
    Result result(double load_seconds = 0) const;

    // Edits of a finished run (docs/EDITS.md), each carried out by step()/run() like the
    // run itself: Lloyd on the regions it touches (apply_edit), then the
    // post-processing of those regions; a cancel drops it. Throws std::invalid_argument
    // (state unchanged) while a run or an edit is under way, or when the edit does not
    // apply. Faces are in the input's order.
    void edit(const Edit& edit);
    // Back to the state before the last edit, and forward again; false when there is
    // nothing to go back (forward) to, or an edit is under way. The last kMaxUndo states
    // are kept.
    bool undo();
    bool redo();
    bool can_undo() const { return done() && !undo_.empty(); }
    bool can_redo() const { return done() && !redo_.empty(); }
    static constexpr std::size_t kMaxUndo = 64;

    // What the stages hand on to each other.
    struct State {
        std::vector<int> labels, lloyd_labels;
        std::vector<Proxy> proxies;
        std::vector<ModelChoice> choices;  // per region, unit frame (without the refit: the type of its own quadric)
        std::vector<char> crease;  // per dual-graph link, when the Lloyd stage used features
        // Per face, Features::roughness (the noise): the mesh's, shared by the undo states.
        std::shared_ptr<const std::vector<double>> roughness;
        // Lloyd::noisy: the regions' model selections see their noise (Samples::noise).
        bool noisy = false;
        double energy = 0;
        StopReason stop_reason = StopReason::none;
        int iterations = 0;
        std::pair<int, double> settled{0, 0.0};  // Lloyd::settled at the end of the stage
        const char* phase = "initialize";
        std::vector<Vec3> projected;  // unit frame
        std::optional<Metrics> metrics;
        // Per region (may be shorter than proxies: unlocked, no type imposed).
        std::vector<char> locked;
        std::vector<ImposedType> imposed;
        std::vector<Edit> edits;           // applied so far
        std::vector<double> edit_seconds;  // each one's time
    };

private:
    const Lloyd* running_lloyd() const;  // the Lloyd engine while its stage runs, else null
    void add_stages(const std::vector<char>& regions);  // post-processing (of `regions`; all when empty)

    InputInfo input_;
    std::vector<int> source_face_;  // Mesh::source_face
    Options options_;
    std::shared_ptr<const Model> shared_model_;
    State state_;
    std::vector<std::unique_ptr<PipelineStage>> stages_;
    std::size_t current_ = 0;
    double seconds_[static_cast<int>(Stage::done)] = {};  // per stage
    bool cancel_requested_ = false;
    bool editing_ = false;
    std::vector<State> undo_, redo_;
};

}  // namespace vqsa
