// Variational quadric shape approximation: Lloyd iteration with progressive proxy
// insertion, validity splits, merging and teleportation (docs/METHOD.md §2, §4, §5, §7).
#pragma once

#include "fitting/classify.h"
#include "fitting/fit.h"
#include "geometry/features.h"
#include "geometry/model.h"
#include "geometry/rng.h"
#include "lloyd/flooding.h"

#include <array>
#include <cstdint>
#include <functional>
#include <limits>
#include <optional>
#include <set>
#include <unordered_map>
#include <utility>
#include <vector>

namespace vqsa {

// How proxies are seeded and inserted.
enum class Initialization {
    // Sharp creases cut the mesh into charts; seeds and insertions go first to the
    // charts no proxy covers whose faces fit their proxies worse than the noise
    // explains, and regions flood their own chart before crossing a crease.
    features,
    // The paper's: one seed per component, then farthest-point insertion.
    paper,
};

struct LloydOptions {
    // Stop at this many proxies. 0 with no tolerance: automatic, growing while proxies
    // pay (every chart covered, every region explained by the noise, or no gain).
    int proxies = 0;
    double tolerance = 0;       // stop when the RMS distance (relative to the longest bounding-box side) is below
    int max_iterations = 2000;  // Lloyd iterations in all
    std::uint64_t seed = 1;     // drives the random choices: the seed face within a chart or component
    Initialization init = Initialization::features;
    FeatureOptions features;    // crease angle and normal filtering

    // A region is explained when its mean squared error is at most noise_factor² times
    // the mean squared roughness of its faces (Features::roughness: the RMS a locally
    // exact surface leaves), or below `precision` (RMS, relative to the longest
    // bounding-box side), the automatic count's floor for free-form shapes (on an exact
    // export, the stored precision instead: its surfaces leave no error). A chart is
    // structure its region misses when its error exceeds chart_factor times its error under
    // its own fit.
    double noise_factor = 1.4;
    double chart_factor = 2;
    double precision = 1e-3;
    // The automatic count also stops when an insertion lowered the energy by less than
    // this fraction per added proxy.
    double min_gain = 0.05;

