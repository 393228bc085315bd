// What a run produces, as plain data in the input's coordinates: everything the report,
// the GLB, the bindings and the benchmarks need, with no engine behind it.
#pragma once

#include "edit/edit.h"
#include "fitting/classify.h"
#include "fitting/quadric.h"
#include "lloyd/lloyd.h"
#include "pipeline/options.h"
#include "post/metrics.h"

#include <optional>
#include <vector>

namespace vqsa {

struct RunnerUp {
    QuadricType type = QuadricType::plane;
    double rms = 0;
};

struct ProxyResult {
    int id = 0;
    QuadricType type = QuadricType::plane;
    bool special_fit = false;  // a geometric fit of its type, not the region's general quadric
    // The chosen type's RMS distance to the region's vertices, and the best candidate of
    // another type with its own (when types were selected: refit on).
    double type_rms = 0;
    std::optional<RunnerUp> runner_up;
    Quadric quadric;           // unit coefficient norm, largest coefficient positive
    Classification shape;      // the type's parameters
    int faces = 0;
    double area = 0;
    double rms_error = 0;  // RMS Taubin distance of the region to its quadric
    bool locked = false;   // by an edit: later edits leave its faces and quadric alone
    ImposedType imposed = ImposedType::none;  // by an edit
};

struct InputInfo {
    int vertices = 0;    // distinct positions in the file
    int faces = 0;       // triangles after fanning polygons
    int faces_used = 0;  // after dropping zero-area ones
    int components = 0;
    double bbox_diagonal = 0;
    double bbox_longest_side = 0;
};

struct Timing {  // seconds
    double load = 0, lloyd = 0, postprocess = 0, total = 0;
    // The post-processing stages (0 for one that did not run): their sum is `postprocess`.
    double smooth = 0, refit = 0, project = 0, measure = 0;
    std::vector<double> edits;  // each edit's, in order (the run's stages exclude them)
};

struct Result {
    InputInfo input;
    Options options;
    StopReason stop_reason = StopReason::none;
    int iterations = 0;  // Lloyd iterations
    double rms_error = 0;           // RMS Taubin distance over the mesh
    double rms_error_relative = 0;  // ... over the longest bounding-box side
    std::vector<ProxyResult> proxies;
    // Region of every face: in the input's face order (-1 for dropped faces), and in the
    // order of the faces kept (Mesh::triangles); before smoothing too.
    std::vector<int> labels, lloyd_labels;
    std::vector<int> face_labels, lloyd_face_labels;
    std::vector<Vec3> projected;  // one per mesh vertex; empty when not projected
    std::optional<Metrics> metrics;  // per region too, indexed by proxy id
    Timing timing;
    std::vector<Edit> edits;  // applied after the run, in order (faces in the input's order)
};

}  // namespace vqsa
