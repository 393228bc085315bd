// Procedural CAD parts whose every triangle knows the true face it was cut from, and
// every face its true surface: the ground truth of the CAD-extraction tests and
// benchmarks, and examples for the app. Faces are meshed as structured bands between
// boundary polylines that neighbouring faces share point for point, so the parts are
// watertight and crease-exact.
#pragma once

#include "fitting/classify.h"
#include "io/mesh.h"

#include <cstdint>
#include <string>
#include <vector>

namespace vqsa {

// A face's true surface in the part's coordinates. `point`: a point of the plane, the
// sphere's centre, a point of the cylinder's axis, the cone's apex; `axis`: the plane's
// normal or the axis (towards the cone's opening); `half_angle` in radians.
struct TrueSurface {
    QuadricType type = QuadricType::plane;
    Vec3 point = Vec3::Zero();
    Vec3 axis = Vec3::UnitZ();
    double radius = 0;
    double half_angle = 0;
};

struct Part {
    std::string name;
    Mesh mesh;
    std::vector<int> face;              // true face of every kept triangle (Mesh::triangles)
    std::vector<TrueSurface> surfaces;  // one per true face
};

struct PartOptions {
    // Boundary samples with a density varying by about 6× and jittered rows: edge
    // lengths vary by more than 5× across the part.
    bool irregular = false;
    // Gaussian displacement of every vertex along its normal, σ relative to the
    // bounding-box diagonal.
    double noise = 0;
    bool random_pose = false;  // a random rotation and translation
    std::uint64_t seed = 1;    // pose, jitter and noise
    double detail = 1;         // scales every sample count (faces grow as its square)
};

// box_boss_hole, l_bracket, stepped_shaft, flange, thin_plate, slotted_block (the corpus
// the CAD-extraction tests hold to their accuracy), then shapes beyond it, measured but
// not held to the corpus's bar: rounded_block (no crease anywhere), plate_assembly (three
// thin plates, 39 faces on three components), hex_nut, chamfered_box, tube, pencil,
// roof_block, oblique_hole, d_shaft (a flat along a cylinder), octagon_bore (sides bending
// 45°), domed_cylinder (a sphere meeting a cylinder at 34°), angled_cut (a bar cut at 50°: its
// crease runs out half way round), bowl (two concentric spheres 4 % of their radius apart),
// dish (a paraboloid of revolution on a disc), rolled_sheet, countersunk_plate (a cone and a
// bore one facet row each, meeting at 45°), rounded_plate (sides of two triangles between
// corners of 11 facets) and stepped_block (two walls and the chamfer between them, each in
// quads of full-height triangles).
std::vector<std::string> part_names();
std::vector<std::string> corpus_part_names();
// Throws std::invalid_argument for an unknown name.
Part make_part(const std::string& name, const PartOptions& options = {});

// Gaussian noise along the vertex normals, σ = `relative` × the bounding-box diagonal, as
// the parts' noisy variants have it: for other meshes (a shared CAD export made noisy).
void add_normal_noise(Mesh& mesh, double relative, std::uint64_t seed);

}  // namespace vqsa