    // Lloyd stops when the energy falls by less than this fraction, or after
    // `stage_iterations` iterations, before the next proxy operation.
    double convergence = 3e-3;
    int stage_iterations = 4;
    // Proxies inserted at once while growing, as a fraction of the current count (at
    // least one): 0 inserts one at a time, as the paper does.
    double insertion_batch = 0.25;
    // Merge-and-reinsert attempts once the proxy count is reached: each is kept only
    // if it lowers the energy, and the first that does not stops them.
    int teleports = 8;
    // A region whose quadric has two parts is split when the smaller part holds at
    // least this fraction of its area (and three faces); smaller second parts are
    // reported and refitted as the larger part's surface.
    double split_fraction = 0.05;
    // Regions with fewer faces get a plane: a quadric through a handful of flat
    // triangles is underdetermined.
    int min_quadric_faces = 10;
    FitOptions fit;
    ClassifyOptions classify;
};

// Checks the tuning parameters (the user-facing ones are checked by the option schema,
// pipeline/options.h). Throws std::invalid_argument naming the offending one.
void validate(const LloydOptions& options);

// What a Lloyd step did.
enum class Operation { initialize, iterate, insert, split, merge, teleport };
const char* operation_name(Operation operation);

// Why the Lloyd stage stopped: the proxy count or tolerance was reached; (automatic
// count) every region is explained by the noise, or more proxies no longer pay; the
// iteration cap; a cancel; every face has its own proxy.
enum class StopReason { none, proxies, tolerance, fitted, no_gain, max_iterations, cancelled, exhausted };
const char* stop_reason_name(StopReason reason);

struct Proxy {
    Quadric quadric;        // unit frame, unit norm
    Moments moments{};      // sum over the region
    double area = 0;        // unit frame
    double error = 0;       // Σ d(t, P) over the region
    double fit_error = 0;   // the fit's mean squared distance (unit frame)
    int faces = 0;
    int seed = -1;          // the region's face of least error
    bool fitted = false;    // the quadric is the fit of `moments` (not a seed plane)
};

// The fit a region of `faces` faces gets: a plane below `min_quadric_faces`, else the
// better of plane and quadric (fit_region; FitOptions::plane_of_pair as given).
Fit fit_proxy(const Moments& moments, int faces, const LloydOptions& options, bool plane_of_pair = false);

// Σ over the model's faces of each region's moments, face count and area; refits the
// regions flagged in `changed` (all when empty).
void refit_regions(const Model& model, const std::vector<int>& labels, const LloydOptions& options,
                   std::vector<Proxy>& proxies, const std::vector<char>& changed = {});

// Charts for evaluate_regions: the chart of each face and the faces of each chart, in
// increasing order.
struct ChartFaces {
    const std::vector<int>& chart;
    const std::vector<std::vector<int>>& faces;
    // Per face: whether a flood from it reaches min_quadric_faces faces or more without
    // crossing a crease.
    const std::vector<char>& seedable;
};

// d(t, P) of every face against its region's proxy into `errors`; each proxy's error and
// seed (its face of least error; with `charts`, of least error in the chart holding most
// of its region's area, a seedable face where there is one). Regions not flagged in
// `changed` (when given) keep the errors already in `errors`. Returns the energy Σ d(t, P).
double evaluate_regions(const Model& model, const std::vector<int>& labels, std::vector<Proxy>& proxies,
                        std::vector<double>& errors, FaceErrors& evaluator, const std::vector<char>* changed = nullptr,
                        const ChartFaces* charts = nullptr);

// The faces labelled `region`, in increasing order.
std::vector<int> faces_of(const std::vector<int>& labels, int region);

// Whether a region (its faces, labelled in `labels`) is a strip, too thin to tell a surface
// of its own: fewer than `min_faces` faces, or one facet wide (no face with all its
// neighbours in it; a column of a ruled band is exactly planar, a ring of a sphere's
// tessellation exactly a cone, so its own fit says nothing of the surface it lies on).
// The same for any set of faces: `group_of(f)` names the set face f is in.
template <class GroupOf>
bool is_strip(const Model& model, const std::vector<int>& faces, int min_faces, const GroupOf& group_of) {
    if (static_cast<int>(faces.size()) < min_faces) return true;
    for (int f : faces) {
        bool inside = true;
        for (int e = model.graph.begin(f); e < model.graph.end(f) && inside; ++e)
            inside = group_of(model.graph.neighbor[e]) == group_of(f);
        if (inside) return false;
    }
    return true;
}
inline bool is_strip(const Model& model, const std::vector<int>& labels, const std::vector<int>& faces, int min_faces) {
    return is_strip(model, faces, min_faces, [&](int f) { return labels[f]; });
}

// The plane of a face (a new proxy's quadric before its first fit).
Quadric plane_through(const Model& model, int face);

std::vector<Quadric> quadrics_of(const std::vector<Proxy>& proxies);
std::vector<int> seeds_of(const std::vector<Proxy>& proxies);

// The Lloyd stage on one model. Each step() is one unit of work: a Lloyd iteration or a
// proxy operation.
// A mesh with faces, and a proxy count it can hold (std::invalid_argument).
void check_proxy_count(const Model& model, const LloydOptions& options);

// The faces of each region.
using RegionFaces = std::vector<std::vector<int>>;

class Lloyd {
public:
    Lloyd(const Model& model, const LloydOptions& options);

    // False once the stage has stopped.
    bool step();
    // Stops at the next step, leaving a consistent partition.
    void cancel() { cancel_requested_ = true; }

    bool done() const { return stop_reason_ != StopReason::none; }
    StopReason stop_reason() const { return stop_reason_; }
    Operation last_operation() const { return last_operation_; }
    int iterations() const { return iterations_; }
    const std::vector<Proxy>& proxies() const { return proxies_; }
    // Region of every face, in the model's order.
    const std::vector<int>& labels() const { return labels_; }
    const std::vector<double>& errors() const { return errors_; }
    double energy() const { return energy_; }  // Σ d(t, P) over the mesh (unit frame)
    double rms() const;                         // relative to the longest bounding-box side
    // The proxy count and RMS of the partition Lloyd last settled on (converged, or at the
    // iteration cap of an operation), before the operation that followed: one point per
    // settle of the curve of error against count. {0, 0} before the first settle.
    std::pair<int, double> settled() const { return settled_; }
    // How far the stage is, in [0, 1] (by proxy count when there is a target).
    double fraction() const;
    const Features& features() const { return features_; }
    // The mesh's median roughness is above `precision`: noise everywhere.
    bool noisy() const { return noisy_; }
    const LloydOptions& options() const { return options_; }

private:
    // A partition to go back to (its errors are recomputed from labels and quadrics).
    struct Snapshot {
        std::vector<int> labels;
        std::vector<Proxy> proxies;
        double energy = 0;
    };

    // How a region's faces divide between the two parts of its quadric, if it has two (or
    // between the two planes it lies on: plane_pair).
    struct Parts : PartWeights {  // weights: areas
        int best[2] = {-1, -1};     // face of least error on each part
        std::vector<int> faces[2];  // the faces on each part
    };

