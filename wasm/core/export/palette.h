// The colours of regions and quadric types: one palette for the GLB and the browser
// (the web build writes it into the viewer's schema module, scripts/write-schema.mjs).
#pragma once

#include "fitting/classify.h"

#include <nlohmann/json.hpp>

namespace vqsa {

// Linear RGB in [0, 1].
Vec3 type_color(QuadricType type);

// Regions' colours repeat after this many ids: a table of that size describes the whole
// palette to a front end.
constexpr int kRegionPaletteSize = 256;

// A region's colour, linear RGB: golden-ratio steps of hue, alternating lightness, so
// that regions with neighbouring ids (often neighbours on the mesh) stay apart.
Vec3 region_color(int region);

// The whole palette as data: {"types": {type name: RGB} for every type a region can have,
// "regions": the kRegionPaletteSize region colours}.
nlohmann::json palette_json();

}  // namespace vqsa
