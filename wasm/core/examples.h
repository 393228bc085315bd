// The example meshes the app and the CLI offer (procedural, made here).
#pragma once

#include "mesh.h"

#include <string>
#include <vector>

namespace vqsa {

std::vector<const char*> example_names();

// Throws std::invalid_argument for an unknown name.
Mesh example_mesh(const std::string& name);

}  // namespace vqsa
