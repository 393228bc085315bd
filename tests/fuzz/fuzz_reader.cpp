// libFuzzer target for one mesh reader (FUZZ_EXTENSION picks it): any input must either
// read or fail with a MeshReadError. Crashes, leaks, hangs and UB are findings.
#include "io/mesh_io.h"

#include <cstddef>
#include <cstdint>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    try {
        vqsa::read_mesh("fuzz." FUZZ_EXTENSION, data, size);
    } catch (const vqsa::MeshReadError&) {
    }
    return 0;
}
