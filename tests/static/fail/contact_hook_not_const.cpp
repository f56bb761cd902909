// SPDX-License-Identifier: MIT
// Must not compile: a contact law whose per-particle hook is not const. The solver would skip it
// (and the field it writes would stay at its initial value); contact::check names it instead,
// with g++ 12 and clang 14 alike (docs/concepts.md, Contact).
// GIMLET_FAILTEST_EXPECT: after_contact must be
#include <gimlet/contact/check.hpp>

struct touched {
    template <class S> using type = typename S::real;
    static constexpr const char* name = "touched";
};

struct marking {
    static constexpr bool multi_field = true;
    using required_fields = gimlet::field_list<touched>;
    template <gimlet::Space S>
    bool in_contact(const gimlet::contact::pair_view<S>& pair) const {
        return pair.gap <= pair.cell;
    }
#ifdef GIMLET_FAILTEST_OK
    template <class P, gimlet::Space S>
    void after_contact(const P& p, const gimlet::contact::particle_contact<S>& info) const {
        if (info.engaged) p.template get<touched>() += 1;
    }
#else
    template <class P, gimlet::Space S>
    void after_contact(const P& p, const gimlet::contact::particle_contact<S>& info) {
        if (info.engaged) p.template get<touched>() += 1;
    }
#endif
};

static_assert(gimlet::contact::check<marking>());

int main() { return 0; }
