// The result as one binary glTF (GLB) that carries every region's quadric.
#pragma once

#include "io/mesh.h"
#include "pipeline/result.h"

#include <string>

namespace vqsa {

// How COLOR_0 paints the regions: each its own colour, or its quadric type's (palette.h).
enum class GlbColours { region, type };

// Node "input" (scene 0): the input mesh, vertices split along region borders, coloured as
// `colours` says, with normals and the region of each vertex in _FEATURE_ID_0
// (EXT_mesh_features) pointing into an EXT_structural_metadata property table with one
// row per region. Node "projected" (scene 1): the projected mesh, when the run projected it.
// The same per-region data is plain JSON in the input mesh's `extras.regions` (indexed by
// feature id), and the run in the scene's `extras`. Everything in input coordinates.
// Triangles keep the input's face order (zero-area faces are left out and listed in
// `extras.dropped_faces`).
// `result` must come from a run on `mesh`.
std::string export_glb(const Mesh& mesh, const Result& result, GlbColours colours = GlbColours::region);

// "region" or "type"; throws std::invalid_argument naming the choices otherwise.
GlbColours glb_colours_from(const std::string& name);

}  // namespace vqsa
