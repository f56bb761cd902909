// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// Conserved quantities of a particle system: mass, linear momentum, kinetic and internal
/// energy. Sums run in particle order, so they do not depend on the thread count.

#include "gimlet/core/fields.hpp"

#include <cstddef>

/// Observers and measurements of a running solver: conserved quantities, hot spots, void
/// surfaces, schedules for solver::run_until, a progress line.
namespace gimlet::diagnostics {

/// Total mass sum m_p (kg; per unit thickness in 2-D).
template <class Solver>
[[nodiscard]] double total_mass(const Solver& s) {
    double m = 0;
    for (auto mp : s.particles().template column<fields::mass>()) m += double(mp);
    return m;
}

/// Linear momentum sum m_p v_p.
template <class Solver>
[[nodiscard]] Eigen::Matrix<double, Solver::dim, 1> linear_momentum(const Solver& s) {
    const auto& m = s.particles().template column<fields::mass>();
    const auto& v = s.particles().template column<fields::velocity>();
    Eigen::Matrix<double, Solver::dim, 1> p = Eigen::Matrix<double, Solver::dim, 1>::Zero();
    for (std::size_t i = 0; i < m.size(); ++i) p += double(m[i]) * v[i].template cast<double>();
    return p;
}

/// Kinetic energy sum m_p |v_p|^2 / 2 (J).
template <class Solver>
[[nodiscard]] double kinetic_energy(const Solver& s) {
    const auto& m = s.particles().template column<fields::mass>();
    const auto& v = s.particles().template column<fields::velocity>();
    double e = 0;
    for (std::size_t i = 0; i < m.size(); ++i) e += 0.5 * double(m[i]) * v[i].template cast<double>().squaredNorm();
    return e;
}

/// Internal energy sum m_p e_p (J): the stress work stored in (elastic: strain energy) or
/// dissipated by the material since the start, integrated from sigma:D (docs/physics.md section 1).
template <class Solver>
[[nodiscard]] double internal_energy(const Solver& s) {
    const auto& m = s.particles().template column<fields::mass>();
    const auto& e = s.particles().template column<fields::specific_internal_energy>();
    double u = 0;
    for (std::size_t i = 0; i < m.size(); ++i) u += double(m[i]) * double(e[i]);
    return u;
}

/// One sample of the conserved quantities.
template <int Dim>
struct conservation_sample {
    /// Simulated time (s).
    double time = 0;
    /// Total mass (kg; per unit thickness in 2-D): total_mass().
    double mass = 0;
    /// Linear momentum (kg m/s; per unit thickness in 2-D): linear_momentum().
    Eigen::Matrix<double, Dim, 1> momentum = Eigen::Matrix<double, Dim, 1>::Zero();
    /// Kinetic energy (J; per unit thickness in 2-D): kinetic_energy().
    double kinetic = 0;
    /// Internal energy (J; per unit thickness in 2-D): internal_energy().
    double internal = 0;
    /// kinetic + internal (J; per unit thickness in 2-D).
    [[nodiscard]] double total_energy() const { return kinetic + internal; }
};

/// Take a sample now.
template <class Solver>
[[nodiscard]] conservation_sample<Solver::dim> sample_conservation(const Solver& s) {
    return {double(s.time()), total_mass(s), linear_momentum(s), kinetic_energy(s), internal_energy(s)};
}

}  // namespace gimlet::diagnostics
