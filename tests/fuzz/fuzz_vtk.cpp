// SPDX-License-Identifier: MIT
// libFuzzer harness: the .vtp and .pvd writers fed arbitrary values (any double, NaN, huge and
// tiny; any array name; Float32 or Float64), and the .pvd reader (pvd_writer::resume) on
// arbitrary files. Every input must write or refuse by name. docs/robustness.md, "Fuzzing".
#include "fuzz_common.hpp"

#include <gimlet/io/vtk.hpp>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

namespace {

using S = gimlet::space<2>;
struct value {
    template <class Sp> using type = typename Sp::real;
    static constexpr const char* name = "value";
};
using store = gimlet::particle_store<S, gimlet::field_union_t<gimlet::core_fields<S>, gimlet::field_list<value>>>;
namespace f = gimlet::fields;

// A written file's XML must be what an XML parser accepts (VTK's is expat): UTF-8, and no
// control character but the line ends the writer puts there. Checked up to the appended binary.
void require_well_formed_text(const std::filesystem::path& path) {
    std::ifstream f(path, std::ios::binary);
    std::string text{std::istreambuf_iterator<char>(f), std::istreambuf_iterator<char>()};
    if (const auto end = text.find("<AppendedData"); end != std::string::npos) text.resize(end);
    for (std::size_t i = 0; i < text.size();) {
        const auto c = static_cast<unsigned char>(text[i]);
        if (c < 0x20 && c != '\n') fuzz::finding(path.filename().string() + ": control character in the XML");
        const std::size_t len = c < 0x80 ? 1 : (c >> 5) == 0x6 ? 2 : (c >> 4) == 0xe ? 3 : (c >> 3) == 0x1e ? 4 : 0;
        if (len == 0 || i + len > text.size()) fuzz::finding(path.filename().string() + ": not UTF-8");
        for (std::size_t k = 1; k < len; ++k)
            if ((static_cast<unsigned char>(text[i + k]) >> 6) != 0x2) fuzz::finding(path.filename().string() + ": not UTF-8");
        i += len;
    }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    fuzz::bytes in(data, size);
    const int mode = in.u8() % 3;
    if (mode == 2) {
        // The .pvd reader on arbitrary text.
        const auto path = fuzz::scratch("input.pvd");
        const double time = in.f64();
        {
            std::ofstream out(path, std::ios::binary | std::ios::trunc);
            out << in.rest();
        }
        fuzz::expect_clean([&] { (void)gimlet::io::pvd_writer::resume(path, time); });
        return 0;
    }
    // Up to 64 particles with arbitrary positions, velocities, stresses and values.
    store s;
    const std::size_t n = in.u8() % 65;
    for (std::size_t i = 0; i < n; ++i) {
        s.add();
        s.column<f::position>()[i] = S::vector(in.f64(), in.f64());
        s.column<f::velocity>()[i] = S::vector(in.f64(), in.f64());
        s.column<f::stress>()[i] << in.f64(), in.f64(), in.f64(), in.f64();
        s.column<value>()[i] = in.f64();
        s.column<f::body>()[i] = in.u32();
    }
    using particle = gimlet::io::vtp_writer<store>::particle;
    const auto prec = [&] { return in.u8() & 1 ? gimlet::io::precision::float32 : gimlet::io::precision::float64; };
    fuzz::expect_clean([&] {
        gimlet::io::vtp_writer<store> w(prec());
        w.add(in.text(40), [](const particle& p) { return p.get<value>(); }, prec());
        w.add(in.text(40), [](const particle& p) { return p.get<f::velocity>(); }, prec());
        w.add(in.text(40), [](const particle& p) { return p.get<f::stress>(); }, prec());
        w.add(in.text(40), [](const particle& p) { return p.get<f::body>(); });
        const std::optional<double> time = in.u8() & 1 ? std::optional<double>(in.f64()) : std::nullopt;
        if (mode == 0) {
            w.write(fuzz::scratch("out.vtp"), s, time);
            require_well_formed_text(fuzz::scratch("out.vtp"));
        } else {
            // A series: the snapshot recorded at a fuzzed time under a fuzzed file name.
            gimlet::io::pvd_writer series(fuzz::scratch("series.pvd"));
            w.write(fuzz::scratch("out.vtp"), s, time);
            series.add(in.f64(), fuzz::scratch("dir") / in.text(30));
            require_well_formed_text(fuzz::scratch("series.pvd"));
            (void)gimlet::io::pvd_writer::resume(fuzz::scratch("series.pvd"), in.f64());
        }
    });
    return 0;
}
