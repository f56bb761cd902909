// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// One particle's interpolation stencil: the 1-D weights and gradients of each axis, computed
/// once per step and shared by every transfer (P2G, G2P, velocity gradient). N-D weights are
/// their tensor product (docs/physics.md section 2).

#include "gimlet/core/grid.hpp"
#include "gimlet/core/space.hpp"
#include "gimlet/core/radial_factors.hpp"

#include <array>
#include <cassert>
#include <cstddef>
#include <type_traits>

namespace gimlet::shape {
template <class Sh>
struct axisymmetric_form;  // shape/axisymmetric.hpp
}  // namespace gimlet::shape

namespace gimlet::detail {

/// Nothing: a member a configuration does without (the axis factors outside an axisymmetric
/// space, a stage that is compiled out).
struct nothing {};

/// An axisymmetric stencil's factors along r beyond the weights: the hoop factor T^r of each
/// node (1/m), and the coefficients of the particle's position velocity, the plain (not
/// r-weighted) shape's weights with the nodes beyond the axis folded onto their mirror images
/// (v_r odd, v_z even across the axis).
template <class Real, int W>
struct axis_factors {
    std::array<Real, W> hoop;   ///< T^r
    std::array<Real, W> pos_r;  ///< the radial velocity's coefficient
    std::array<Real, W> pos_z;  ///< the axial velocity's coefficient
};

/// \tparam S the space, \tparam W the nodes per axis of the shape function.
template <Space S, int W>
struct stencil {
    using real = typename S::real;
    using vector = typename S::vector;
    static constexpr int dim = S::dim;

    std::array<std::array<int, W>, dim> offset;  ///< storage offset of each node along each axis
    std::array<std::array<real, W>, dim> w;      ///< 1-D weights
    std::array<std::array<real, W>, dim> dw;     ///< 1-D derivatives (1/m)
    std::array<real, dim> local;                 ///< particle position from the first node (cells)
    int first_row = 0;  ///< storage index of the first node along the last axis (the solver's slab)
    /// Axisymmetric space: the radial hoop factor T^r of each node along r (1/m), T_ip = T^r S^z,
    /// and the position velocity's coefficients (axis_factors, for_each_position).
    [[no_unique_address]] std::conditional_t<is_axisymmetric_v<S>, axis_factors<real, W>, nothing> axis;

    /// \param x particle position (m); \param half_width per axis, in cell units.
    template <class Shape>
    void compute_with(const grid<S>& g, const vector& x, const vector& half_width) {
        if constexpr (is_axisymmetric_v<S>) {
            // Along r the shape's axisymmetric form (r-weighted, the axis at r = 0 = the grid's
            // lower bound), along z its own weights.
            const real h = g.cell();
            std::array<radial_factors<real>, W> f;
            int first = 0;
            shape::axisymmetric_form<Shape>::radial(x[0], half_width[0] * h, h, first, f);
            finish_axis(g, 0, x[0] * g.inv_cell(), first);
            for (int a = 0; a < W; ++a) w[0][a] = f[a].weight, dw[0][a] = f[a].gradient, axis.hoop[a] = f[a].hoop;
            // The domain's midpoint moves with the plain shape's interpolation, which gives a
            // linear field's value at r_p; the nodes beyond the axis carry their mirror images'
            // velocities (docs/equations.md, "Axisymmetric GIMP").
            std::array<real, W> plain, slope;
            int plain_first = 0;
            Shape::weights(x[0] / h, half_width[0], plain_first, plain.data(), slope.data());
            assert(plain_first == first);  // both locate r_p / h
            for (int a = 0; a < W; ++a) {
                const bool beyond = first + a < 0;
                axis.pos_r[a] = beyond ? real(0) : plain[a];
                axis.pos_z[a] = beyond ? real(0) : plain[a];
            }
            for (int a = 0; a < W; ++a)
                if (first + a < 0) {
                    const int mirror = -(first + a) - first;  // node -k's place in the stencil
                    axis.pos_r[mirror] -= plain[a];
                    axis.pos_z[mirror] += plain[a];
                }
            const real zc = (x[1] - g.spec().lower[1]) * g.inv_cell();
            int first_z = 0;
            Shape::weights(zc, half_width[1], first_z, w[1].data(), dw[1].data());
            finish_axis(g, 1, zc, first_z);
            return;
        }
        // A shape that computes both axes of a 2-D particle at once (ugimp, cpgimp: faster under
        // g++, the same numbers bit for bit) is asked for them together. It names itself in
        // weights_2d_shape: a shape derived from it inherits the member, not the name.
        if constexpr (dim == 2 && std::is_same_v<real, double> &&
                      requires(const std::array<double, 2>& xs, std::array<int, 2>& f, std::array<std::array<double, W>, 2>& ws) {
                          requires std::is_same_v<typename Shape::weights_2d_shape, Shape>;
                          Shape::weights_2d(xs, xs, f, ws, ws);
                      }) {
            const std::array<double, 2> xc{(x[0] - g.spec().lower[0]) * g.inv_cell(), (x[1] - g.spec().lower[1]) * g.inv_cell()};
            const std::array<double, 2> l{half_width[0], half_width[1]};
            std::array<int, 2> first{};
            Shape::weights_2d(xc, l, first, w, dw);
            for (int d = 0; d < dim; ++d) finish_axis(g, d, xc[d], first[d]);
            return;
        }
        for (int d = 0; d < dim; ++d) {
            const real xc = (x[d] - g.spec().lower[d]) * g.inv_cell();
            int first = 0;
            Shape::weights(xc, half_width[d], first, w[d].data(), dw[d].data());
            finish_axis(g, d, xc, first);
        }
    }

