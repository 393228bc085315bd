// Which surface a region is: the candidate types fitted to its vertices, and the simplest
// one the data do not reject, by the Bayesian information criterion (docs/METHOD.md §6).
#pragma once

#include "fitting/classify.h"
#include "fitting/fit.h"
#include "fitting/quadric.h"
#include "fitting/samples.h"

#include <optional>
#include <string>

namespace vqsa {

struct TypedFit {
    QuadricType type = QuadricType::plane;
    Quadric quadric;       // unit coefficient norm
    Classification shape;  // the type's parameters
    // Weighted RMS of the samples' Taubin distance (second-order, below the true distance,
    // equal to it for a plane), the same measure for every candidate.
    double rms = 0;
    int parameters = 0;    // degrees of freedom of the type
    bool special = false;  // one of the geometric fits, not the region's general quadric
    double bic = 0;
};

// A CAD surface: one of the plane, sphere, circular cylinder and circular cone fits (the
// types a part's faces are made of).
bool elementary(const TypedFit& c);

struct ModelChoice {
    TypedFit chosen;
    // The best candidate of another type: among those the edges' midpoints left, else
    // among those they ruled out (how clear the choice was, for the report).
    std::optional<TypedFit> runner_up;
};

// A type imposed on a region by hand (an edit): one of the geometric fits, or the general
// quadric whatever its affine type. `none` lets the data choose.
enum class ImposedType { none, plane, sphere, cylinder, cone, quadric };
const char* imposed_type_name(ImposedType type);
// Throws std::invalid_argument listing the names when `name` is none of them.
ImposedType imposed_type_from(const std::string& name);

struct ModelSelectionOptions {
    // Mean squared distances below (floor × region radius)² count as zero: every type
    // that contains the surface fits a clean tessellation's vertices to rounding.
    double floor = 1e-9;
    // Nor do distances below what the input stores (RMS, in the samples' units; the
    // library selects in the unit frame, where this is kStoredPrecision): a float STL's
    // rounding must not make a sphere of a cylinder's band.
    double stored = kStoredPrecision;
    ClassifyOptions classify;
    // The candidate of this type wins whatever the criterion says (if its fit exists).
    ImposedType imposed = ImposedType::none;
    // With a type imposed, whether the other types are fitted too (for the runner-up).
    bool rivals = true;
};

// `vertices`: each vertex of the region once (the vertices of a CAD tessellation lie on
// the surface; the barycentres do not), of equal weights under noise per vertex.
// `general`: the region's quadric. Candidates: plane (3 parameters), sphere (4), circular
// cylinder (5), circular cone (6), elliptic paraboloid (8) and the general quadric with its
// affine type (its degrees of freedom, 6 to 9) — unless it has two parts with vertices on
// both, or is a pair of planes (one of them is the plane candidate). The chosen one
// minimises n ln(MSE + floor² + stored² + tolerance²) + k ln(n), n the number of vertices, the
// tolerance the samples' own (region_samples: the tessellation's chordal deviation, below
// which a closer fit is no evidence). The edges' midpoints (Samples::edge_midpoints) say
// where the surface runs between the vertices: a candidate ten times farther from them
// than another, beyond the tessellation's deviation, is dropped, however closely it holds
// the vertices (a strip's two rows of vertices, a pin's two end circles, lie on many
// quadrics); among the candidates left that are exact to the floor, they break the tie,
// and so they do under noise among the plane, sphere, cylinder and cone where the
// criterion chose one of those (docs/METHOD.md §6). With a type imposed, the best
// candidate of that type is chosen; std::invalid_argument when none could be fitted (a
// sphere through a flat region).
ModelChoice select_model(const Samples& vertices, const Quadric& general, const ModelSelectionOptions& options = {});

// The RMS distance by which candidates compete: Taubin's, each point's capped at a few
// times the samples' noise on a noisy mesh (beyond that a point tells of the partition, not
// of the region's surface).
double selection_rms(const Samples& s, const Quadric& q);

// A region's general quadric as select_model weighs it: typed by its affine type in the
// frame of these vertices, with its RMS; none when no region could be that surface (empty,
// a pair of planes, whose one plane the region would be, or two parts with vertices on both).
std::optional<TypedFit> general_fit(const Quadric& q, const Samples& vertices, const ClassifyOptions& options = {});

// Whether descend moves a fit: a general quadric of a type no CAD face has. A special fit,
// or a general quadric typed plane, sphere, cylinder or cone (a part's surface, which the
// selection weighed against its rivals), stays as chosen.
bool descends(const TypedFit& fit);

// The chosen fit, if it descends, with its coefficients descended (Levenberg–Marquardt) to
// the least RMS Taubin distance of `samples`, the distance every candidate is measured by
// and the mesh is then projected along: the moment and Taubin fits minimise algebraic sums,
// which weigh each point by its gradient there. The pipeline descends over the region's
// vertices weighted by area (VertexWeight::area), for a free-form region has no surface
// through its vertices to recover, only its surface to approximate, as the distance between
// the input and the projected mesh measures it. The descended quadric is typed anew (a
// hyperboloid of one sheet may pass its cone to become one of two) and is chosen if the
// criterion, on `samples`, prefers it to the start and some region could be it (not a pair
// of planes, empty, or two parts with vertices on both); the fit it started from is then
// the runner-up if the type changed, its RMS measured on `samples`.
ModelChoice descend(const Samples& samples, const ModelChoice& choice, const ModelSelectionOptions& options = {});

}  // namespace vqsa
