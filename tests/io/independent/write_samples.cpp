// SPDX-License-Identifier: MIT
// Writes one file of every type gimlet writes, with hard values, and a manifest of what each
// holds, for read_back.py to read with implementations that share no code with the writers
// (VTK's own reader, Python's xml.etree, csv and struct): docs/testing.md, "Independent
// readers".
//
//   write_samples DIR
//
// DIR/series.pvd with series_000000.vtp and series_000001.vtp (2-D, Float64 points),
// DIR/points32.vtp (3-D, Float32 points), DIR/values.csv (io::exact_numbers), DIR/run.ckpt
// (io::save_checkpoint), and DIR/manifest.txt. The manifest is printed here with std::fprintf
// ("%a": hexadecimal floating point, exact) straight from the values handed to the writers,
// so neither side of the comparison goes through gimlet's text or binary formatting.
#include <gimlet/gimlet.hpp>

#include <cfloat>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>
#include <vector>

namespace {

namespace fields = gimlet::fields;

// A user field of arbitrary doubles: what the writers must carry exactly.
struct sample {
    template <class S> using type = typename S::real;
    static constexpr const char* name = "sample";
};

// Every kind of double a field can hold: signed zeros, the smallest subnormal, the extremes,
// values that overflow or underflow float32, non-finite ones, and ordinary ones.
const std::vector<double> specials{0.0,
                                   -0.0,
                                   0.1,
                                   -1.0 / 3.0,
                                   3.141592653589793,
                                   std::numeric_limits<double>::denorm_min(),
                                   std::numeric_limits<double>::min(),
                                   std::numeric_limits<double>::max(),
                                   -std::numeric_limits<double>::max(),
                                   double(FLT_MAX),
                                   1e39,   // beyond float32: inf there
                                   1e-46,  // below float32's subnormals: 0 there
                                   double(std::numeric_limits<float>::denorm_min()),
                                   std::numeric_limits<double>::infinity(),
                                   -std::numeric_limits<double>::infinity(),
                                   std::numeric_limits<double>::quiet_NaN(),
                                   123456789.123456789,
                                   -2.5e-300};

// The array name with every character XML must escape in an attribute.
const std::string odd_name = "odd <name> & \"quoted\" 'apostrophe'";

void hex(std::FILE* f, double v) {
    if (std::isnan(v)) std::fprintf(f, " nan");
    else std::fprintf(f, " %a", v);
}

template <class Solver>
void fill(Solver& sol, double shift) {
    auto& ps = sol.particles();
    auto& smp = ps.template column<sample>();
    auto& v = ps.template column<fields::velocity>();
    auto& sig = ps.template column<fields::stress>();
    for (std::size_t i = 0; i < ps.size(); ++i) {
        smp[i] = specials[(i + std::size_t(shift)) % specials.size()];
        for (int d = 0; d < Solver::dim; ++d) v[i][d] = specials[(3 * i + std::size_t(d)) % specials.size()];
        for (int r = 0; r < Solver::dim; ++r)
            for (int c = 0; c < Solver::dim; ++c) sig[i](r, c) = shift + 10.0 * r + c + 0.001 * double(i);
    }
}

template <class Solver>
void write_snapshot_manifest(std::FILE* f, const std::string& file, const Solver& sol, bool points64) {
    const auto& ps = sol.particles();
    const std::size_t n = ps.size();
    const auto& x = ps.template column<fields::position>();
    const auto& smp = ps.template column<sample>();
    const auto& v = ps.template column<fields::velocity>();
    const auto& sig = ps.template column<fields::stress>();
    const auto& body = ps.template column<fields::body>();
    std::fprintf(f, "vtp %s %zu", file.c_str(), n);
    hex(f, double(sol.time()));
    std::fprintf(f, "\n");
    auto array = [&](const char* name, const char* type, int comps, auto value) {
        std::fprintf(f, "array %s %s %d %s", file.c_str(), type, comps, name);
        for (std::size_t i = 0; i < n; ++i)
            for (int k = 0; k < comps; ++k) hex(f, value(i, k));
        std::fprintf(f, "\n");
    };
    const auto f32 = [](double d) { return double(static_cast<float>(d)); };
    array("Points", points64 ? "Float64" : "Float32", 3, [&](std::size_t i, int k) {
        const double c = k < Solver::dim ? double(x[i][k]) : 0.0;
        return points64 ? c : f32(c);
    });
    array("sample", "Float64", 1, [&](std::size_t i, int) { return double(smp[i]); });
    array("sample_f32", "Float32", 1, [&](std::size_t i, int) { return f32(smp[i]); });
    array("velocity", "Float64", 3,
          [&](std::size_t i, int k) { return k < Solver::dim ? double(v[i][k]) : 0.0; });
    // A dim x dim stress, padded to 3 x 3 with zeros.
    array("stress", "Float32", 9, [&](std::size_t i, int k) {
        const int r = k / 3, c = k % 3;
        return r < Solver::dim && c < Solver::dim ? f32(sig[i](r, c)) : 0.0;
    });
    array("body", "Int32", 1, [&](std::size_t i, int) { return double(body[i]); });
    // The odd name is written on a line of its own: it holds spaces.
    std::fprintf(f, "array_named %s Float64 1", file.c_str());
    for (std::size_t i = 0; i < n; ++i) hex(f, 2.0 * double(x[i][0]) + 0.5);
    std::fprintf(f, "\nname %s\n", odd_name.c_str());
}

template <class Solver>
gimlet::io::vtp_writer<typename Solver::store_type> writer_for(gimlet::io::precision points) {
    using W = gimlet::io::vtp_writer<typename Solver::store_type>;
    using particle = typename W::particle;
    W w(points);
    w.template add_field<sample>()
        .add("sample_f32", [](const particle& p) { return p.template get<sample>(); }, gimlet::io::precision::float32)
        .template add_field<fields::velocity>()
        .template add_field<fields::stress>(gimlet::io::precision::float32)
        .template add_field<fields::body>()
        .add(odd_name, [](const particle& p) { return 2.0 * double(p.template get<fields::position>()[0]) + 0.5; });
    return w;
}

template <int Dim>
auto make_solver() {
    using S = gimlet::space<Dim>;
    using V = typename S::vector;
    gimlet::grid_spec<S> gs;
    gs.lower = V::Zero();
    gs.upper = V::Constant(0.05);
    gs.cell = 0.01;
    gimlet::scene::scene<S, gimlet::elastic_material> sc(gs);
    const auto mat = gimlet::make_elastic_material(1000, 1e6, 0.3);
    // 36 particles (216 in 3-D) and one: every special value at least once in every array.
    sc.add_body(gimlet::scene::box<S>(V::Constant(0.01), V::Constant(0.03)), mat, V::Zero(), 3, "first");
    sc.add_body(gimlet::scene::box<S>(V::Constant(0.03), V::Constant(0.04)), mat, V::Zero(), 1, "second");
    return gimlet::solver<S, gimlet::shape::ugimp, gimlet::elastic_material, gimlet::contact::single_field,
                          gimlet::field_list<sample>>(sc);
}

}  // namespace

