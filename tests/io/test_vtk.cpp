// SPDX-License-Identifier: MIT
// VTK XML particle snapshots and the ParaView series: a known particle set is written, read
// back by a parser of the format written here, and compared bit for bit. (VTK's own reader
// reads them in io.independent_readers: tests/io/independent/.)
#include <gimlet/gimlet.hpp>

#include "scratch_dir.hpp"

#include <catch2/catch.hpp>

#include <bit>
#include <charconv>
#include <cstdint>
#include <cstring>
#include <map>
#include <string>
#include <vector>

using Catch::Matchers::Contains;
using S2 = gimlet::space<2>;
using S3 = gimlet::space<3>;
namespace fields = gimlet::fields;

namespace {

// The attributes of every element <tag ...> in `xml`, in order. (Parsed by hand: std::regex
// trips a false -Wmaybe-uninitialized in GCC 12 under the sanitizers.)
std::vector<std::map<std::string, std::string>> elements(const std::string& xml, const std::string& tag) {
    std::vector<std::map<std::string, std::string>> out;
    const std::string open = "<" + tag + " ";
    for (auto at = xml.find(open); at != std::string::npos; at = xml.find(open, at + 1)) {
        const auto end = xml.find('>', at);
        REQUIRE(end != std::string::npos);
        std::map<std::string, std::string> attrs;
        std::size_t i = at + open.size();
        while (true) {
            const auto eq = xml.find("=\"", i);
            if (eq == std::string::npos || eq > end) break;
            const auto close = xml.find('"', eq + 2);
            REQUIRE(close < end);
            const auto name_start = xml.find_last_of(' ', eq) + 1;
            attrs[xml.substr(name_start, eq - name_start)] = xml.substr(eq + 2, close - eq - 2);
            i = close + 1;
        }
        out.push_back(std::move(attrs));
    }
    return out;
}

// The parts of a .vtp file this library writes: the XML header, every DataArray's attributes
// by name, and the appended raw blocks (UInt64 byte count, then the bytes).
struct vtp_file {
    std::string xml;
    std::map<std::string, std::map<std::string, std::string>> arrays;
    std::vector<char> bytes;
    std::size_t data_at = 0;  // first byte after the '_' that starts the appended data
    std::size_t data_end = 0;

    explicit vtp_file(const std::filesystem::path& path) : bytes(io_test::read_bytes(path)) {
        const std::string text(bytes.begin(), bytes.end());
        const std::string start = "<AppendedData encoding=\"raw\">\n   _";
        const auto at = text.find(start);
        REQUIRE(at != std::string::npos);
        xml = text.substr(0, at + start.size() - 1);
        data_at = at + start.size();
        for (auto attrs : elements(xml, "DataArray")) {
            REQUIRE(arrays.count(attrs["Name"]) == 0);
            arrays[attrs["Name"]] = attrs;
        }
        // The blocks must tile the appended data exactly, and the file must close properly.
        for (const auto& [name, attrs] : arrays) {
            if (attrs.at("format") != "appended") continue;
            const std::size_t begin = data_at + std::stoull(attrs.at("offset"));
            data_end = std::max(data_end, begin + 8 + block_size(begin));
        }
        CHECK(text.substr(data_end) == "\n  </AppendedData>\n</VTKFile>\n");
    }

    [[nodiscard]] std::uint64_t block_size(std::size_t begin) const {
        std::uint64_t n = 0;
        REQUIRE(begin + 8 <= bytes.size());
        std::memcpy(&n, bytes.data() + begin, 8);
        return n;
    }

    template <class T>
    [[nodiscard]] std::vector<T> values(const std::string& name) const {
        const auto& attrs = arrays.at(name);
        const std::size_t begin = data_at + std::stoull(attrs.at("offset"));
        const std::uint64_t n = block_size(begin);
        REQUIRE(n % sizeof(T) == 0);
        REQUIRE(begin + 8 + n <= bytes.size());
        std::vector<T> out(n / sizeof(T));
        if (n) std::memcpy(out.data(), bytes.data() + begin + 8, n);
        return out;
    }

