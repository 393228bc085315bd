// The one translation unit that compiles tinygltf (Debian ships it header-only for
// our purposes: emcc cannot link the host's shared library).
#define TINYGLTF_IMPLEMENTATION
#include <tiny_gltf.h>