    /// What follows an axis's weights: the position in the stencil, the nodes' storage offsets,
    /// and the gradients from cell units to 1/m.
    void finish_axis(const grid<S>& g, int d, real xc, int first) {
        local[d] = xc - real(first);
        first_row = g.template axis_offsets<W>(d, first, offset[d].data());
        for (int a = 0; a < W; ++a) dw[d][a] *= g.inv_cell();
    }

    /// Call f(node, weight, r) for every node of the stencil, in for_each's order, where
    /// r = x_p - x_i (m) is measured to that node (unwrapped across periodic seams).
    template <class F>
    void for_each_offset(real h, F&& f) const {
        if constexpr (dim == 2) {
            for (int b = 0; b < W; ++b)
                for (int a = 0; a < W; ++a)
                    f(static_cast<std::size_t>(offset[0][a] + offset[1][b]), w[0][a] * w[1][b],
                      vector((local[0] - real(a)) * h, (local[1] - real(b)) * h));
        } else {
            for (int c = 0; c < W; ++c)
                for (int b = 0; b < W; ++b)
                    for (int a = 0; a < W; ++a)
                        f(static_cast<std::size_t>(offset[0][a] + offset[1][b] + offset[2][c]), w[0][a] * w[1][b] * w[2][c],
                          vector((local[0] - real(a)) * h, (local[1] - real(b)) * h, (local[2] - real(c)) * h));
        }
    }

    /// Call f(node, weight, position) for every node of the stencil, in for_each's order (and
    /// with its weights), where position is g.node_position(node) to the bit: each axis's W
    /// positions are formed once (grid::axis_position) instead of dividing the flat index twice
    /// per axis at every node.
    template <class F>
    void for_each_node_position(const grid<S>& g, F&& f) const {
        std::array<std::array<real, W>, dim> at;
        for (int d = 0; d < dim; ++d)
            for (int a = 0; a < W; ++a) at[d][a] = g.axis_position(d, offset[d][a]);
        if constexpr (dim == 2) {
            for (int b = 0; b < W; ++b)
                for (int a = 0; a < W; ++a)
                    f(static_cast<std::size_t>(offset[0][a] + offset[1][b]), w[0][a] * w[1][b], vector(at[0][a], at[1][b]));
        } else {
            for (int c = 0; c < W; ++c)
                for (int b = 0; b < W; ++b)
                    for (int a = 0; a < W; ++a)
                        f(static_cast<std::size_t>(offset[0][a] + offset[1][b] + offset[2][c]), w[0][a] * (w[1][b] * w[2][c]),
                          vector(at[0][a], at[1][b], at[2][c]));
        }
    }

    /// The number of nodes of a stencil.
    static constexpr std::size_t nodes = [] {
        std::size_t n = 1;
        for (int d = 0; d < dim; ++d) n *= std::size_t(W);
        return n;
    }();

    /// Axisymmetric space: call f(node, weight, gradient, hoop) for every node of the stencil, in
    /// for_each's order, where hoop is T_ip = T^r S^z (1/m).
    template <class F>
    void for_each_hoop(F&& f) const
        requires(is_axisymmetric_v<S>)
    {
        for (int b = 0; b < W; ++b)
            for (int a = 0; a < W; ++a) {
                const vector g(dw[0][a] * w[1][b], w[0][a] * dw[1][b]);
                f(static_cast<std::size_t>(offset[0][a] + offset[1][b]), w[0][a] * w[1][b], g, axis.hoop[a] * w[1][b]);
            }
    }

    /// Axisymmetric space: call f(node, cr, cz) for every node of the stencil, in for_each's
    /// order, where the particle's position moves with sum (cr v_ir, cz v_iz): the domain's
    /// midpoint's velocity (axis_factors).
    template <class F>
    void for_each_position(F&& f) const
        requires(is_axisymmetric_v<S>)
    {
        for (int b = 0; b < W; ++b)
            for (int a = 0; a < W; ++a)
                f(static_cast<std::size_t>(offset[0][a] + offset[1][b]), axis.pos_r[a] * w[1][b], axis.pos_z[a] * w[1][b]);
    }

    /// Call f(node, weight, gradient) for every node of the stencil.
    template <class F>
    void for_each(F&& f) const {
        if constexpr (dim == 2) {
            for (int b = 0; b < W; ++b)
                for (int a = 0; a < W; ++a) {
                    const vector g(dw[0][a] * w[1][b], w[0][a] * dw[1][b]);
                    f(static_cast<std::size_t>(offset[0][a] + offset[1][b]), w[0][a] * w[1][b], g);
                }
        } else {
            for (int c = 0; c < W; ++c)
                for (int b = 0; b < W; ++b)
                    for (int a = 0; a < W; ++a) {
                        const real wbc = w[1][b] * w[2][c];
                        const vector g(dw[0][a] * wbc, w[0][a] * dw[1][b] * w[2][c], w[0][a] * w[1][b] * dw[2][c]);
                        f(static_cast<std::size_t>(offset[0][a] + offset[1][b] + offset[2][c]), w[0][a] * wbc, g);
                    }
        }
    }
};

}  // namespace gimlet::detail
