// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// The silent numerical guards a run met (solver::health()).

#include "gimlet/core/fields.hpp"
#include "gimlet/core/grid.hpp"
#include "gimlet/eos/concepts.hpp"

#include <array>
#include <cstddef>
#include <cstdint>
#include <cmath>
#include <string>

namespace gimlet {

/// The silent numerical guards that acted on particles in a run (eos::guard): how often each
/// kind did, and the first particle it met (its body, place and step). A guard that stops the
/// run throws a numerical_error instead and is not counted here. Counted when the guarded value
/// enters a step (the wave speeds of a time step the solver chose).
struct health_events {
    /// Number of guard kinds (eos::guard::kinds).
    static constexpr std::size_t kinds = eos::guard::kinds;
    /// Column names, in eos::guard bit order.
    static constexpr std::array<const char*, kinds> names = {"eos_compression_capped", "eos_negative_modulus",
                                                             "no_wave_speed"};
    /// What each kind did, in the same order (the text after the particle in `first`).
    static constexpr std::array<const char*, kinds> what = {
        "the EOS's tangent modulus was taken at the capped compression (the singularity margin)",
        "the EOS's tangent modulus was negative and taken as 0",
        "(K + 4G/3)/rho was not positive: the wave speed was taken as 0"};
    /// How often each kind acted, in eos::guard bit order.
    std::array<std::uint64_t, kinds> count{};
    std::array<std::string, kinds> first;  ///< "step N (t = ...): particle i (body b) at (x, y) m: ..."; empty if none
    /// Sum of count over the kinds.
    [[nodiscard]] std::uint64_t total() const noexcept {
        std::uint64_t n = 0;
        for (auto c : count) n += c;
        return n;
    }
};

namespace detail {

/// The guards a time step met (solver::stable_time_step), held until that step is taken.
struct pending_health {
    std::uint64_t step = 0;
    bool valid = false;
    std::array<std::uint64_t, health_events::kinds> count{};
    std::array<std::ptrdiff_t, health_events::kinds> first{};

    /// Into `health`, if they belong to step `now`; `describe(i)` names particle i.
    template <class Describe>
    void commit(health_events& health, std::uint64_t now, Describe describe) {
        if (!valid || step != now) return;
        valid = false;
        for (std::size_t k = 0; k < health_events::kinds; ++k) {
            if (count[k] == 0) continue;
            health.count[k] += count[k];
            if (health.first[k].empty()) health.first[k] = describe(std::size_t(first[k])) + ": " + health_events::what[k];
        }
    }
};

/// The first of the policies' own scalar fields the particle carries that is not finite (the
/// out-of-plane stress, the temperature, the plastic strain and work, the compression rate),
/// or nullptr. A specific heat of 1e-316 J/(kg K) makes the temperature infinite while every
/// core field stays finite. Users' own fields are theirs to check.
template <class P>
[[nodiscard]] const char* non_finite_policy_field(const P& p) {
    const char* bad = nullptr;
    auto test = [&]<class Tag>() {
        if constexpr (P::template has<Tag>)
            if (!bad && !std::isfinite(double(p.template get<Tag>()))) bad = Tag::name;
    };
    test.template operator()<fields::stress_zz>();
    test.template operator()<fields::temperature>();
    test.template operator()<fields::plastic_strain>();
    test.template operator()<fields::plastic_work>();
    test.template operator()<fields::compression_rate>();
    test.template operator()<fields::hoop_stretch>();
    return bad;
}

/// An axisymmetric particle's ring: off the axis (r > 0) with a positive hoop stretch; always
/// true in other spaces. The radial weights assume r_p > 0 (shape/detail/axisymmetric_gimp.hpp).
template <class P>
[[nodiscard]] bool ring_valid(const P& p) {
    if constexpr (is_axisymmetric_v<typename P::space_type>)
        return p.template get<fields::position>()[0] > 0 && p.template get<fields::hoop_stretch>() > 0;
    else
        return (void)p, true;
}

/// What particle_problem tests, without building its message (it runs for every particle and step).
template <class P, Space S>
[[nodiscard]] bool particle_healthy(const P& p, const grid<S>& g) {
    const auto& x = p.template get<fields::position>();
    return x.allFinite() && p.template get<fields::velocity>().allFinite() &&
           p.template get<fields::stress>().allFinite() &&
           std::isfinite(p.template get<fields::specific_internal_energy>()) && !non_finite_policy_field(p) &&
           p.template get<fields::deformation_gradient>().determinant() > 0 && ring_valid(p) && g.inside(x);
}

/// Why a particle stops the run (non-finite values, inverted, off the grid), or empty. Mass
/// and initial volume never change in a step, so only this check (of a scene's particles and of
/// particles changed between steps) reads them, and not particle_healthy.
template <class P, Space S>
[[nodiscard]] std::string particle_problem(const P& p, const grid<S>& g) {
    const double m = double(p.template get<fields::mass>()), v0 = double(p.template get<fields::volume0>());
    if (!(std::isfinite(m) && m > 0)) return "mass = " + detail::to_text(m) + " is not finite and > 0";
    if (!(std::isfinite(v0) && v0 > 0)) return "volume0 (initial volume) = " + detail::to_text(v0) + " is not finite and > 0";
    const auto& x = p.template get<fields::position>();
    if (!x.allFinite()) return "position is not finite";
    if (!p.template get<fields::velocity>().allFinite()) return "velocity is not finite";
    if (!p.template get<fields::stress>().allFinite()) return "stress is not finite";
    if (!std::isfinite(p.template get<fields::specific_internal_energy>())) return "internal energy is not finite";
    if (const char* name = non_finite_policy_field(p)) return std::string(name) + " is not finite";
    const auto j = p.template get<fields::deformation_gradient>().determinant();
    if (!(j > 0)) return "det F = " + detail::to_text(double(j)) + " <= 0 (inverted particle)";
    if constexpr (is_axisymmetric_v<typename P::space_type>) {
        const double r = double(x[0]), hoop = double(p.template get<fields::hoop_stretch>());
        if (!(hoop > 0)) return "hoop stretch = " + detail::to_text(hoop) + " <= 0 (inverted ring)";
        if (!(r > 0))
            return "reached the axis of symmetry: r = " + detail::to_text(r) +
                   " <= 0 (an axisymmetric particle is a ring of radius r > 0)";
    }
    if (!g.inside(x)) return "left the grid through a non-periodic boundary";
    return {};
}

}  // namespace detail

}  // namespace gimlet
