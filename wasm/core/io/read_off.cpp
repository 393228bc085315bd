#include "io/mesh_io.h"
#include "io/text_tokenizer.h"

#include <vector>

namespace vqsa {

PolygonSoup read_off(std::string_view text) {
    TextTokenizer in(text);
    std::string_view keyword = in.token("the OFF header");
    std::int64_t counts[3];
    int known = 0;
    if (keyword.size() >= 3 && keyword.substr(keyword.size() - 3) == "OFF") {
        const std::string_view prefix = keyword.substr(0, keyword.size() - 3);
        if (prefix.find_first_of("4n") != std::string_view::npos)
            in.fail("'" + std::string(keyword) + "' (OFF in other than three dimensions) is not supported");
    } else if (parse_integer(keyword, counts[0])) {
        known = 1;  // some writers omit the keyword
    } else {
        in.fail("not an OFF file: it starts with '" + std::string(keyword.substr(0, 20)) + "'");
    }
    for (int i = known; i < 3; ++i) counts[i] = in.integer(i == 0 ? "the vertex count" : i == 1 ? "the face count" : "the edge count");
    const std::int64_t nv = counts[0], nf = counts[1];
    if (nv < 0 || nf < 0) in.fail("negative vertex or face count");
    // A vertex takes at least 6 characters, a face at least 8: counts beyond that are lies.
    if (nv > static_cast<std::int64_t>(text.size() / 6) || nf > static_cast<std::int64_t>(text.size() / 8))
        in.fail("the header announces " + std::to_string(nv) + " vertices and " + std::to_string(nf) +
                " faces, more than the file can hold (truncated or corrupt)");
    in.skip_line();

    PolygonSoup soup;
    soup.positions.reserve(static_cast<std::size_t>(nv));
    for (std::int64_t i = 0; i < nv; ++i) {
        soup.positions.push_back(in.point());
        in.skip_line();  // colours, normals
    }
    std::vector<int> polygon;
    for (std::int64_t f = 0; f < nf; ++f) {
        const std::int64_t n = in.integer("a face's vertex count");
        if (n < 0 || n > 1 << 20) in.fail("a face with " + std::to_string(n) + " vertices");
        polygon.clear();
        for (std::int64_t k = 0; k < n; ++k) {
            const std::int64_t v = in.integer("a vertex index");
            if (v < 0 || v >= nv)
                in.fail("vertex index " + std::to_string(v) + " is out of range (0.." + std::to_string(nv - 1) + ")");
            polygon.push_back(static_cast<int>(v));
        }
        soup.add_polygon(polygon.data(), polygon.size());
        in.skip_line();  // colours
    }
    return soup;
}

}  // namespace vqsa