int main(int argc, char** argv) {
    if (argc != 2) {
        std::fprintf(stderr, "usage: write_samples DIR\n");
        return 2;
    }
    const std::filesystem::path dir = argv[1];
    std::filesystem::create_directories(dir);
    std::FILE* m = std::fopen((dir / "manifest.txt").string().c_str(), "w");
    if (!m) return 1;

    // The series: two 2-D snapshots with Float64 points, the second at a time that needs 17
    // digits.
    auto sol2 = make_solver<2>();
    gimlet::io::pvd_writer series(dir / "series.pvd");
    const auto w2 = writer_for<decltype(sol2)>(gimlet::io::precision::float64);
    for (int k = 0; k < 2; ++k) {
        fill(sol2, double(k));
        sol2.resume_at(k == 0 ? 0.0 : 1.0000000000000002e-06, std::uint64_t(k));
        const auto file = series.write(w2, sol2).filename().string();
        write_snapshot_manifest(m, file, sol2, true);
        std::fprintf(m, "pvd series.pvd %d %s", k, file.c_str());
        hex(m, double(sol2.time()));
        std::fprintf(m, "\n");
    }

    // A 3-D snapshot with Float32 points, without a series.
    auto sol3 = make_solver<3>();
    fill(sol3, 2.0);
    sol3.resume_at(2.5e-7, 3);
    writer_for<decltype(sol3)>(gimlet::io::precision::float32).write(dir / "points32.vtp", sol3);
    write_snapshot_manifest(m, "points32.vtp", sol3, false);

    // A CSV as the examples write them: a header, then rows through io::exact_numbers.
    {
        std::ofstream csv(dir / "values.csv");
        gimlet::io::exact_numbers(csv);
        csv << "index,value,float_value,label\n";
        for (std::size_t i = 0; i < specials.size(); ++i)
            csv << i << ',' << specials[i] << ',' << static_cast<float>(specials[i]) << ",row" << i << '\n';
        std::fprintf(m, "csv values.csv %zu 4\n", specials.size());
        for (std::size_t i = 0; i < specials.size(); ++i) {
            std::fprintf(m, "row values.csv %zu", i);
            hex(m, double(i));
            hex(m, specials[i]);
            hex(m, double(static_cast<float>(specials[i])));
            std::fprintf(m, " row%zu\n", i);
        }
    }

    // A checkpoint of the 2-D solver (finite state: the sampler's values replaced) with values.
    {
        auto& ps = sol2.particles();
        auto& smp = ps.template column<sample>();
        auto& v = ps.template column<fields::velocity>();
        for (std::size_t i = 0; i < ps.size(); ++i) {
            smp[i] = 0.1 * double(i) - 1.0;
            v[i] = gimlet::space<2>::vector(double(i), -1.0 / double(i + 1));
        }
        sol2.resume_at(3.25e-6, 42);
        gimlet::io::save_checkpoint(dir / "run.ckpt", sol2, {{"peak_K", 1234.5}, {"ratio", 1.0 / 3.0}});
        const std::size_t n = ps.size();
        std::fprintf(m, "ckpt run.ckpt 2 8 %zu", n);
        hex(m, 3.25e-6);
        std::fprintf(m, " 42\n");
        std::fprintf(m, "value run.ckpt peak_K");
        hex(m, 1234.5);
        std::fprintf(m, "\nvalue run.ckpt ratio");
        hex(m, 1.0 / 3.0);
        std::fprintf(m, "\n");
        auto column = [&](const char* name, int comps, auto value) {
            std::fprintf(m, "column run.ckpt %s %d", name, comps);
            for (std::size_t i = 0; i < n; ++i)
                for (int k = 0; k < comps; ++k) hex(m, value(i, k));
            std::fprintf(m, "\n");
        };
        const auto& x = ps.template column<fields::position>();
        const auto& mass = ps.template column<fields::mass>();
        const auto& body = ps.template column<fields::body>();
        column("position", 2, [&](std::size_t i, int k) { return double(x[i][k]); });
        column("velocity", 2, [&](std::size_t i, int k) { return double(v[i][k]); });
        column("mass", 1, [&](std::size_t i, int) { return double(mass[i]); });
        column("sample", 1, [&](std::size_t i, int) { return double(smp[i]); });
        column("body", 1, [&](std::size_t i, int) { return double(body[i]); });
    }
    std::fclose(m);
    return 0;
}
