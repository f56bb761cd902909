// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// The stable time step of an explicit MPM step (gimlet::solver::stable_time_step).

#include "gimlet/core/detail/omp.hpp"
#include "gimlet/core/detail/shares.hpp"
#include "gimlet/core/fields.hpp"
#include "gimlet/core/grid.hpp"
#include "gimlet/eos/concepts.hpp"
#include "gimlet/material/update.hpp"
#include "gimlet/solver/health.hpp"
#include "gimlet/solver/options.hpp"

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace gimlet::detail {

/// dt = C h / max_p (c_p + |v_p|), c_p = sqrt((K + 4G/3) / rho) from the current state
/// (docs/physics.md section 1, step 6), with c_p raised to the viscosity's signal speed where an
/// artificial viscosity acts (viscosity::Viscosity), capped by options.max_time_step. The guards
/// the wave speeds met (eos::guard) go into `pending`, for step `step`, to be counted once that
/// step is taken. Loops of fewer than `parallel_from` particles run on one thread.
template <class S, class Store, class M>
[[nodiscard]] typename S::real stable_time_step(const Store& particles, const std::vector<M>& materials,
                                                const grid<S>& grid, const solver_options<S>& options, int threads,
                                                std::ptrdiff_t parallel_from, std::uint64_t step,
                                                pending_health& pending) {
    using real = typename S::real;
    const auto n = static_cast<std::ptrdiff_t>(particles.size());
    real fastest = 0;
    // The guards met on the way (health_events), counted once the step is taken.
    std::uint64_t n0 = 0, n1 = 0, n2 = 0;
    std::ptrdiff_t f0 = n, f1 = n, f2 = n;
    thread_shares shares(n, threads, n >= parallel_from);
    GIMLET_OMP(parallel reduction(max : fastest) reduction(+ : n0, n1, n2) reduction(min : f0, f1, f2) num_threads(shares.team()))
    for (auto claimed = shares.start(); shares.claim(claimed);)
        for (std::ptrdiff_t i = claimed.first, end = claimed.last; i < end; ++i) {
            const auto p = particles[static_cast<std::size_t>(i)];
            unsigned guards = 0;
            real c = longitudinal_wave_speed(p, materials[p.template get<fields::body>()], guards);
            if (guards != 0) {
                if (guards & eos::guard::compression_capped) ++n0, f0 = std::min(f0, i);
                if (guards & eos::guard::negative_modulus) ++n1, f1 = std::min(f1, i);
                if (guards & eos::guard::no_wave_speed) ++n2, f2 = std::min(f2, i);
            }
            if constexpr (M::viscosity_type::enabled)
                c = materials[p.template get<fields::body>()].viscosity.signal_speed(c, grid.cell(), p);
            fastest = std::max(fastest, c + p.template get<fields::velocity>().norm());
        }
    pending = {step, true, {n0, n1, n2}, {f0, f1, f2}};
    real dt = real(options.max_time_step);
    if (fastest > 0) dt = std::min(dt, real(options.cfl) * grid.cell() / fastest);
    return dt;
}

}  // namespace gimlet::detail