    [[nodiscard]] std::string header_attribute(const std::string& element, const std::string& name) const {
        const auto found = elements(xml, element);
        REQUIRE(found.size() == 1);
        REQUIRE(found[0].count(name) == 1);
        return found[0].at(name);
    }
};

template <class T>
bool same_bits(T a, T b) {
    return std::memcmp(&a, &b, sizeof(T)) == 0;
}

template <class T>
bool same_bits(const std::vector<T>& a, const std::vector<T>& b) {
    return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0);
}

using store2 = gimlet::particle_store<S2, gimlet::core_fields<S2>>;
using store3 = gimlet::particle_store<S3, gimlet::core_fields<S3>>;

// Values with full 53-bit mantissas (thirds, sevenths), signs, and one subnormal, so a lossy
// or reordered write cannot pass.
template <class Store>
Store known_particles(std::size_t n) {
    using S = typename Store::space_type;
    Store s;
    for (std::size_t i = 0; i < n; ++i) {
        auto p = s[s.add()];
        const double k = double(i);
        for (int d = 0; d < S::dim; ++d) {
            p.template get<fields::position>()[d] = (k + 1) / 3.0 - d / 7.0;
            p.template get<fields::velocity>()[d] = -(k + 2) * (d + 1) / 11.0;
            for (int e = 0; e < S::dim; ++e) p.template get<fields::stress>()(d, e) = 1e9 * (k - 1.5) / (3 + d + 5 * e);
        }
        p.template get<fields::mass>() = i == 2 ? 4.9e-320 : 1e-3 * (k + 1) / 7.0;
        p.template get<fields::body>() = static_cast<std::uint32_t>(i % 2 + 5 * (i / 3));
        if constexpr (S::dim == 2) p.template get<fields::stress_zz>() = -2e8 * k / 3.0;
    }
    return s;
}

}  // namespace

TEST_CASE("vtp: a 2-D particle set reads back bit for bit, vectors padded to 3 components", "[io][vtk]") {
    io_test::scratch_dir dir("vtp2d");
    const auto particles = known_particles<store2>(5);
    gimlet::io::vtp_writer<store2> vtp;
    vtp.add("pressure", [](const auto& p) { return gimlet::mean_pressure(p); })
        .add_field<fields::velocity>()
        .add_field<fields::body>()
        .add_field<fields::stress>()
        .add("mass32", [](const auto& p) { return p.template get<fields::mass>(); }, gimlet::io::precision::float32)
        .add("twice velocity", [](const auto& p) { return 2.0 * p.template get<fields::velocity>(); });
    CHECK(vtp.array_names() ==
          std::vector<std::string>{"pressure", "velocity", "body", "stress", "mass32", "twice velocity"});
    vtp.write(dir / "p.vtp", particles, 1.25e-6);
    const vtp_file f(dir / "p.vtp");

    CHECK(f.xml.rfind("<?xml version=\"1.0\"?>\n<VTKFile type=\"PolyData\"", 0) == 0);
    CHECK(f.header_attribute("VTKFile", "byte_order") == "LittleEndian");  // the test hosts are little-endian
    CHECK(f.header_attribute("VTKFile", "header_type") == "UInt64");
    CHECK(f.header_attribute("Piece", "NumberOfPoints") == "5");
    CHECK(f.header_attribute("Piece", "NumberOfVerts") == "5");
    CHECK(f.header_attribute("Piece", "NumberOfPolys") == "0");
    CHECK_THAT(f.xml, Contains("Name=\"TimeValue\" NumberOfTuples=\"1\" format=\"ascii\">1.25e-06</DataArray>"));
    const std::map<std::string, std::pair<std::string, std::string>> expected{
        {"pressure", {"Float64", "1"}}, {"velocity", {"Float64", "3"}}, {"body", {"Int32", "1"}},
        {"stress", {"Float64", "9"}},   {"mass32", {"Float32", "1"}},   {"twice velocity", {"Float64", "3"}},
        {"Points", {"Float64", "3"}}};
    for (const auto& [name, tc] : expected) {
        INFO(name);
        REQUIRE(f.arrays.count(name) == 1);
        CHECK(f.arrays.at(name).at("type") == tc.first);
        CHECK(f.arrays.at(name).at("NumberOfComponents") == tc.second);
    }

    std::vector<double> pressure, velocity, stress, twice, points;
    std::vector<std::int32_t> body, connectivity, offsets;
    std::vector<float> mass32;
    for (std::size_t i = 0; i < particles.size(); ++i) {
        const auto p = particles[i];
        pressure.push_back(gimlet::mean_pressure(p));
        const auto& v = p.get<fields::velocity>();
        const auto& x = p.get<fields::position>();
        const auto& sig = p.get<fields::stress>();
        velocity.insert(velocity.end(), {v[0], v[1], 0.0});
        twice.insert(twice.end(), {2.0 * v[0], 2.0 * v[1], 0.0});
        points.insert(points.end(), {x[0], x[1], 0.0});
        stress.insert(stress.end(), {sig(0, 0), sig(0, 1), 0.0, sig(1, 0), sig(1, 1), 0.0, 0.0, 0.0, 0.0});
        body.push_back(std::int32_t(p.get<fields::body>()));
        mass32.push_back(float(p.get<fields::mass>()));
        connectivity.push_back(std::int32_t(i));
        offsets.push_back(std::int32_t(i + 1));
    }
    CHECK(same_bits(f.values<double>("pressure"), pressure));
    CHECK(same_bits(f.values<double>("velocity"), velocity));
    CHECK(same_bits(f.values<double>("twice velocity"), twice));
    CHECK(same_bits(f.values<double>("stress"), stress));
    CHECK(same_bits(f.values<double>("Points"), points));
    CHECK(same_bits(f.values<std::int32_t>("body"), body));
    CHECK(same_bits(f.values<float>("mass32"), mass32));
    CHECK(same_bits(f.values<std::int32_t>("connectivity"), connectivity));
    CHECK(same_bits(f.values<std::int32_t>("offsets"), offsets));
    CHECK(f.values<float>("mass32")[2] == 0.0f);  // the subnormal double underflows in float32
}

