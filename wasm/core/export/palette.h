// The colour legend of quadric types, shared by the glTF export and the browser.
#pragma once

#include "fitting/classify.h"

namespace vqsa {

// Linear RGB in [0, 1].
Vec3 type_color(QuadricType type);

// A region's colour: its type's colour, darkened by up to 22 % (by region id, golden
// ratio steps) so that neighbouring regions of one type stay apart.
Vec3 region_color(QuadricType type, int region);

}  // namespace vqsa