    void initialize();
    void iterate();
    // The next operation (or the stop), after Lloyd has settled.
    void decide();
    void judge_teleport();
    // No teleport pending and none more: single, wide or to a misfit.
    void end_teleports();
    void restore(const Snapshot& snapshot);
    void decide_at_target();
    bool decide_finish();  // automatic count: whether growth has ended (then finishes)
    void finish();
    void insert_batch();
    // Up to `count` proxies: into misfit charts, misfit clusters, then at the worst faces.
    int insert_where_needed(int count);
    void start_operation(Operation operation);
    void stop(StopReason reason);
    // After the stage that follows a stop's repair: `reason` none when it settled,
    // otherwise what cut it short.
    void end_settling(StopReason reason);
    void evaluate(const std::vector<char>* changed = nullptr);
    std::uint64_t partition_hash() const;
    // Growing: with the automatic count, and at a fixed count while regrowing (regrowth_goes_on).
    bool automatic() const { return automatic_count() || regrowth_ == Regrowth::growing; }
    // The user's choice of the automatic count (no proxy count, no tolerance).
    bool automatic_count() const { return options_.proxies == 0 && options_.tolerance == 0; }
    // The count to reach, 0 while growing as the automatic count does.
    int target() const { return regrowth_ == Regrowth::growing ? 0 : options_.proxies; }
    // Whether a stop at a fixed count for `reason` first grows past the count and merges back.
    bool regrows(StopReason reason) const;
    // How far a regrowth may grow: three times the count (at twice, the coarse irregular
    // pencil's was cut short before it found its cone, 0.822).
    int regrowth_ceiling() const { return 3 * options_.proxies; }
    // At a stop for `reason`: whether a regrowth starts, or goes on from growing to merging
    // back (the stop waits). Otherwise, if one has just ended and did no better, the
    // partition it started from is restored, with its stop reason unless the iteration cap
    // or a cancel cut the regrowth short.
    bool regrowth_goes_on(StopReason& reason);
    // Σ A (noise_factor · roughness)² over a region: the energy the noise explains.
    double noise_energy(int proxy) const;
    bool explained(int proxy) const;
    bool every_region_explained() const;
    // Per chart: whether a proxy seeded in it holds at least half of it.
    std::vector<char> owned_charts() const;
    // Charts without a seed whose faces fit worse than the noise explains, worst first.
    std::vector<int> misfit_charts() const;
    // Whether the regions' quadrics (or `united`, for all) miss the vertices of the creases
    // they cross (pairs of region and vertex) by more than the noise (`noise2`: its mean
    // square) allows.
    bool rounds_off(std::vector<std::pair<int, int>> crease_vertices, double noise2, const Quadric* united = nullptr) const;
    int insert_into_charts(int count);
    // A proxy seeded at a random face of `faces` that seeds none yet; false if all do.
    bool seed_at_random(const std::vector<int>& faces);
    // Connected faces (a handful or more) whose normals stray from their region's surface
    // normal by more than the crease angle, largest first.
    std::vector<std::vector<int>> misfit_clusters() const;
    int insert_into_clusters(int count);
    // Into the `count` regions of largest error (only unexplained ones when automatic).
    int insert_farthest(int count);
    // The faces of regions a and b (a == b for one region) on each part of q, classified
    // as c; faces within `margin` of where the parts separate count on neither.
    Parts parts(const Quadric& q, const Classification& c, double margin, int a, int b) const;
    Parts parts(const Quadric& q, const Classification& c, double margin, const std::vector<int>& faces) const;
    // Whether faces of that area lie on two parts (enough of them to count; see invalid). On
    // a quadric of two parts, the second counts from `faces` faces and split_fraction of the
    // area.
    bool on_two_parts(const Quadric& q, const Parts& p, double area, int faces = 3) const;
    // Regions fitted as one.
    struct Union {
        Moments moments;
        Fit fit;
    };
    Union fit_union(const std::vector<int>& regions) const;
    // fit_union({a, b}), kept by the two regions' fingerprints (`prints`, per region): the
    // finish fits every adjacent pair again after each merge, though a merge and its Lloyd
    // stage change few regions.
    Union fit_pair(int a, int b, const std::vector<std::uint64_t>& prints) const;
    Classification classify_union(const Union& u) const;
    // The faces of a and b on each part of their union's quadric (beyond the margin a
    // region's validity is judged with), and whether that union would be an invalid region.
    Parts union_parts(const Union& u, int a, int b) const;
    bool union_on_two_parts(const Union& u, int a, int b) const;
    // Whether the union lies on a plane_pair; `error`: errors_against its quadric.
    bool union_on_plane_pair(const Union& u, int a, int b, const RegionFaces& faces,
                             const std::array<double, 2>& error) const;
    // Merges the adjacent pair, among those `eligible`, whose union costs least and is
    // `acceptable`, then the next such pair sharing no region with those merged, up to
    // `limit` pairs; `merged` and `merged_cost`, if given, receive the pairs (kept region
    // first) and their summed cost.
    bool merge_least_cost(const std::function<bool(int, int)>& eligible,
                          const std::function<bool(const Union&, int, int, const RegionFaces&)>& acceptable,
                          std::vector<std::pair<int, int>>* merged = nullptr, double* merged_cost = nullptr,
                          int limit = 1);
    // A candidate merge: the union of the regions of adjacent pair `pair` and what it costs.
    struct MergeCandidate {
        double cost;
        int pair;
        Union u;
        bool exact = false;        // merge_same_surface's: within `precision`
        bool on_vertices = false;  // merge_same_surface's: vertices_on_one_surface
    };
    // Merges, cheapest first (ties by pair), the candidates that share no region with one
    // taken before and are `acceptable`, up to `limit`; as merge_least_cost reports them.
    bool merge_disjoint(const std::vector<std::pair<int, int>>& pairs, std::vector<MergeCandidate> candidates,
                        const std::function<bool(const MergeCandidate&)>& acceptable,
                        std::vector<std::pair<int, int>>* merged, double* merged_cost, int limit);
    // Whether a region (`faces`: of each region) lies on two parts of its quadric.
    bool invalid(int proxy, const RegionFaces& faces, Parts* parts = nullptr) const;
    // On an exact export, whether a region lies on two parts of its quadric, which holds
    // them within the stored precision, and the parts' faces turn from each other by more
    // than the crease angle: two faces, however few faces the second has.
    bool on_two_exact_faces(int proxy, const RegionFaces& faces, Parts* parts = nullptr) const;
    // Whether regions on a plane_pair are split (and refused as unions): with the automatic
    // count, which promises one region per surface, and below a target count, where a split
    // costs no merge (from the moment a run settles explained or stops below it, for the
    // rest of the run), on a mesh that is not an exact export. On an exact one the creases
    // are found, a quadric through two planes is fitted as the pair it is, and the facets of
    // a coarse tessellation lie on two planes about as closely as on their quadric (the
    // rounded ends of a coarse slot: split, 0.978 → 0.969).
    bool plane_pairs_split() const {
        return (automatic() || below_target_ || static_cast<int>(proxies_.size()) < options_.proxies) && !exact_;
    }
    // Whether a region (`faces`: of each region) lies on a plane_pair (plane_pairs_split only).
    bool on_plane_pair(int proxy, const RegionFaces& faces, Parts* parts) const;
    // At the stop: the faces on a region's second part, too small to split off, to
    // neighbouring regions that explain them as well (see lloyd.cpp).
    void release_minor_parts();
    // With the automatic count, at the stop: a handful of faces of an exact tessellation on
    // more than one plane parts into its pieces of exactly coplanar faces, which join the
    // neighbours they lie on one surface with or stay regions of their own, if any piece
    // joins (see lloyd.cpp). Whether any handful parted.
    bool part_handfuls();
    // With the automatic count, at the stop, before part_handfuls: a region fitted by a
    // curved quadric over faces of an exact tessellation lets its plane faces (pieces of
    // exactly coplanar faces that are no strips or no columns of the arc the others make
    // (off_the_arc), or both of two that meet at an inflection)
    // go, when that leaves less error (see lloyd.cpp). Whether any did.
    bool release_planes();
    // Per piece of `region` (its pieces of coplanar faces, labelled in `piece`, of these
    // areas): whether it is no facet column of the arc the others make, by the radius its
    // bends to its neighbours imply (see lloyd.cpp).
    std::vector<char> off_the_arc(const std::vector<int>& region, const std::vector<int>& piece,
                                  const std::vector<double>& area) const;
    // Whether `faces` (a piece of coplanar faces of one region) bend one way from the faces
    // of piece `from` (per face of the model, as coplanar_pieces labels them) and only the
    // other way into the faces of other regions beyond them, over edges that are no creases.
    bool inflects(const std::vector<int>& faces, const std::vector<int>& piece, int from) const;
    // Parts the regions `admitted` takes and joins the pieces (part_and_join), keeping
    // parted only those of which a piece joined another region or was joined. Whether any
    // was.
    bool part_joining(const std::function<bool(int)>& admitted);
    // Parts the regions `admitted` takes (of exact faces, whose vertices determine no
    // quadric) into their pieces of exactly coplanar faces and joins the pieces; per region
    // before, whether a piece of it joined another region or was joined.
    std::vector<char> part_and_join(const std::function<bool(int)>& admitted);
    // On an exact export: the faces of `region` off the plane of its largest piece of exactly
    // coplanar faces, when that holds most of its area (else none). `piece`: per face of the
    // model, all -1; left so.
    std::vector<int> off_plane_faces(const std::vector<int>& region, std::vector<int>& piece) const;
    // Labels the faces of `region` (one region's, not empty) in `piece` (per face of the
    // model, -1 where not yet labelled) by their pieces of exactly coplanar neighbours, from
    // 0; returns how many.
    int coplanar_pieces(const std::vector<int>& region, std::vector<int>& piece) const;
    // Whether each of `faces` lies in one plane with a neighbour (coplanar_with_a_neighbour):
    // faces of an exact tessellation, as Features::exact asks of half the mesh's; not so
    // beside a smooth surface's faces, nor under noise.
    bool on_exact_faces(const std::vector<int>& faces) const;
    // Splits the invalid region of largest error (`plane_pairs`: the region on a plane pair).
    bool split_invalid(bool plane_pairs);
    // split_invalid within the split budget, and not from a partition split from before.
    bool split(bool plane_pairs);
    // The adjacent pair whose union fit costs least, if its union is valid; up to `limit`
    // such pairs sharing no region, cheapest first.
    bool merge_cheapest(int limit = 1);
    // Splits what is still invalid at the end of the stage (see lloyd.cpp).
    void ensure_valid();
    // Whether a region of a noisy mesh is one plane: a plane holds it within its noise and
    // its faces face one way (all but split_fraction of its area).
    bool one_noisy_plane(int proxy, const RegionFaces& faces) const;
    // Each piece of these regions (faces meeting at a vertex at least) but the largest goes
    // to the adjacent region whose surface holds it within its noise, or becomes a region of
    // its own if it can tell a surface (see lloyd.cpp); the regions changed are refitted and
    // evaluated.
    void settle_pieces(const std::vector<int>& regions);
    // Merges `region` into the neighbour (not `excluded`) it costs least and lies on one
    // surface with (one_surface), whose union's quadric has one part.
    bool absorb(int region, int excluded);
    // Which part of q (classified as `c`) a face lies on: ±1, or 0.
    int side_of(const Quadric& q, int face, const Classification& c, double margin) const;
    double part_margin(int proxy) const;
    // The two planes `faces` lie on, meeting at a sharp crease, if they lie on them as
    // closely as on their quadric (within noise_factor² times `error`, their error against
    // it); no faces on either part if they do not (see lloyd.cpp).
    Parts plane_pair(const std::vector<int>& faces, double error) const;
    // Adjacent regions on one surface (their union fits as well as they do apart, or, when
    // `within_noise`, within their noise). At a count the user chose, both: the noise alone
    // must not take away a face it blurs (a thin plate's side), nor fitting as well as apart
    // join two pieces of a free-form surface (which neither precision nor noise explains).
    // Under noise, also pieces that the union's plane holds within their noise, as that plane.
    // Up to `limit` pairs that share no region, least cost first; `merged`, if given,
    // receives them. Pairs rejected as they are (rejected) are not merged again.
    bool merge_same_surface(bool within_noise = true, std::vector<std::pair<int, int>>* merged = nullptr,
                            int limit = 1);
    // The candidate merge of adjacent regions i and j if they lie on one surface, before
    // the tests merge_same_surface makes of each candidate in turn; `prints`: fingerprints.
    std::optional<MergeCandidate> same_surface_candidate(int i, int j, bool within_noise, const RegionFaces& faces,
                                                         const std::vector<std::uint64_t>& prints) const;
    // The error a region may carry and be explained: its noise_energy, or its area times
    // `precision`² (kStoredPrecision² on an exact export), whichever is larger.
    double allowance(int proxy) const;
    // Σ over regions of the error beyond their allowance.
    double unexplained() const;
    // Judges the last finishing merge once Lloyd has settled around it: it stands if it
    // left no more error unexplained than before it (or than the same Lloyd stage leaves
    // without it), plus the noise of its two regions; a single handful's, if all of them
    // together, their unions' cost included, left at most kHandfulDrift times the energy
    // the finish began at, plus their noise (several handfuls at once, as other merges,
    // plus their unions' cost). Else it is
    // undone. True when that stage without it must run first (the partition is then the
    // one before the merge).
    bool judge_merge();
    // Whether merging regions a and b was undone (judge_merge) while they were as they are
    // (their fingerprints): it is not tried again until one of them changes, whatever
    // merges elsewhere did in between; under noise, only from the partition it was undone
    // from (rejection_context). For the partition whose fingerprints are `prints`, which the
    // predicate reads by reference: they must outlive it.
    std::function<bool(int, int)> rejected(const std::vector<std::uint64_t>& prints) const;
    std::uint64_t rejection_context() const;
    // Below a target count: judges the last insertion, then whether insertions have stopped
    // paying with every region explained.
    bool fitted_below_target();
    // Whether faces whose plane leaves `plane_mean_squared`, where the noise is `noise2`
    // (mean square), are an exact plane: a face of a coarse CAD tessellation, however few
    // of them (one triangle too).
    static bool exactly_planar(double plane_mean_squared, double noise2);
    // Whether faces of these moments lie in one plane as closely as a file stores them.
    static bool on_one_exact_plane(const Moments& faces) { return exactly_planar(fit_plane(faces).mean_squared, 0); }
    // Whether `faces` are one triangle that is a chart of its own on an exact tessellation.
    bool face_of_its_own(const std::vector<int>& faces) const;
    // Whether faces of these moments, on a tessellation that is not exact and with this
    // noise (Σ face_noise_), are at least kFaceWidthInNoise times as wide as their roughness
    // and as `precision`: a face of its own under noise if they are a chart (see lloyd.cpp).
    bool wide_against_noise(const Moments& faces, double noise) const;
    // Whether `faces` are a chart of two faces or more, wide_against_noise.
    bool wide_chart_of_its_own(const std::vector<int>& faces) const;
    // Whether the vertices of `region` lie on the surface of region `other` as closely as
    // its own do.
    bool vertices_on(const std::vector<int>& region, int other, const RegionFaces& faces) const;
    // A region of fewer than min_quadric_faces faces into the neighbour it costs least;
    // one exactly planar, only into a neighbour its vertices lie on. Not a pair undone as
    // it is (rejected). Up to `limit` such pairs sharing no region; `merged` and `cost`
    // receive the pairs and their unions' summed cost.
    bool merge_handful(std::vector<std::pair<int, int>>* merged, double* cost, int limit);
    // Every region of fewer than min_quadric_faces faces into a neighbour it lies on one
    // surface with (one_surface), the cheapest: whether any.
    bool merge_slivers();
    // Every sliver and every pair on one exact surface (merge_same_surface(false)), at once
    // (joint/30 has nine slivers, a turned part at 50 thirty pieces): whether any.
    bool merge_at_count();
    // Whether the union of regions a and b (of quadric `united`) is the surface type the
    // larger of them is (see lloyd.cpp). `prints`: the regions' fingerprints.
    bool keeps_type(int a, int b, const Quadric& united, const RegionFaces& faces,
                    const std::vector<std::uint64_t>& prints) const;
    // Σ d(f, q) over the faces of region a, and of region b.
    std::array<double, 2> errors_against(const Quadric& q, int a, int b, const RegionFaces& faces) const;
    // Whether q explains regions a and b as one surface (see merge_same_surface); `error`:
    // errors_against q.
    bool one_surface(const Quadric& q, int a, int b, const RegionFaces& faces, const std::array<double, 2>& error) const;
    // Whether the vertices of regions a and b (union u) lie on one quadric, with one part
    // under them, far closer than their faces do: a tessellation's surface (see lloyd.cpp).
    // `prints`: every region's fingerprint, for `faces`.
    bool vertices_on_one_surface(const Union& u, int a, int b, const RegionFaces& faces,
                                 const std::vector<std::uint64_t>& prints) const;
    // Whether the vertices of `regions` lie on one quadric as closely as a file stores them
    // and determine it (no other comes within the tessellation's deviation), and whether they
    // are one surface on it: each region's faces within that deviation, all facing one way,
    // one part of the quadric under them.
    struct VertexSurface {
        bool determined = false, one = false;
    };
    VertexSurface vertex_surface(const std::vector<int>& regions, const RegionFaces& faces) const;
    // The same for pieces that need not be regions (a region and a face of another).
    struct Piece {
        const std::vector<int>* faces;
        Moments moments;  // of the faces
        double noise;     // Σ face_noise_ over them
    };
    VertexSurface vertex_surface(const std::vector<Piece>& pieces) const;
    // Whether two regions' vertices are plainly on no quadric together, from the larger
    // one's vertex moments kept by its fingerprint: vertex_surface's first test, for a few
    // of the smaller one's vertices' worth of work.
    struct Printed {
        int region;
        std::uint64_t print;  // its fingerprint
    };
    bool plainly_on_no_quadric(Printed a, Printed b, const RegionFaces& faces) const;
    // What the vertex tests above found, by the regions they were asked of. They depend on
    // a region only through its faces, moments and noise, and the finish asks them of every
    // region and pair again after each merge, though the merge and its Lloyd stage change
    // few regions (on a pocketed part, 3K faces merged from 130 regions to 110, they were
    // four fifths of 16 s). Keyed by `fingerprint`s (64-bit hashes, as partition_hash).
    std::uint64_t fingerprint(int region, const RegionFaces& faces) const;
    std::vector<std::uint64_t> fingerprints(const RegionFaces& faces) const;  // every region's
    struct ExactRegion {  // merge_exact_pieces' look at one region
        bool exact = false, determined = false;
        Moments vertices{};
    };
    ExactRegion exact_region(int region, const RegionFaces& faces) const;
    // Merges a run of adjacent regions whose vertices lie on one quadric as closely as a
    // file stores them and determine it together, though no pair of them does (a coarse
    // fillet's one-facet strips): whether it did (see lloyd.cpp).
    bool merge_exact_pieces();
    // Whether `error`, the region's error against another quadric, says it lies on that
    // quadric's surface as well as on its own; for a `strip` (is_strip), as well as the
    // faces that quadric was fitted to: `reference` is their error per unit area.
    bool lies_on(int region, double error, bool strip, double reference) const;
    // A face's area times the cosine between its normal and q's gradient (0 where q has none).
    double facing(const Quadric& q, int face) const;
    // Whether regions of faces a and b face opposite ways along q's normal (two sides of a sheet).
    bool faces_both_ways(const Quadric& q, const std::vector<int>& a, const std::vector<int>& b) const;
    // Whether a face's (filtered) normal is off q's gradient by more than the crease angle.
    bool off_normal(const Quadric& q, int face) const;
    // Whether most of a region's faces are off_normal to q.
    bool strays(const Quadric& q, const std::vector<int>& region) const;
    // Whether q, fitted to the faces of two regions, turns through the creases between
    // them (by half the crease angle or more, on half of them) or rounds off a crease
    // inside their union (`inside` false: one between them): it would be fitting two faces.
    bool joins_faces_across_creases(const Quadric& q, const std::vector<int>& a, const std::vector<int>& b,
                                    bool inside = true) const;
    // A region of a handful of faces that explains nothing, while another (`worst`) has
    // errors the noise does not explain or, every region within its noise, while a chart
    // no proxy owns (`chart`, worst -1) holds far more error (region -1: none).
    struct Stuck {
        int region = -1, worst = -1, chart = -1;
    };
    Stuck find_stuck() const;
    // Merges the stuck region away and reinserts its proxy in the worst region, or in the chart.
    bool repair(const Stuck& stuck);
    // Regions `gone` into region `keep`, of quadric `fit` (the indices above each gone shift down).
    void merge_into(int keep, const std::vector<int>& gone, const Fit& fit);
    // Each (gone, keep) in turn: region gone into region keep (which must stay), in one pass
    // over the faces; the merged regions keep their quadrics. Returns each old region's new
    // index (-1: merged away).
    std::vector<int> merge_regions(const std::vector<std::pair<int, int>>& merges);
    // The faces of each region, in increasing order.
    RegionFaces faces_by_region() const;
    void add_proxy(int seed);  // a plane through the seed face
    bool is_seed(int face) const;
    Classification classify_proxy(int proxy) const;