TEST_CASE("vtp: 3-D vectors and tensors as they are, float32 points, no particles", "[io][vtk]") {
    io_test::scratch_dir dir("vtp3d");
    const auto particles = known_particles<store3>(4);
    gimlet::io::vtp_writer<store3> vtp(gimlet::io::precision::float32);
    vtp.add_field<fields::velocity>().add_field<fields::stress>().add_field<fields::mass>();
    vtp.write(dir / "p.vtp", particles);
    const vtp_file f(dir / "p.vtp");
    CHECK(f.header_attribute("Piece", "NumberOfPoints") == "4");
    CHECK(f.xml.find("TimeValue") == std::string::npos);
    CHECK(f.arrays.at("Points").at("type") == "Float32");
    std::vector<double> velocity, stress, mass;
    std::vector<float> points;
    for (std::size_t i = 0; i < particles.size(); ++i) {
        const auto p = particles[i];
        for (int d = 0; d < 3; ++d) {
            velocity.push_back(p.get<fields::velocity>()[d]);
            points.push_back(float(p.get<fields::position>()[d]));
            for (int e = 0; e < 3; ++e) stress.push_back(p.get<fields::stress>()(d, e));  // row-major
        }
        mass.push_back(p.get<fields::mass>());
    }
    CHECK(same_bits(f.values<double>("velocity"), velocity));
    CHECK(same_bits(f.values<double>("stress"), stress));
    CHECK(same_bits(f.values<double>("mass"), mass));
    CHECK(same_bits(f.values<float>("Points"), points));

    vtp.write(dir / "empty.vtp", store3{});
    const vtp_file empty(dir / "empty.vtp");
    CHECK(empty.header_attribute("Piece", "NumberOfPoints") == "0");
    CHECK(empty.values<double>("velocity").empty());
}

