// Scoring a partition against a part's true faces: the area labelled as its true face
// under the best one-to-one matching of regions to faces, and the types found.
#pragma once

#include "cad_parts.h"
#include "fitting/samples.h"
#include "geometry/model.h"
#include "pipeline/result.h"

#include <string>
#include <vector>

namespace vqsa {

struct PartitionScore {
    double accuracy = 0;       // matched area / total area
    std::vector<int> face_of;  // per region: its matched true face, or -1
    // Per region: it and its matched face share at least 90 % of the area of each (the
    // patches whose type and parameters are judged).
    std::vector<char> clean_match;
};

// The corpus the CAD-extraction tests and benchmarks score: every part, clean, with
// Gaussian noise of 0.2 % of the diagonal along the normals, and irregularly meshed, each
// in its own random pose: the parts of corpus_part_names(), or of `parts` (each keeps the
// seeds it has in the order of part_names()).
struct CorpusCase {
    std::string part, variant;  // variant: clean, noisy, irregular
    PartOptions options;
};
std::vector<CorpusCase> cad_corpus(const std::vector<std::string>& parts = corpus_part_names());

// `labels`: region of every kept triangle of part.mesh; `regions`: how many there are.
PartitionScore score_partition(const Part& part, const std::vector<int>& labels, int regions);

// The share of the area lying in its region's largest chart (`chart`: per face, of the same
// mesh's faces, such as a clean export's crease charts): 1 when no region crosses a chart.
double area_within_one_chart(const Model& model, const std::vector<int>& chart, const std::vector<int>& labels,
                             int regions);

// Regions of a result whose reported type has two parts and whose faces lie on both
// (each part holding 1 % of the region's area and three of its faces, as PartWeights
// counts them; faces within twice the type's RMS of where the parts separate counting on
// neither): what a valid result never has.
int two_part_regions(const Mesh& mesh, const Result& result);

// How far a region's parameters (`found`, in the part's frame) lie from its true face's,
// for a region of the true type; NaN where the type has no such parameter.
struct ParameterError {
    double axis_degrees;     // plane normal; cylinder and cone axis (either direction)
    double radius_relative;  // sphere, cylinder: |r − r₀| / r₀
    double half_angle_degrees;  // cone
};
ParameterError parameter_error(const TrueSurface& truth, const Classification& found);

// Each vertex of a true face once, of weight one: what a fit to exactly its faces sees.
Samples true_face_vertices(const Part& part, int face);

// The assignment maximising Σ weight[i][assignment[i]] over distinct columns (-1 where a
// row gets none): the Hungarian method, O(n³) on the square completion.
std::vector<int> best_assignment(const std::vector<std::vector<double>>& weight);

}  // namespace vqsa
