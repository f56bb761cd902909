// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// Conserved quantities of a particle system: mass, linear momentum, kinetic and internal
/// energy. Each is the exact sum of its particles' terms rounded once (gimlet::exact_sum), so it
/// does not depend on the particle order, the thread count or how the particles are split
/// between processes. On many processes (solver_options::processes) each is the whole run's,
/// collective: every process calls it. In plane
/// strain they are per metre of depth; in an axisymmetric space they are the whole body's, the
/// rings' per-radian sums times 2 pi (the integral over theta of the weak form's r dr dz).

#include "gimlet/core/exact_sum.hpp"
#include "gimlet/core/fields.hpp"
#include "gimlet/core/processes.hpp"
#include "gimlet/core/space.hpp"

#include <array>
#include <cstddef>
#include <numbers>
#include <type_traits>
#include <utility>

/// Observers and measurements of a running solver: conserved quantities, hot spots, void
/// surfaces, schedules for solver::run_until, a progress line.
namespace gimlet::diagnostics {

namespace detail {
// A sum over this process's particles completed over every process of the run (the solver's
// processes(), where it has some): exact, so the same bits as one process's sum.
template <class Solver>
[[nodiscard]] exact_sum over_processes(const Solver& s, const exact_sum& part) {
    if (gimlet::processes* p = gimlet::detail::processes_of(s)) return p->sum(part);
    return part;
}

// A per-radian sum of an axisymmetric solver times 2 pi: the whole body's; other sums as they are.
template <class Solver, class T>
[[nodiscard]] T whole_body(T sum) {
    using store_type = std::remove_cvref_t<decltype(std::declval<const Solver&>().particles())>;
    if constexpr (is_axisymmetric_v<typename store_type::space_type>) return 2 * std::numbers::pi * sum;
    else return sum;
}
}  // namespace detail

/// Total mass sum m_p (kg; per unit thickness in plane strain; 2 pi sum m_p axisymmetric).
template <class Solver>
[[nodiscard]] double total_mass(const Solver& s) {
    exact_sum m;
    for (auto mp : s.particles().template column<fields::mass>()) m += double(mp);
    return detail::whole_body<Solver>(detail::over_processes(s, m).value());
}

/// Linear momentum sum m_p v_p (axisymmetric: 2 pi sum m_p v_p, whose radial component is no
/// momentum of the body, which has none along r by symmetry, and is not conserved: the hoop
/// stress pushes the rings radially).
template <class Solver>
[[nodiscard]] Eigen::Matrix<double, Solver::dim, 1> linear_momentum(const Solver& s) {
    const auto& m = s.particles().template column<fields::mass>();
    const auto& v = s.particles().template column<fields::velocity>();
    std::array<exact_sum, Solver::dim> sum;
    for (std::size_t i = 0; i < m.size(); ++i)
        for (int d = 0; d < Solver::dim; ++d) sum[std::size_t(d)] += double(m[i]) * double(v[i][d]);
    Eigen::Matrix<double, Solver::dim, 1> p;
    for (int d = 0; d < Solver::dim; ++d) p[d] = detail::over_processes(s, sum[std::size_t(d)]).value();
    return detail::whole_body<Solver>(p);
}

/// Kinetic energy sum m_p |v_p|^2 / 2 (J; axisymmetric: times 2 pi).
template <class Solver>
[[nodiscard]] double kinetic_energy(const Solver& s) {
    const auto& m = s.particles().template column<fields::mass>();
    const auto& v = s.particles().template column<fields::velocity>();
    exact_sum e;
    for (std::size_t i = 0; i < m.size(); ++i) e += 0.5 * double(m[i]) * v[i].template cast<double>().squaredNorm();
    return detail::whole_body<Solver>(detail::over_processes(s, e).value());
}

/// Internal energy sum m_p e_p (J): the stress work stored in (elastic: strain energy) or
/// dissipated by the material since the start, integrated from sigma:D (docs/physics.md section 1);
/// axisymmetric: times 2 pi.
template <class Solver>
[[nodiscard]] double internal_energy(const Solver& s) {
    const auto& m = s.particles().template column<fields::mass>();
    const auto& e = s.particles().template column<fields::specific_internal_energy>();
    exact_sum u;
    for (std::size_t i = 0; i < m.size(); ++i) u += double(m[i]) * double(e[i]);
    return detail::whole_body<Solver>(detail::over_processes(s, u).value());
}

/// One sample of the conserved quantities (per unit thickness in plane strain; the whole body's
/// in an axisymmetric space).
template <int Dim>
struct conservation_sample {
    /// Simulated time (s).
    double time = 0;
    /// Total mass (kg): total_mass().
    double mass = 0;
    /// Linear momentum (kg m/s): linear_momentum().
    Eigen::Matrix<double, Dim, 1> momentum = Eigen::Matrix<double, Dim, 1>::Zero();
    /// Kinetic energy (J): kinetic_energy().
    double kinetic = 0;
    /// Internal energy (J): internal_energy().
    double internal = 0;
    /// kinetic + internal (J).
    [[nodiscard]] double total_energy() const { return kinetic + internal; }
};

/// Take a sample now.
template <class Solver>
[[nodiscard]] conservation_sample<Solver::dim> sample_conservation(const Solver& s) {
    return {double(s.time()), total_mass(s), linear_momentum(s), kinetic_energy(s), internal_energy(s)};
}

}  // namespace gimlet::diagnostics
