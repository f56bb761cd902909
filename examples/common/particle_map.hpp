// SPDX-License-Identifier: MIT
#pragma once
// The particle maps the examples' figures are drawn from (examples' helper, not part of the
// library).

#include <gimlet/core/detail/omp.hpp>
#include <gimlet/core/fields.hpp>
#include <gimlet/core/processes.hpp>
#include <gimlet/material/update.hpp>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstddef>
#include <exception>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace example {

// A particle map for figures, one CSV row per particle (in 3-D, of the section y = 0): position (mm), mean pressure (MPa),
// temperature (K), body and the in-plane deformation gradient F (cavity_collapse's plot.py
// paints each particle as its current domain, its initial square mapped by F, so that only a
// real gap shows; docs/io.md, "The flagship's particle maps"). The numbers are
// exact_numbers' (std::to_chars' shortest text that reads back to the same double), formatted
// straight into a buffer, a block of consecutive particles on each of the run's threads, and
// written in block order: the bytes a stream through exact_numbers writes, particle by particle,
// in a fraction of its time, and on every thread (a serial pass would leave the others idle).
// The whole map is held as text until it is written: about 160 bytes a particle.
// From `parallel_from` particles the rows are formatted on `threads` threads.
template <class Store>
void write_map_of(const std::filesystem::path& file, const Store& ps, int threads, std::size_t parallel_from,
                        double section_y = 0) {
    constexpr int dim = Store::space_type::dim;
    const std::size_t n = ps.size();
    const std::size_t blocks = n >= parallel_from && threads > 1 ? std::size_t(threads) : 1;
    const std::size_t size = (n + blocks - 1) / blocks;
    std::vector<std::string> text(blocks);
    // An exception must not leave the parallel region (that ends the program): a block's
    // (an allocation that fails) is kept and thrown after it.
    std::vector<std::exception_ptr> failed(blocks);
    GIMLET_OMP(parallel for schedule(static, 1) num_threads(int(blocks)))
    for (std::ptrdiff_t b = 0; b < std::ptrdiff_t(blocks); ++b) {
        try {
            std::string& t = text[std::size_t(b)];
            char buf[32];
            auto put = [&](auto v, char end) {
                t.append(buf, std::to_chars(buf, buf + sizeof buf, v).ptr);
                t += end;
            };
            const std::size_t first = std::min(n, std::size_t(b) * size), last = std::min(n, first + size);
            t.reserve((last - first) * 160);
            // 2-D: every particle, (x, y) or (r, z). 3-D: the section y = section_y, the particles
            // within a spacing of it (the layer on each side of a plane between two layers, the
            // first layer beside a symmetry plane), in x and z, with F's (x, z) block.
            constexpr int up = dim - 1;
            for (std::size_t i = first; i < last; ++i) {
                const auto p = ps[i];
                const auto& x = p.template get<gimlet::fields::position>();
                if constexpr (dim == 3)
                    if (!(std::abs(x[1] - section_y) < 2 * p.template get<gimlet::fields::domain_half_width>()[1])) continue;
                put(double(x[0] * 1e3), ',');
                put(double(x[up] * 1e3), ',');
                put(double(gimlet::mean_pressure(p) * 1e-6), ',');
                put(double(p.template get<gimlet::fields::temperature>()), ',');
                put(p.template get<gimlet::fields::body>(), ',');
                const auto& F = p.template get<gimlet::fields::deformation_gradient>();
                put(double(F(0, 0)), ',');
                put(double(F(0, up)), ',');
                put(double(F(up, 0)), ',');
                put(double(F(up, up)), '\n');
            }
        } catch (...) {
            failed[std::size_t(b)] = std::current_exception();
        }
    }
    for (const auto& e : failed)
        if (e) std::rethrow_exception(e);
    std::ofstream os(file);
    os << "x_mm,y_mm,pressure_MPa,temperature_K,body,F_xx,F_xy,F_yx,F_yy\n";
    for (const auto& t : text) os.write(t.data(), std::streamsize(t.size()));
    if (!os) throw std::runtime_error("could not write " + file.string());
}

// The map of a solver's particles, on the solver's threads. On many processes
// (solver_options::processes) it is collective: the particles are gathered in ordinal order and
// the first process writes the map one process writes (a failure to write stops every process).
template <class Solver>
void write_particle_map(const std::filesystem::path& file, const Solver& sol, std::size_t parallel_from,
                        double section_y = 0) {
    if (gimlet::processes* many = sol.processes()) {
        const auto whole = sol.gathered_particles();
        many->together([&] {
            if (many->rank() == 0) write_map_of(file, whole, sol.threads(), parallel_from, section_y);
        });
        return;
    }
    write_map_of(file, sol.particles(), sol.threads(), parallel_from, section_y);
}

}  // namespace example
