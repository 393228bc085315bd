// Exact surface moments of triangles: the integrals ∫ x^i y^j z^k dA, i+j+k ≤ 4.
// They are all that quadric fitting needs (docs/METHOD.md §1): a region's moments are the
// sum of its faces', so refitting costs 35 additions per face and fitting the union
// of two regions costs one addition of sums.
#pragma once

#include "io/mesh.h"

#include <array>

namespace vqsa {

constexpr int kMomentCount = 35;
using Moments = std::array<double, kMomentCount>;

// Position of x^i y^j z^k in a Moments array: by degree, then by decreasing power of
// x, then of y. The first ten entries are the quadric monomials 1, x, y, z, x², xy,
// xz, y², yz, z² in the order of the coefficients C0..C9.
int moment_index(int i, int j, int k);

Moments triangle_moments(const Vec3& a, const Vec3& b, const Vec3& c);

// The moments of a weighted point: fitting to a point set (a region's vertices, which
// lie on a CAD surface where its triangles do not) sums these.
Moments point_moments(const Vec3& p, double weight);

// ∫ ((p - center) / scale)^e dA for every exponent e: the same surface seen from a
// frame centred at `center` and shrunk by `scale` (the area element is unchanged).
Moments shifted_moments(const Moments& m, const Vec3& center, double scale);

inline void add_to(Moments& sum, const Moments& m) {
    for (int i = 0; i < kMomentCount; ++i) sum[i] += m[i];
}

}  // namespace vqsa
