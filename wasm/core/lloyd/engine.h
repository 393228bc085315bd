// Variational quadric shape approximation: Lloyd iteration with progressive proxy
// insertion, validity splits, merging and teleportation (ALGORITHM §3–4).
#pragma once

#include "fitting/classify.h"
#include "fitting/fit.h"
#include "lloyd/flooding.h"
#include "post/graph_cut.h"
#include "post/metrics.h"
#include "geometry/model.h"
#include "post/project.h"
#include "fitting/special_fit.h"

#include <memory>
#include <optional>

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace vqsa {

struct EngineOptions {
    int proxies = 0;          // stop at this many proxies (0: no count target)
    double tolerance = 0;     // stop when the RMS distance (relative to the longest bounding-box side) is below
    int max_iterations = 2000;  // Lloyd iterations in all
    std::uint64_t seed = 1;   // picks the first seed face of each component

    // Lloyd stops when the energy falls by less than this fraction, or after
    // `stage_iterations` iterations, before the next proxy operation.
    double convergence = 3e-3;
    int stage_iterations = 4;
    // Proxies inserted at once while growing, as a fraction of the current count (at
    // least one): 0 inserts one at a time, as the paper does.
    double insertion_batch = 0.25;
    // Merge-and-reinsert attempts once the proxy count is reached: each is kept only
    // if it lowers the energy, and the first that does not stops them.
    int teleports = 4;
    // A region whose quadric has two parts is split when the smaller part holds at
    // least this fraction of its area.
    double split_fraction = 0.05;
    // Regions with fewer faces get a plane: a quadric through a handful of flat
    // triangles is underdetermined.
    int min_quadric_faces = 10;
    FitOptions fit;
    ClassifyOptions classify;

    // Post-processing, after the Lloyd stage (ALGORITHM §5–8).
    bool smooth = true;
    SmoothingOptions smoothing;
    bool refit = true;  // refit plane, sphere, cylinder and cone by orthogonal distances
    SpecialFitOptions special;
    bool project = true;
    // Foot points farther than this (relative to the longest bounding-box side) are
    // taken for stray roots and ignored.
    double max_projection_distance = 0.05;
    bool measure = true;  // needs `project`
    MetricsOptions metrics;
};

// Throws std::invalid_argument naming the offending option.
void validate(const EngineOptions& options);

enum class Phase { initialize, lloyd, insert, split, merge, teleport, smooth, classify, project, measure, done };
const char* phase_name(Phase phase);

enum class StopReason { none, proxies, tolerance, max_iterations, cancelled, exhausted };
const char* stop_reason_name(StopReason reason);

struct Proxy {
    Quadric quadric;        // unit frame, unit norm
    Moments moments{};      // sum over the region
    double area = 0;        // unit frame
    double error = 0;       // Σ d(t, P) over the region
    double fit_error = 0;   // the fit's mean squared distance (unit frame)
    int faces = 0;
    int seed = -1;
    bool fitted = false;    // the quadric is the fit of `moments` (not a seed plane)
};

class Engine;

struct ProgressEvent {
    Phase phase;
    int proxies;
    int iteration;  // Lloyd iterations so far
    double rms;     // current RMS distance, relative to the longest bounding-box side
};

// Return false to cancel. Labels and proxies are read from the engine when wanted, so
// an event costs nothing beyond the call.
using ProgressCallback = std::function<bool(const ProgressEvent&, const Engine&)>;

class Engine {
public:
    Engine(const Mesh& mesh, const EngineOptions& options);

    // One unit of work: a Lloyd iteration, a proxy operation, the smoothing of one
    // boundary, or one post-processing stage. False when done.
    bool step();
    // Steps until done, reporting after every step.
    void run(const ProgressCallback& progress = {});
    void cancel();

    bool done() const { return stage_ == Stage::done; }
    bool lloyd_done() const { return stage_ != Stage::lloyd; }
    // Why the Lloyd stage stopped (or `cancelled`, if a cancel came at any point).
    StopReason stop_reason() const { return stop_reason_; }
    int iterations() const { return iterations_; }
    Phase last_phase() const { return last_phase_; }

    const Model& model() const { return model_; }
    const EngineOptions& options() const { return options_; }
    const std::vector<Proxy>& proxies() const { return proxies_; }
    // Region of every kept face, in the model's face order.
    const std::vector<int>& face_labels() const { return labels_; }
    const std::vector<double>& face_errors() const { return errors_; }
    // Region of every input face, in the input's order (-1 for dropped faces).
    std::vector<int> labels() const;
    // The same before boundary smoothing (equal to labels() when smoothing is off).
    std::vector<int> lloyd_labels() const;
    // ... and in the model's face order.
    const std::vector<int>& lloyd_face_labels() const { return lloyd_labels_.empty() ? labels_ : lloyd_labels_; }
    // Projected positions, input coordinates, one per mesh vertex (empty until projected).
    std::vector<Vec3> projected_vertices() const;
    const std::optional<Metrics>& metrics() const { return metrics_; }
    // Whether the proxy's quadric is an exact special type from the orthogonal refit.
    bool is_special(int proxy) const { return proxy < static_cast<int>(special_.size()) && special_[proxy].has_value(); }
    // Σ d(t, P) over the mesh (unit frame).
    double energy() const { return energy_; }
    double rms() const;  // relative to the longest bounding-box side
    // A proxy's quadric and type in the input's coordinates.
    Quadric input_quadric(int proxy) const;
    Classification classification(int proxy) const;

private:
    struct Snapshot {
        std::vector<int> labels;
        std::vector<double> errors;
        std::vector<Proxy> proxies;
        double energy = 0;
    };

    void initialize();
    void lloyd_iteration();
    void decide();
    // Both skip the regions whose faces did not change since their last fit.
    void refit(const std::vector<char>& changed);
    void evaluate(const std::vector<char>* changed = nullptr);
    void insert_farthest(int count);  // into the `count` regions of largest error
    bool split_invalid();
    // The adjacent pair whose union fit costs least; `gated`: only if merging pays.
    bool merge_cheapest(bool gated);
    Quadric plane_through(int face) const;
    void add_proxy(int seed);  // a plane through the seed face
    void remove_proxy(int index);
    Classification classify_unit(int proxy) const;
    void end_lloyd(StopReason reason);
    void post_step();
    void next_stage();
    Samples region_samples(int proxy) const;

    std::vector<int> source_face_;
    int input_face_count_;
    Model model_;
    EngineOptions options_;
    Flooding flooding_;
    FaceErrors face_errors_;

    std::vector<Proxy> proxies_;
    std::vector<Quadric> quadrics_;  // the proxies' quadrics, as flooding takes them
    std::vector<int> seeds_;
    std::vector<int> labels_;
    std::vector<int> previous_labels_;
    std::vector<char> changed_;  // per proxy, in the current Lloyd iteration
    std::vector<double> errors_;
    double energy_ = 0;
    double previous_energy_ = 0;
    int stage_iteration_ = 0;
    int iterations_ = 0;
    int teleports_left_ = 0;
    int splits_left_ = 0;
    bool in_lloyd_ = false;
    bool teleport_pending_ = false;
    Snapshot snapshot_;
    enum class Stage { lloyd, smooth, classify, project, measure, done };
    Stage stage_ = Stage::lloyd;
    Phase last_phase_ = Phase::initialize;
    StopReason stop_reason_ = StopReason::none;
    std::vector<int> lloyd_labels_;
    std::unique_ptr<BoundarySmoother> smoother_;
    std::vector<std::optional<Classification>> special_;  // unit frame
    std::vector<Vec3> projected_;                         // unit frame
    std::optional<Metrics> metrics_;
    bool cancel_requested_ = false;
};

}  // namespace vqsa
