// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// A scene: the grid and the bodies that fill it. Built in C++, validated as it is built; the
/// solver turns it into particles.

#include "gimlet/core/error.hpp"
#include "gimlet/core/grid.hpp"
#include "gimlet/material/material.hpp"
#include "gimlet/scene/geometry.hpp"

#include <cmath>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

/// Scene set-up: the grid, the bodies, and the regions they fill.
namespace gimlet::scene {

/// One body: a region filled with particles of one material, moving at an initial velocity.
template <Space S, Material M>
struct body {
    /// A position or velocity: S::vector.
    using vector = typename S::vector;
    std::string name;                          ///< used in messages and output
    M material;                                ///< its parameter values
    vector velocity = vector::Zero();          ///< initial velocity (m/s)
    int particles_per_cell = 2;                ///< per axis; particle size is h / this
    std::function<bool(const vector&)> contains;  ///< the region (set-up only, never in the step)
    ///@{
    vector lower = vector::Zero(), upper = vector::Zero();  ///< the region's bounding box
    ///@}
};

/// The grid and the bodies of a simulation.
/// \tparam S the space, \tparam M the material type every body uses (its values may differ).
template <Space S, Material M>
class scene {
public:
    /// A position or velocity: S::vector.
    using vector = typename S::vector;
    /// The scene's body type.
    using body_type = body<S, M>;

    /// A scene with no bodies on the domain `grid` (checked when the solver builds its grid).
    explicit scene(const grid_spec<S>& grid) : grid_(grid) {}

    /// Add a body filling `region`. Returns the body id (its index).
    /// \param region             where the body is (scene::Region: box, ball, difference, ...).
    /// \param material           its material (validated here: material::validate()).
    /// \param velocity           its initial velocity (m/s), finite.
    /// \param particles_per_cell particles per cell per axis, 1 to 8.
    /// \param name               its name in messages and output; empty: "body <id>".
    /// \throws gimlet::invalid_parameter for a bad material, velocity or particles_per_cell, or a
    ///         region whose bounding box is not finite and ordered.
    template <Region<S> R>
    std::uint32_t add_body(const R& region, const M& material, const vector& velocity,
                           int particles_per_cell = 2, std::string name = {}) {
        material.validate();
        require(particles_per_cell >= 1 && particles_per_cell <= 8, "particles_per_cell",
                particles_per_cell, "1 to 8 (per axis)");
        for (int d = 0; d < S::dim; ++d) require_finite("initial velocity component (m/s)", double(velocity[d]));
        if (name.empty()) name = "body " + std::to_string(bodies_.size());
        const vector lo = region.lower(), hi = region.upper();
        for (int d = 0; d < S::dim; ++d) {
            const bool finite = std::isfinite(double(lo[d])) && std::isfinite(double(hi[d]));
            require(finite && hi[d] > lo[d],
                    "bounding box of " + name + " along " + std::string(1, "xyz"[d]) + " (upper - lower, m)",
                    double(hi[d]) - double(lo[d]), "finite and > 0 (a region with finite, ordered bounds)");
        }
        bodies_.push_back(body_type{std::move(name), material, velocity, particles_per_cell,
                                    [region](const vector& x) { return bool(region.contains(x)); },
                                    region.lower(), region.upper()});
        return static_cast<std::uint32_t>(bodies_.size() - 1);
    }

    /// The domain.
    [[nodiscard]] const grid_spec<S>& grid() const noexcept { return grid_; }
    /// The bodies, in the order added (their ids).
    [[nodiscard]] const std::vector<body_type>& bodies() const noexcept { return bodies_; }

private:
    grid_spec<S> grid_;
    std::vector<body_type> bodies_;
};

}  // namespace gimlet::scene
