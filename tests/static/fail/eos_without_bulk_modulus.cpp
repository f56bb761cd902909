// SPDX-License-Identifier: MIT
// Must not compile: an EOS without bulk_modulus (the time step needs it). eos::check names it.
// GIMLET_FAILTEST_EXPECT: needs `template <class Real, class P> Real bulk_modulus
#include <gimlet/eos/check.hpp>

struct gas {
    using required_fields = gimlet::field_list<>;
    template <class Real, class P>
    Real pressure(const gimlet::point_step<Real>& st, const P&) const {
        return Real(1e5) / st.J;
    }
#ifdef GIMLET_FAILTEST_OK
    template <class Real, class P>
    Real bulk_modulus(const gimlet::point_state<Real>& st, const P&) const {
        return Real(1e5) / st.J;
    }
#endif
};

static_assert(gimlet::eos::check<gas>());

int main() { return 0; }
