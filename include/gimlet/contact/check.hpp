// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// contact::check<C>(): a contact policy checked against contact::Contact, with each missing
/// requirement named in plain words (docs/concepts.md, Contact).

#include "gimlet/contact/concepts.hpp"
#include "gimlet/core/material_point.hpp"

#include <concepts>

namespace gimlet::contact {

namespace check_detail {
template <class C>
concept has_flag = requires {
    { C::multi_field } -> std::convertible_to<bool>;
};
template <class C, class S>
concept in_contact_any = requires(C& c, const pair_view<S>& p) { c.in_contact(p); };
template <class C, class S>
concept in_contact_const = requires(const C& c, const pair_view<S>& p) {
    { c.in_contact(p) } -> std::convertible_to<bool>;
};
template <class C, class S>
concept resolve_any = requires(C& c, node_view<S>& n) { c.resolve(n); };
template <class C>
concept friction_any = requires(C& c) { c.friction(); };
template <class C>
concept friction_const = requires(const C& c) {
    { c.friction() } -> std::convertible_to<double>;
};
template <class C, class S>
concept impulse_any = requires(C& c, const pair_view<S>& p) { c.impulse(p); };
template <class C, class S>
concept impulse_const = requires(const C& c, const pair_view<S>& p) {
    { c.impulse(p) } -> std::convertible_to<typename S::vector>;
};
template <class C, class S>
concept resolve_const = requires(const C& c, node_view<S>& n) { c.resolve(n); };
// An after_contact in any form: called on a non-const policy with an lvalue particle handle and
// the info, or with the particle alone.
template <class C, int D>
concept hook_any = requires(C& c, archetype_particle<D, C>& p, const particle_contact<space<D, double>>& i) {
    c.after_contact(p, i);
} || requires(C& c, archetype_particle<D, C>& p) { c.after_contact(p); };
}  // namespace check_detail

/// True if C is a contact policy (contact::Contact); otherwise the compiler stops here with one
/// message per missing requirement. Put it after your policy:
/// \code
/// static_assert(gimlet::contact::check<my_contact>());
/// \endcode
template <class C>
consteval bool check() {
    using S2 = space<2, double>;
    using S3 = space<3, double>;
    static_assert(check_detail::has_flag<C>,
                  "contact policy: needs `static constexpr bool multi_field` (true: one grid velocity field per "
                  "body; false: one field for all, bodies stick where they meet)");
    static_assert(declares_required_fields<C>,
                  "contact policy: needs `using required_fields = gimlet::field_list<...>;` (field_list<> if it "
                  "keeps no per-particle state)");
    if constexpr (check_detail::has_flag<C>) {
        if constexpr (C::multi_field) {
            constexpr bool law = check_detail::in_contact_any<C, S2> || check_detail::in_contact_any<C, S3>;
            constexpr bool resolver = check_detail::resolve_any<C, S2> || check_detail::resolve_any<C, S3>;
            static_assert(law || resolver,
                          "multi-field contact policy: needs `template <gimlet::Space S> bool in_contact(const "
                          "gimlet::contact::pair_view<S>&) const` (a contact law), or the low-level `template "
                          "<gimlet::Space S> void resolve(gimlet::contact::node_view<S>&) const`");
            static_assert(!(law && resolver),
                          "multi-field contact policy: has both in_contact and resolve; a policy is a contact law "
                          "or a node resolver, not both");
            if constexpr (law && !resolver) {
                static_assert(!(check_detail::in_contact_any<C, S2> && !check_detail::in_contact_const<C, S2>) &&
                                  !(check_detail::in_contact_any<C, S3> && !check_detail::in_contact_const<C, S3>),
                              "contact law: in_contact must be const and return something convertible to bool (the "
                              "framework asks it at many nodes, in any order, on a const policy)");
                static_assert(check_detail::in_contact_any<C, S2> && check_detail::in_contact_any<C, S3>,
                              "contact law: in_contact must accept 2-D and 3-D pair views (write it as `template "
                              "<gimlet::Space S> bool in_contact(const gimlet::contact::pair_view<S>&) const`)");

                // Optional members: ignored if their form is wrong, so say so.
                if constexpr (check_detail::friction_any<C>)
                    static_assert(check_detail::friction_const<C>,
                                  "contact law: friction() must be const and return a number (the Coulomb "
                                  "coefficient, >= 0)");
                if constexpr (check_detail::impulse_any<C, S2> || check_detail::impulse_any<C, S3>)
                    static_assert(check_detail::impulse_const<C, S2> && check_detail::impulse_const<C, S3>,
                                  "contact law: impulse must be const, accept 2-D and 3-D pair views and return the "
                                  "momentum for body a (`template <gimlet::Space S> typename S::vector impulse(const "
                                  "gimlet::contact::pair_view<S>&) const`)");
                if constexpr (requires { typename C::tally; })
                    static_assert(Counting<C, S2> && Counting<C, S3>,
                                  "contact law: a `tally` needs `void count(tally&, const pair_view<S>&, const "
                                  "pair_outcome<S>&) const` for 2-D and 3-D, a non-const `void record(const tally&)`, "
                                  "and `tally& operator+=(const tally&)`");
            }
            // The per-particle hook is optional too: one the solver cannot call would be skipped.
            if constexpr (check_detail::hook_any<C, 2> || check_detail::hook_any<C, 3>)
                static_assert(ParticleHook<C, archetype_particle<2, C>, S2> && ParticleHook<C, archetype_particle<3, C>, S3>,
                              "contact policy: after_contact must be `template <class P, gimlet::Space S> void "
                              "after_contact(const P& particle, const gimlet::contact::particle_contact<S>& info) const` "
                              "(const, the particle handle by value or const reference, 2-D and 3-D); the solver "
                              "calls nothing else");
            if constexpr (resolver && !law) {
                static_assert(!(check_detail::resolve_any<C, S2> && !check_detail::resolve_const<C, S2>) &&
                                  !(check_detail::resolve_any<C, S3> && !check_detail::resolve_const<C, S3>),
                              "node resolver: resolve must be const (keep counts in a contact law's tally instead)");
                static_assert(check_detail::resolve_any<C, S2> && check_detail::resolve_any<C, S3>,
                              "node resolver: resolve must accept 2-D and 3-D node views (write it as `template "
                              "<gimlet::Space S> void resolve(gimlet::contact::node_view<S>&) const`)");
            }
        }
    }
    return Contact<C>;
}

}  // namespace gimlet::contact
