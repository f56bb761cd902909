// SPDX-License-Identifier: MIT
#pragma once
// Shared by the benchmarks (not part of the library): the reference scene (two_blocks), the 2-D
// HMX scene, flag parsing, timing and medians.

#include <gimlet/gimlet.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

namespace bench {

using S2 = gimlet::space<2, double>;

/// --name value pairs; every flag a benchmark reads must be known, so a typo is an error.
class flags {
public:
    flags(int argc, char** argv) {
        for (int i = 1; i < argc; ++i) {
            const std::string a = argv[i];
            if (a.rfind("--", 0) != 0 || i + 1 >= argc) throw std::invalid_argument("unexpected argument '" + a + "'");
            values_[a.substr(2)] = argv[++i];
        }
    }
    double number(const std::string& name, double fallback) {
        const auto it = values_.find(name);
        if (it == values_.end()) return fallback;
        char* end = nullptr;
        const double v = std::strtod(it->second.c_str(), &end);
        if (!end || *end != '\0' || !std::isfinite(v)) throw std::invalid_argument("--" + name + ": not a number");
        values_.erase(it);
        return v;
    }
    std::string text(const std::string& name, const std::string& fallback) {
        const auto it = values_.find(name);
        if (it == values_.end()) return fallback;
        std::string v = it->second;
        values_.erase(it);
        return v;
    }
    void finish() const {
        if (!values_.empty()) throw std::invalid_argument("unknown flag --" + values_.begin()->first);
    }

private:
    std::map<std::string, std::string> values_;
};

inline double seconds_since(std::chrono::steady_clock::time_point t0) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

inline double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    const std::size_t n = v.size();
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

inline gimlet::update_scheme parse_scheme(const std::string& s) {
    if (s == "musl") return gimlet::update_scheme::musl;
    if (s == "usl") return gimlet::update_scheme::usl;
    if (s == "usf") return gimlet::update_scheme::usf;
    throw std::invalid_argument("--scheme must be musl, usl or usf");
}

/// Two blocks 40 mm x 50 mm, one above the other, `gap` apart, at +-300 m/s along y; periodic in
/// x, free in y with 10 mm of room at each end: the benchmarks' reference scene (gap 4 mm) and
/// the paper's contact validation geometry (examples/contact_validation).
template <class M, class Sp = S2>
gimlet::scene::scene<Sp, M> two_blocks(const M& mat, double cell, double gap, double velocity = 300.0) {
    constexpr double width = 40e-3, height = 50e-3, margin = 10e-3;
    gimlet::grid_spec<Sp> gs;
    gs.lower = typename Sp::vector(0.0, -margin);
    gs.upper = typename Sp::vector(width, 2 * height + gap + margin);
    gs.cell = typename Sp::real(cell);
    gs.bc = {gimlet::boundary::periodic, gimlet::boundary::free};
    gimlet::scene::scene<Sp, M> sc(gs);
    sc.add_body(gimlet::scene::box<Sp>(typename Sp::vector(0.0, 0.0), typename Sp::vector(width, height)), mat,
                typename Sp::vector(0.0, velocity), 2, "lower block");
    sc.add_body(gimlet::scene::box<Sp>(typename Sp::vector(0.0, height + gap), typename Sp::vector(width, 2 * height + gap)),
                mat, typename Sp::vector(0.0, -velocity), 2, "upper block");
    return sc;
}

/// The reference scene's material: E = 11.87 GPa, nu = 0.25, rho = 1900 kg/m^3 (HMX's elastic
/// constants, linear elastic).
inline gimlet::elastic_material reference_material() { return gimlet::make_elastic_material(1900.0, 11.87e9, 0.25); }

/// The reference scene's time step at 0.5 mm cells, scaled with the cell so the Courant number
/// stays the same (about 0.1 with c = 2.9 km/s).
inline double reference_dt(double cell) { return 1.4e-8 * cell / 0.5e-3; }

}  // namespace bench
