// SPDX-License-Identifier: MIT
// Must not compile: reading a field the scene does not store (temperature without a thermal
// policy) is a compile-time error, never a run-time lookup.
// GIMLET_FAILTEST_EXPECT: no matching function
#include <gimlet/gimlet.hpp>

int main() {
    using S = gimlet::space<2>;
    using solver = gimlet::solver<S, gimlet::shape::ugimp, gimlet::elastic_material>;
    solver::store_type store;
#ifdef GIMLET_FAILTEST_OK
    return static_cast<int>(store.column<gimlet::fields::mass>().size());
#else
    return static_cast<int>(store.column<gimlet::fields::temperature>().size());
#endif
}
