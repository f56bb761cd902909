// SPDX-License-Identifier: MIT
// Must not compile: an axisymmetric particle updated without its hoop rate L_thetatheta, which
// the material update needs (the hoop stretch and D_thetatheta); the overload that takes it is named.
// GIMLET_FAILTEST_EXPECT: needs its hoop rate
#include <gimlet/gimlet.hpp>

using A = gimlet::axisymmetric_space<double>;
using fields = gimlet::field_union_t<gimlet::core_fields<A>, gimlet::field_list<>>;

int main() {
    gimlet::particle_store<A, fields> store;
    store.add();
    store.column<gimlet::fields::mass>()[0] = 1;
    store.column<gimlet::fields::volume0>()[0] = 1;
    const auto mat = gimlet::make_elastic_material(1, 1, 0);
#ifdef GIMLET_FAILTEST_OK
    gimlet::update_material_point(mat, store[0], A::matrix::Zero(), 0.0, 1e-3, 1.0, 0, 0.0);
#else
    gimlet::update_material_point(mat, store[0], A::matrix::Zero(), 1e-3, 1.0, 0, 0.0);
#endif
    return 0;
}
