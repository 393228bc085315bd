// The colours of regions and quadric types: one palette for the GLB and the browser
// (the web build writes it into the viewer's schema module, scripts/write-schema.mjs).
#pragma once

#include "fitting/classify.h"

#include <nlohmann/json.hpp>

namespace vqsa {

// Oklab (Ottosson 2020) of a linear RGB colour: a space where distance follows perceived
// difference, unlike RGB or HSL hue.
Vec3 oklab(const Vec3& linear_rgb);

// How different two linear RGB colours look on a shaded mesh: Oklab distance with
// lightness at half weight, as shading varies lightness across every region.
double color_difference(const Vec3& a, const Vec3& b);

// Linear RGB in [0, 1].
Vec3 type_color(QuadricType type);

// Regions' colours repeat after this many ids: a table of that size describes the whole
// palette to a front end.
constexpr int kRegionPaletteSize = 256;

// A region's colour, linear RGB. Each id's colour is the one farthest, perceptually, from
// all lower ids' (palette.cpp): any two of the first n regions differ as much as n
// colours can, so that neighbours on the mesh, whatever their ids, stay apart.
Vec3 region_color(int region);

// The whole palette as data: {"types": {type name: RGB} for every type a region can have,
// "regions": the kRegionPaletteSize region colours}.
nlohmann::json palette_json();

}  // namespace vqsa