    const Model& model_;
    LloydOptions options_;
    double cos_crease_ = -1;  // crease_cosine of the crease angle, asked per face (side_of, off_normal)
    Features features_;
    std::vector<std::vector<int>> chart_faces_;
    std::vector<char> seedable_;  // ChartFaces::seedable
    std::vector<double> chart_error_;  // under the chart's own fit
    std::vector<char> chart_told_;     // a face of its own, not too small to tell (see the constructor)
    std::vector<double> face_noise_;    // A roughness² per face
    // The mesh's median roughness is above `precision`: noise everywhere (a scan, a noisy
    // export), not the local roughness of creases and coarse facets.
    bool noisy_ = false;
    // Its median roughness is within the stored precision: an exact export, whose surfaces
    // leave no error at their count.
    bool exact_ = false;
    std::vector<double> region_noise_;  // its sum per region, from evaluate()
    SplitMix64 rng_;
    Flooding flooding_;
    FaceErrors face_errors_;

    std::vector<Proxy> proxies_;
    std::vector<int> labels_;
    std::vector<int> previous_labels_;
    std::vector<char> changed_;  // per proxy, in the current Lloyd iteration
    std::vector<double> errors_;
    double energy_ = 0;
    double previous_energy_ = 0;
    std::pair<int, double> settled_{0, 0.0};
    int stage_iteration_ = 0;
    int iterations_ = 0;
    int teleports_left_ = 0;
    int splits_left_ = 0;
    std::vector<std::uint64_t> split_states_;  // partitions a split was made from (partition_hash)
    int repairs_left_ = 0;
    std::vector<std::uint64_t> repair_states_;  // partitions a stuck-proxy repair was made from
    bool repair_pending_ = false;                // the last repair, until it is judged
    Snapshot best_before_repair_;                // the partition of least energy a repair started from
    int unpaid_repairs_ = 0;                     // repairs in a row that did not pay
    bool iterating_ = false;
    bool teleport_pending_ = false;
    bool misfit_teleport_ = false;        // the next teleport goes to a misfit chart or cluster
    bool misfit_teleport_tried_ = false;  // one has (after a farthest-point one did not pay)
    int wide_teleport_ = 0;    // proxies the next wide teleport inserts
    bool wide_pending_ = false;      // the pending teleport is a wide one
    double wide_unexplained_ = 0;    // unexplained() before it
    bool finishing_ = false;              // automatic count: no more insertions, merges only
    double finish_energy_ = -1;           // the energy when the finish began
    double handful_drift_ = 0;            // how far single handfuls' merges took it since, their cost included
    bool below_target_ = false;  // a target count the run settled (explained) or stopped below
    double energy_before_insert_ = -1;    // to judge the last insertion (-1: none)
    int inserted_ = 0;
    int unpaid_ = 0;  // insertions in a row that did not pay
    int fewest_misfit_charts_ = std::numeric_limits<int>::max();  // after an insertion, with little unexplained
    double least_before_insert_ = std::numeric_limits<double>::infinity();  // below a target count
    StopReason finish_reason_ = StopReason::none;
    // The last finishing merge (automatic count), until it is judged.
    struct PendingMerge {
        Snapshot before;
        std::uint64_t state = 0;  // partition_hash() of `before`
        std::vector<std::pair<int, int>> pairs;  // none: no merge pending
        double unexplained = 0;  // unexplained() before it, or its reference stage's if more
        double energy = 0;       // the energy before it, likewise
        double margin = 0;       // per pair its noise and `convergence` of the energy; handfuls' cost
        double cost = 0;         // handfuls': what their unions' fits cost (in `margin` too)
        bool handful = false;    // merge_handful's: one alone is judged by the energy (see judge_merge)
        Snapshot merged;         // Lloyd settled after it, while its reference stage runs
        double merged_unexplained = 0;
    };
    PendingMerge pending_merge_;
    // unexplained() and the energy after a Lloyd stage from a partition (its
    // partition_hash()), no merge made: under noise only (judge_merge).
    struct Reference {
        std::uint64_t state = 0;
        double unexplained = 0, energy = 0;
    };
    Reference reference_;
    // Merges undone: rejection_context() and the two regions' fingerprints, in order.
    std::set<std::array<std::uint64_t, 3>> rejected_merges_;
    int merge_batch_ = 0;    // how many pairs the finish may merge at once (0: not yet set)
    int handful_batch_ = 0;  // how many handfuls, likewise
    // The vertex tests' answers (see fingerprint), by the regions asked.
    mutable std::unordered_map<std::uint64_t, VertexSurface> vertex_surfaces_;
    // A region's vertices (sorted) and their moments, by fingerprint (plainly_on_no_quadric).
    struct RegionVertices {
        std::vector<int> sorted;
        Moments moments{};
    };
    mutable std::unordered_map<std::uint64_t, RegionVertices> region_vertices_;
    mutable std::size_t region_vertices_kept_ = 0;  // their vertices, in all
    mutable std::unordered_map<std::uint64_t, bool> vertices_on_one_surface_;
    mutable std::unordered_map<std::uint64_t, ExactRegion> exact_regions_;
    mutable std::unordered_map<std::uint64_t, Union> unions_;  // fit_pair's
    mutable std::unordered_map<std::uint64_t, std::optional<MergeCandidate>> same_surface_candidates_;
    // keeps_type's model selection for the larger region of a pair, by its fingerprint and
    // quadric: the finish asks it of one region beside each of its neighbours, and again
    // after merges elsewhere (the noisy plate assembly at detail 3: half of 1 000 asks).
    mutable std::unordered_map<std::uint64_t, int> region_kinds_;
    std::unordered_map<std::uint64_t, bool> stop_splits_;  // ensure_valid's verdicts
    Snapshot snapshot_;
    // At a fixed count: growing past it as the automatic count does, then merging back to it.
    enum class Regrowth { untried, growing, merging, done };
    Regrowth regrowth_ = Regrowth::untried;
    Snapshot before_regrowth_;  // the partition it started from, which stands if it does no better
    StopReason regrowth_reason_ = StopReason::none;  // the stop it delayed
    // The stop a Lloyd stage after its repair delays (none: no such stage), and the repaired
    // partition, which stands if the stage does no better.
    StopReason settling_ = StopReason::none;
    Snapshot repaired_;
    Operation last_operation_ = Operation::initialize;
    StopReason stop_reason_ = StopReason::none;
    bool cancel_requested_ = false;
};

}  // namespace vqsa
