#include "io/mesh_io.h"
#include "io/text_tokenizer.h"

#include <cstring>
#include <vector>

namespace vqsa {

namespace {

PolygonSoup read_binary_stl(std::string_view bytes, std::uint32_t triangles) {
    PolygonSoup soup;
    soup.positions.reserve(3 * std::size_t{triangles});
    const char* record = bytes.data() + 84;
    for (std::uint32_t t = 0; t < triangles; ++t, record += 50) {
        int corner[3];
        for (int k = 0; k < 3; ++k) {
            float xyz[3];
            std::memcpy(xyz, record + 12 + 12 * k, sizeof xyz);  // STL is little-endian, as are our targets
            corner[k] = static_cast<int>(soup.positions.size());
            soup.positions.emplace_back(xyz[0], xyz[1], xyz[2]);
        }
        soup.add_polygon(corner, 3);
    }
    return soup;
}

PolygonSoup read_ascii_stl(std::string_view text) {
    TextTokenizer in(text, '\0');
    PolygonSoup soup;
    std::vector<int> loop;
    bool in_loop = false;
    while (!in.at_end()) {
        const std::string_view t = in.token("a keyword");
        if (t == "vertex") {
            if (!in_loop) in.fail("'vertex' outside 'outer loop'");
            loop.push_back(static_cast<int>(soup.positions.size()));
            soup.positions.push_back(in.point());
        } else if (t == "loop") {
            in_loop = true;
            loop.clear();
        } else if (t == "endloop") {
            if (!in_loop) in.fail("'endloop' without 'outer loop'");
            if (loop.size() < 3) in.fail("a facet with fewer than three vertices");
            soup.add_polygon(loop.data(), loop.size());
            in_loop = false;
        }
    }
    if (in_loop) in.fail("the file ends inside a facet (truncated)");
    return soup;
}

}  // namespace

PolygonSoup read_stl(std::string_view bytes) {
    // Binary STL headers may begin with "solid" too, so the size decides.
    if (bytes.size() >= 84) {
        std::uint32_t triangles;
        std::memcpy(&triangles, bytes.data() + 80, 4);
        if (84 + 50 * std::uint64_t{triangles} == bytes.size()) return read_binary_stl(bytes, triangles);
    }
    std::size_t start = 0;
    while (start < bytes.size() && (bytes[start] == ' ' || bytes[start] == '\t' || bytes[start] == '\r' || bytes[start] == '\n'))
        ++start;
    if (bytes.substr(start, 5) != "solid") {
        if (bytes.size() < 84) throw std::invalid_argument("too short for a binary STL and not an ASCII one");
        std::uint32_t triangles;
        std::memcpy(&triangles, bytes.data() + 80, 4);
        throw std::invalid_argument("binary STL header announces " + std::to_string(triangles) + " triangles (" +
                                    std::to_string(84 + 50 * std::uint64_t{triangles}) + " bytes) but the file has " +
                                    std::to_string(bytes.size()) + " bytes (truncated or corrupt)");
    }
    return read_ascii_stl(bytes);
}

}  // namespace vqsa
