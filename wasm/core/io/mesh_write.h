// Writing triangle meshes as OBJ, PLY (binary) or OFF.
#pragma once

#include "io/mesh.h"

#include <string>
#include <string_view>
#include <vector>

namespace vqsa {

// The file's bytes; the format is chosen by `name`'s extension (.obj, .ply, .off).
// Throws std::invalid_argument for other extensions.
std::string write_mesh(std::string_view name, const std::vector<Vec3>& vertices, const std::vector<Triangle>& triangles);

}  // namespace vqsa
