// The example meshes the app and the CLI offer (procedural, made here).
#pragma once

#include "io/mesh.h"

#include <string>
#include <vector>

namespace vqsa {

std::vector<std::string> example_names();

// `name`, or `name:FACES` for about FACES triangles (the resolution scales; at most
// 20 million). Throws std::invalid_argument for an unknown name or a bad size.
Mesh example_mesh(const std::string& name);

}  // namespace vqsa
