// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// The silent numerical guards a run met (solver::health()).

#include "gimlet/eos/concepts.hpp"

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>

namespace gimlet {

/// The silent numerical guards that acted on particles in a run (eos::guard): how often each
/// kind did, and the first particle it met (its body, place and step). A guard that stops the
/// run throws a numerical_error instead and is not counted here. Counted when the guarded value
/// enters a step (the wave speeds of a time step the solver chose).
struct health_events {
    static constexpr std::size_t kinds = eos::guard::kinds;
    /// Column names, in eos::guard bit order.
    static constexpr std::array<const char*, kinds> names = {"eos_compression_capped", "eos_negative_modulus",
                                                             "no_wave_speed"};
    /// What each kind did, in the same order (the text after the particle in `first`).
    static constexpr std::array<const char*, kinds> what = {
        "the EOS's tangent modulus was taken at the capped compression (the singularity margin)",
        "the EOS's tangent modulus was negative and taken as 0",
        "(K + 4G/3)/rho was not positive: the wave speed was taken as 0"};
    std::array<std::uint64_t, kinds> count{};
    std::array<std::string, kinds> first;  ///< "step N (t = ...): particle i (body b) at (x, y) m: ..."; empty if none
    [[nodiscard]] std::uint64_t total() const noexcept {
        std::uint64_t n = 0;
        for (auto c : count) n += c;
        return n;
    }
};

}  // namespace gimlet
