// SPDX-License-Identifier: MIT
// Must not compile: a region without its bounding box (the seeding needs it). scene::check_region
// names it (docs/concepts.md, Material and Region).
// GIMLET_FAILTEST_EXPECT: needs `S::vector lower\(\) const`
#include <gimlet/scene/check.hpp>

using S = gimlet::space<2>;

struct half_plane {
    bool contains(const S::vector& x) const { return x[1] < 0.5; }
#ifdef GIMLET_FAILTEST_OK
    S::vector lower() const { return S::vector(0, 0); }
    S::vector upper() const { return S::vector(1, 0.5); }
#endif
};

static_assert(gimlet::scene::check_region<half_plane, S>());

int main() { return 0; }