TEST_CASE("vtp: bad array names and values are refused by name", "[io][vtk][errors]") {
    io_test::scratch_dir dir("vtpnames");
    gimlet::io::vtp_writer<store2> vtp;
    auto mass = [](const auto& p) { return p.template get<fields::mass>(); };
    CHECK_THROWS_AS(vtp.add("", mass), gimlet::invalid_parameter);
    vtp.add("m", mass);
    CHECK_THROWS_WITH(vtp.add("m", mass), Contains("VTK array name") && Contains("'m'") && Contains("not used"));
    vtp.add("huge id", [](const auto&) { return std::uint32_t(3'000'000'000u); });
    CHECK_THROWS_WITH(vtp.write(dir / "p.vtp", known_particles<store2>(2)),
                      Contains("huge id") && Contains("3000000000") && Contains("32-bit signed integer"));
    CHECK(std::filesystem::is_empty(dir.path()));  // neither the file nor its temporary
    // Names are escaped in the XML.
    gimlet::io::vtp_writer<store2> quoted;
    quoted.add("a<\"b\">&c", mass);
    quoted.write(dir / "q.vtp", known_particles<store2>(1));
    CHECK_THAT(vtp_file(dir / "q.vtp").xml, Contains("Name=\"a&lt;&quot;b&quot;&gt;&amp;c\""));
    // What XML cannot hold even escaped is refused (VTK's reader refuses the whole file);
    // UTF-8 text is kept as it is.
    CHECK_THROWS_WITH(quoted.add(std::string("tab\there"), mass), Contains("VTK array name") && Contains("0x09"));
    CHECK_THROWS_WITH(quoted.add(std::string("bell\x07"), mass), Contains("control character"));
    CHECK_THROWS_WITH(quoted.add(std::string("latin1 \xe9t\xe9"), mass), Contains("not UTF-8"));
    CHECK_THROWS_WITH(quoted.add(std::string("overlong \xc0\xaf"), mass), Contains("not UTF-8"));
    CHECK_THROWS_WITH(quoted.add(std::string("surrogate \xed\xa0\x80"), mass), Contains("not UTF-8"));
    quoted.add("\xcf\x83_yy (Pa)", mass);  // sigma_yy in UTF-8
    quoted.write(dir / "u.vtp", known_particles<store2>(1));
    CHECK_THAT(vtp_file(dir / "u.vtp").xml, Contains("Name=\"\xcf\x83_yy (Pa)\""));
    gimlet::io::pvd_writer series(dir / "s.pvd");
    CHECK_THROWS_WITH(series.add(0.0, dir / "bad\nname.vtp"), Contains("ParaView snapshot file name") &&
                                                                   Contains("control character"));
    CHECK(series.entries().empty());
}

TEST_CASE("vtp and pvd: an output path that cannot be written is refused, naming it", "[io][vtk][errors]") {
    io_test::scratch_dir dir("vtpunwritable");
    gimlet::io::vtp_writer<store2> vtp;
    vtp.add_field<fields::mass>();
    const auto particles = known_particles<store2>(3);
    const auto missing = dir / "no such directory" / "p.vtp";
    CHECK_THROWS_AS(vtp.write(missing, particles), gimlet::invalid_parameter);
    CHECK_THROWS_WITH(vtp.write(missing, particles),
                      Contains("VTK output file (.vtp)") && Contains(missing.string()) && Contains("writable file"));
    // A directory in the way: the data is written, then the final rename fails; nothing is left.
    std::filesystem::create_directory(dir / "taken.vtp");
    CHECK_THROWS_WITH(vtp.write(dir / "taken.vtp", particles), Contains("taken.vtp") && Contains("writable file"));
    CHECK(!std::filesystem::exists(gimlet::io::detail::temporary_for(dir / "taken.vtp")));
    CHECK_THROWS_WITH(gimlet::io::pvd_writer(dir / "no such directory" / "s.pvd"),
                      Contains("ParaView series file (.pvd)") && Contains("s.pvd") && Contains("writable file"));
    CHECK_THROWS_WITH(gimlet::io::pvd_writer::resume(dir / "absent.pvd", 1.0),
                      Contains("absent.pvd") && Contains("existing, readable .pvd"));
}

namespace {

using elastic_solver = gimlet::solver<S2, gimlet::shape::ugimp, gimlet::elastic_material>;

elastic_solver small_solver() {
    gimlet::grid_spec<S2> gs;
    gs.upper = S2::vector(1.0, 1.0);
    gs.cell = 0.1;
    gs.bc = {gimlet::boundary::periodic, gimlet::boundary::periodic};
    gimlet::scene::scene<S2, gimlet::elastic_material> sc(gs);
    sc.add_body(gimlet::scene::ball<S2>(S2::vector(0.5, 0.5), 0.2), gimlet::make_elastic_material(1000.0, 1e6, 0.3),
                S2::vector(0.3, -0.1));
    return elastic_solver(sc);
}

// The (timestep, file) entries of a .pvd, timesteps read exactly.
std::vector<std::pair<double, std::string>> pvd_entries(const std::filesystem::path& path) {
    const auto bytes = io_test::read_bytes(path);
    const std::string text(bytes.begin(), bytes.end());
    CHECK(text.rfind("<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\">\n  <Collection>\n", 0) == 0);
    CHECK(text.ends_with("  </Collection>\n</VTKFile>\n"));
    std::vector<std::pair<double, std::string>> out;
    for (auto attrs : elements(text, "DataSet")) {
        CHECK(attrs.size() == 4);
        CHECK(attrs["group"].empty());
        CHECK(attrs["part"] == "0");
        const std::string& t = attrs["timestep"];
        double v = 0;
        const auto r = std::from_chars(t.data(), t.data() + t.size(), v);
        CHECK(r.ptr == t.data() + t.size());
        out.emplace_back(v, attrs["file"]);
    }
    return out;
}

}  // namespace

TEST_CASE("pvd: the series lists every snapshot at its exact time, relative names, valid after each", "[io][vtk]") {
    io_test::scratch_dir dir("pvd");
    auto sol = small_solver();
    gimlet::io::vtp_writer_for<elastic_solver> vtp;
    vtp.add_field<fields::velocity>().add_field<fields::body>();
    gimlet::io::pvd_writer series(dir / "particles.pvd");
    CHECK(pvd_entries(dir / "particles.pvd").empty());  // valid before the first snapshot

    std::vector<double> times;
    for (int k = 0; k < 3; ++k) {
        if (k) sol.step(), sol.step();
        times.push_back(sol.time());
        const auto file = series.write(vtp, sol);
        char name[32];
        std::snprintf(name, sizeof name, "particles_%06d.vtp", k);
        CHECK(file == dir / name);
        const auto listed = pvd_entries(dir / "particles.pvd");
        REQUIRE(listed.size() == std::size_t(k + 1));  // rewritten after every snapshot
        CHECK(same_bits(listed.back().first, times.back()));
        CHECK(listed.back().second == name);
        // The snapshot carries the same time.
        const vtp_file f(file);
        // Built piecewise: GCC 12 warns a false -Wrestrict on "literal" + string + "literal".
        std::string value = ">";
        value += gimlet::io::detail::exact_text(times.back());
        value += "</DataArray>";
        CHECK_THAT(f.xml, Contains(value));
        CHECK(f.header_attribute("Piece", "NumberOfPoints") == std::to_string(sol.particles().size()));
    }
    CHECK(!std::filesystem::exists(gimlet::io::detail::temporary_for(dir / "particles.pvd")));

    // A file elsewhere is stored relative to the .pvd's directory.
    std::filesystem::create_directory(dir / "sub");
    vtp.write(dir / "sub" / "extra.vtp", sol);
    series.add(9.5, dir / "sub" / "extra.vtp");
    CHECK(pvd_entries(dir / "particles.pvd").back().second == "sub/extra.vtp");

    // A resumed run keeps the entries up to its checkpoint time and numbers on from there.
    auto resumed = gimlet::io::pvd_writer::resume(dir / "particles.pvd", times[1]);
    REQUIRE(resumed.entries().size() == 2);
    CHECK(pvd_entries(dir / "particles.pvd").size() == 2);
    CHECK(resumed.write(vtp, sol) == dir / "particles_000002.vtp");
    const auto listed = pvd_entries(dir / "particles.pvd");
    REQUIRE(listed.size() == 3);
    CHECK(same_bits(listed[0].first, times[0]));
    CHECK(same_bits(listed[1].first, times[1]));
    CHECK(listed[2].second == "particles_000002.vtp");
}

TEST_CASE("vtp pieces: on one process one piece with the ordinals, and a .pvtp that names it with every array's type",
          "[io][vtk]") {
    io_test::scratch_dir dir("pvtp");
    auto sol = small_solver();
    sol.step();
    gimlet::io::vtp_writer_for<elastic_solver> vtp(gimlet::io::precision::float32);
    vtp.add_field<fields::velocity>().add_field<fields::body>().add(
        "speed", [](const auto& p) { return p.template get<fields::velocity>().norm(); }, gimlet::io::precision::float32);
    vtp.write_pieces(dir / "snap.pvtp", sol);
    vtp.write(dir / "whole.vtp", sol);
    CHECK(gimlet::io::vtp_writer_for<elastic_solver>::piece_path(dir / "snap.pvtp", 0) == dir / "snap_0.vtp");
    // The piece holds write()'s arrays bit for bit, then the ordinals 0 .. n - 1 (the GlobalIds).
    const vtp_file piece(dir / "snap_0.vtp"), whole(dir / "whole.vtp");
    for (const char* name : {"velocity", "body", "speed", "Points", "connectivity", "offsets"}) {
        INFO(name);
        CHECK(piece.arrays.at(name).at("type") == whole.arrays.at(name).at("type"));
        CHECK(same_bits(piece.values<char>(name), whole.values<char>(name)));
    }
    CHECK(piece.arrays.at("ordinal").at("type") == "Int64");
    const auto ordinals = piece.values<std::int64_t>("ordinal");
    REQUIRE(ordinals.size() == sol.particles().size());
    for (std::size_t i = 0; i < ordinals.size(); ++i) CHECK(ordinals[i] == std::int64_t(i));
    CHECK(piece.header_attribute("PointData", "GlobalIds") == "ordinal");
    const auto bytes = io_test::read_bytes(dir / "snap.pvtp");
    const std::string xml(bytes.begin(), bytes.end());
    CHECK_THAT(xml, Contains("<VTKFile type=\"PPolyData\" version=\"1.0\""));
    CHECK_THAT(xml, Contains("<PPointData GlobalIds=\"ordinal\">"));
    CHECK(xml.ends_with("  </PPolyData>\n</VTKFile>\n"));
    const auto pieces = elements(xml, "Piece");
    REQUIRE(pieces.size() == 1);
    CHECK(pieces[0].at("Source") == "snap_0.vtp");
    // Every point array and the points, with the piece's type and components, in its order.
    const auto declared = elements(xml, "PDataArray");
    std::vector<std::string> names;
    for (const auto& a : declared) {
        names.push_back(a.at("Name"));
        CHECK(a.at("type") == piece.arrays.at(a.at("Name")).at("type"));
        CHECK(a.at("NumberOfComponents") == piece.arrays.at(a.at("Name")).at("NumberOfComponents"));
    }
    CHECK(names == std::vector<std::string>{"velocity", "body", "speed", "ordinal", "Points"});
    // The summary's name must end in .pvtp (ParaView picks its reader by it); "ordinal" is taken.
    CHECK_THROWS_WITH(vtp.write_pieces(dir / "snap.vtp", sol), Contains("snap.vtp") && Contains("ending in .pvtp"));
    CHECK(!std::filesystem::exists(dir / "snap.vtp"));
    vtp.add("ordinal", [](const auto&) { return 0; });
    CHECK_THROWS_WITH(vtp.write_pieces(dir / "again.pvtp", sol), Contains("ordinal") && Contains("VTK array name"));
    CHECK(!std::filesystem::exists(dir / "again_0.vtp"));
}
