// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// Particle snapshots for ParaView: VTK XML PolyData (.vtp), one vertex per particle, with the
/// point-data arrays the caller chooses. The .pvd series that lists them is io/pvd.hpp
/// (included here). Format and usage: docs/io.md.
///
/// \code
/// gimlet::io::vtp_writer_for<decltype(sol)> vtp;
/// vtp.add("pressure", [](const auto& p) { return gimlet::mean_pressure(p); })
///    .add_field<gimlet::fields::velocity>()
///    .add_field<gimlet::fields::body>();                       // Int32
/// gimlet::io::pvd_writer series(out / "particles.pvd");
/// series.write(vtp, sol);                                        // particles_000000.vtp + .pvd
/// \endcode

#include "gimlet/core/error.hpp"
#include "gimlet/core/fields.hpp"
#include "gimlet/core/processes.hpp"
#include "gimlet/core/particle_store.hpp"
#include "gimlet/io/detail/file.hpp"
#include "gimlet/io/detail/text.hpp"
#include "gimlet/io/pvd.hpp"

#include <bit>
#include <cmath>
#include <concepts>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <functional>
#include <limits>
#include <optional>
#include <ostream>
#include <sstream>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

/// Output and restart: ParaView .vtp snapshots and .pvd series, CSV tables, checkpoints.
namespace gimlet::io {

/// Floating-point type of an array in the file. float32 halves the file; positions and
/// values then keep about 7 significant digits.
enum class precision { float32, float64 };

namespace detail {

template <class T>
concept eigen_dense = requires {
    T::RowsAtCompileTime;
    T::ColsAtCompileTime;
    typename T::Scalar;
    typename T::PlainObject;
};

// An Eigen expression (2 * v), as opposed to a plain matrix type: evaluated before storing.
template <class T>
constexpr bool is_eigen_expression() {
    if constexpr (eigen_dense<T>) return !std::is_same_v<T, typename T::PlainObject>;
    else return false;
}

// How many components an array of values of type T has in the file: 1 for a scalar, 3 for a
// vector (2-D padded with z = 0, so ParaView sees a vector), 9 for a square tensor (2x2 padded
// to 3x3, row-major as ParaView labels them XX, XY, XZ, YX, ...). 0: not writable.
template <class T>
constexpr int vtk_components() {
    if constexpr (std::is_arithmetic_v<T>) {
        return 1;
    } else if constexpr (eigen_dense<T>) {
        constexpr int r = T::RowsAtCompileTime, c = T::ColsAtCompileTime;
        if constexpr (c == 1 && (r == 2 || r == 3)) return 3;
        else if constexpr (r == c && (r == 2 || r == 3)) return 9;
        else return 0;
    } else {
        return 0;
    }
}

// Component k of value v, padded as vtk_components describes.
template <class T>
double vtk_component(const T& v, int k) {
    if constexpr (std::is_arithmetic_v<T>) {
        return (void)k, double(v);
    } else if constexpr (T::ColsAtCompileTime == 1) {
        return k < T::RowsAtCompileTime ? double(v[k]) : 0.0;
    } else {
        const int i = k / 3, j = k % 3;
        return i < T::RowsAtCompileTime && j < T::ColsAtCompileTime ? double(v(i, j)) : 0.0;
    }
}

// Append `x` to a byte buffer as the file type Out.
template <class Out>
void put(std::vector<char>& bytes, std::size_t& at, Out x) {
    std::memcpy(bytes.data() + at, &x, sizeof(Out));
    at += sizeof(Out);
}

}  // namespace detail

/// Writes particle snapshots as VTK XML PolyData (.vtp) for ParaView.
///
/// Encoding: appended raw binary (`<AppendedData encoding="raw">`, each block preceded by its
/// byte count as UInt64). It is the most compact form ParaView reads without a compression
/// library: no base64 (a third larger, and time to encode) and no text (three times larger and
/// lossy unless printed with 17 digits). Values are written in the host's byte order, which the
/// file's `byte_order` attribute records, so the files are correct on any host.
///
/// \tparam Store the particle store (`solver::store_type`; see vtp_writer_for).
template <class Store>
class vtp_writer {
public:
    /// The particle store, Store.
    using store_type = Store;
    /// The store's space.
    using space_type = typename Store::space_type;
    /// What the functions of add() receive: a read-only handle (`p.get<fields::mass>()`).
    using particle = particle_ref<const Store>;

    /// \param points precision of the particle positions.
    explicit vtp_writer(precision points = precision::float64) : points_(points) {}

    /// Add a point-data array `name` whose value at a particle is `f(p)`. By what `f` returns:
    /// a floating-point scalar gives a scalar array, an integer (e.g. a body id) an Int32 array,
    /// an `S::vector` a 3-component vector (z = 0 in 2-D), an `S::matrix` or 3x3 tensor a
    /// 9-component tensor. `prec` applies to floating-point arrays.
    /// Throws invalid_parameter for an empty or repeated name, or one XML cannot hold (control
    /// characters, bytes that are not UTF-8).
    template <class F>
        requires std::is_invocable_v<const F&, const particle&>
    vtp_writer& add(std::string name, F f, precision prec = precision::float64) {
        using R = std::remove_cvref_t<std::invoke_result_t<const F&, const particle&>>;
        if constexpr (detail::is_eigen_expression<R>()) {
            // Evaluate an Eigen expression into its plain type so nothing dangles.
            return add(std::move(name), [f = std::move(f)](const particle& p) {
                return typename R::PlainObject(f(p));
            }, prec);
        } else {
            constexpr int comps = detail::vtk_components<R>();
            static_assert(comps > 0,
                          "vtp_writer::add: the function must return a scalar, an integer, an S::vector or a "
                          "square S::matrix / 3x3 tensor");
            check_name(name);
            if constexpr (std::is_integral_v<R>) push<std::int32_t>(std::move(name), "Int32", comps, std::move(f));
            else if (prec == precision::float32) push<float>(std::move(name), "Float32", comps, std::move(f));
            else push<double>(std::move(name), "Float64", comps, std::move(f));
            return *this;
        }
    }

    /// Add the particle field `Tag` as an array named `Tag::name`.
    template <Field Tag>
        requires(Store::template has<Tag>)
    vtp_writer& add_field(precision prec = precision::float64) {
        return add(Tag::name, [](const particle& p) { return p.template get<Tag>(); }, prec);
    }

    /// Write the particles to `path`. `time` (s), if given, is stored as the field-data array
    /// TimeValue, which ParaView shows as the snapshot's time.
    /// Throws invalid_parameter if `path` cannot be written; the file is then left untouched.
    void write(const std::filesystem::path& path, const Store& particles,
               std::optional<double> time = std::nullopt) const {
        gimlet::io::detail::write_atomically(path, "VTK output file (.vtp)", [&](std::ostream& out) {
            write_to(out, particles, time);
        });
    }

    /// Write a solver's particles, with its time. On many processes (solver_options::processes)
    /// it is collective: the particles are gathered in ordinal order and the first process
    /// writes the file one process would write.
    template <class Solver>
        requires requires(const Solver& s) {
            { s.particles() } -> std::same_as<const Store&>;
            s.time();
        }
    void write(const std::filesystem::path& path, const Solver& solver) const {
        if (gimlet::processes* p = gimlet::detail::processes_of(solver)) {
            const auto whole = solver.gathered_particles();
            p->together([&] {
                if (p->rank() == 0) write(path, whole, double(solver.time()));
            });
            return;
        }
        write(path, solver.particles(), double(solver.time()));
    }

    /// Write a solver's particles as pieces, one a process, and a `.pvtp` at `path` that names
    /// them, which ParaView opens as one dataset: each process writes its own particles to
    /// `<stem>_<rank>.vtp` beside `path` (`<stem>` the name of `path` without its extension),
    /// then the first process writes `path`. Nothing is gathered, so no process holds more than
    /// its own particles. Each piece holds the arrays added, and one more, `ordinal`
    /// (ordinal_array; Int64, the pieces' GlobalIds): each particle's number in the whole run
    /// (`solver.ordinal(i)`, its index in one process's store), so that the pieces' particles
    /// can be put in one process's order. A sort (solver_options::sort_interval) renumbers
    /// them: across snapshots an ordinal names one particle only where the run does not sort. On many processes (solver_options::processes) it is
    /// collective and a failure to write on any process throws on all; on one process it writes
    /// the one piece `<stem>_0.vtp` and the `.pvtp`. Throws invalid_parameter for a `path` that
    /// does not end in `.pvtp` or cannot be written, or where an array added is named `ordinal`.
    template <class Solver>
        requires requires(const Solver& s, std::size_t i) {
            { s.particles() } -> std::same_as<const Store&>;
            s.time();
            { s.ordinal(i) } -> std::convertible_to<std::uint64_t>;
        }
    void write_pieces(const std::filesystem::path& path, const Solver& solver) const {
        if (path.extension() != ".pvtp")
            throw invalid_parameter("VTK pieces' summary file", detail::quoted(path.string()),
                                    "a path ending in .pvtp (ParaView chooses its reader by the extension)");
        for (const auto& a : arrays_)
            if (a.name == ordinal_array)
                throw invalid_parameter("VTK array name", detail::quoted(a.name),
                                        "a name other than 'ordinal', which write_pieces gives the particles' ordinals");
        gimlet::processes* p = gimlet::detail::processes_of(solver);
        const int rank = p ? p->rank() : 0, size = p ? p->size() : 1;
        // The pieces' names go into the summary's XML (the same check on every process).
        const std::string piece_name = piece_path(path, size - 1).filename().string();
        if (const auto why = gimlet::io::detail::xml_attribute_problem(piece_name); !why.empty())
            throw invalid_parameter("VTK pieces' summary file", detail::quoted(path.string()),
                                    "a name of UTF-8 text without control characters (it holds " + why + ")");
        const auto mine = [&] {
            const auto& particles = solver.particles();
            std::vector<std::int64_t> ordinals(particles.size());
            for (std::size_t i = 0; i < ordinals.size(); ++i) ordinals[i] = std::int64_t(solver.ordinal(i));
            gimlet::io::detail::write_atomically(piece_path(path, rank), "VTK output file (.vtp)", [&](std::ostream& out) {
                write_to(out, particles, double(solver.time()), &ordinals);
            });
        };
        const auto summary = [&] {
            if (rank != 0) return;
            gimlet::io::detail::write_atomically(path, "VTK pieces' summary file (.pvtp)", [&](std::ostream& out) {
                write_summary(out, path, size);
            });
        };
        if (p) {
            p->together(mine);
            p->together(summary);
        } else {
            mine();
            summary();
        }
    }

    /// The name of the array of the particles' ordinals in pieces (write_pieces).
    static constexpr const char* ordinal_array = "ordinal";

    /// The file of piece `rank` of the `.pvtp` at `path` (write_pieces): `<stem>_<rank>.vtp`
    /// beside it.
    [[nodiscard]] static std::filesystem::path piece_path(const std::filesystem::path& path, int rank) {
        std::filesystem::path piece = path;
        piece.replace_filename(path.stem().string() + "_" + std::to_string(rank) + ".vtp");
        return piece;
    }

    /// Names of the arrays added so far, in file order.
    [[nodiscard]] std::vector<std::string> array_names() const {
        std::vector<std::string> names;
        for (const auto& a : arrays_) names.push_back(a.name);
        return names;
    }

private:
    struct array {
        std::string name;
        const char* type;
        int components;
        std::size_t bytes_per_component;
        std::function<void(const Store&, std::vector<char>&)> fill;
    };

    void check_name(const std::string& name) const {
        if (name.empty()) throw invalid_parameter("VTK array name", "''", "a non-empty name");
        if (const auto why = gimlet::io::detail::xml_attribute_problem(name); !why.empty())
            throw invalid_parameter("VTK array name", detail::quoted(name),
                                    "UTF-8 text without control characters (it holds " + why + ")");
        for (const auto& a : arrays_)
            if (a.name == name)
                throw invalid_parameter("VTK array name", detail::quoted(name), "a name not used by another array");
    }

    template <class Out, class F>
    void push(std::string name, const char* type, int comps, F f) {
        auto fn = fill<Out>(std::move(f), name);  // before the move: it keeps the name for its messages
        arrays_.push_back({std::move(name), type, comps, sizeof(Out), std::move(fn)});
    }

    // One type-erased call per array and snapshot (not per particle): the loop over particles
    // is compiled for the caller's function.
    template <class Out, class F>
    static std::function<void(const Store&, std::vector<char>&)> fill(F f, const std::string& name) {
        using R = std::remove_cvref_t<std::invoke_result_t<const F&, const particle&>>;
        constexpr int comps = detail::vtk_components<R>();
        return [f = std::move(f), name](const Store& s, std::vector<char>& bytes) {
            bytes.resize(s.size() * comps * sizeof(Out));
            std::size_t at = 0;
            for (std::size_t i = 0; i < s.size(); ++i) {
                const R v = f(s[i]);
                if constexpr (std::is_integral_v<R>) {
                    if constexpr (!std::is_same_v<R, bool>)
                        if (!std::in_range<std::int32_t>(v))
                            throw invalid_parameter("value of VTK array '" + name + "' at particle " + std::to_string(i),
                                                    gimlet::detail::to_text(v), "a 32-bit signed integer");
                    detail::put(bytes, at, static_cast<std::int32_t>(v));
                } else {
                    for (int k = 0; k < comps; ++k) detail::put(bytes, at, static_cast<Out>(detail::vtk_component(v, k)));
                }
            }
        };
    }

    // `ordinals`, if given: one more point array, ordinal_array (Int64), the GlobalIds.
    void write_to(std::ostream& out, const Store& s, std::optional<double> time,
                  const std::vector<std::int64_t>* ordinals = nullptr) const {
        const std::size_t n = s.size();
        // Int32 vertex indices while they fit: a third of the size of the points array.
        const bool wide = n > std::size_t(std::numeric_limits<std::int32_t>::max());
        const char* index_type = wide ? "Int64" : "Int32";
        const std::size_t index_bytes = wide ? 8 : 4;
        const bool points64 = points_ == precision::float64;

        // Offsets of the appended blocks, each a UInt64 byte count then the bytes.
        std::uint64_t offset = 0;
        auto block = [&](std::size_t bytes) {
            const std::uint64_t at = offset;
            offset += sizeof(std::uint64_t) + bytes;
            return std::to_string(at);
        };
        std::ostringstream xml;
        xml << "<?xml version=\"1.0\"?>\n"
            << "<VTKFile type=\"PolyData\" version=\"1.0\" byte_order=\""
            << (std::endian::native == std::endian::little ? "LittleEndian" : "BigEndian")
            << "\" header_type=\"UInt64\">\n  <PolyData>\n";
        if (time)
            xml << "    <FieldData>\n      <DataArray type=\"Float64\" Name=\"TimeValue\" NumberOfTuples=\"1\" "
                   "format=\"ascii\">"
                << gimlet::io::detail::exact_text(*time) << "</DataArray>\n    </FieldData>\n";
        xml << "    <Piece NumberOfPoints=\"" << n << "\" NumberOfVerts=\"" << n
            << "\" NumberOfLines=\"0\" NumberOfStrips=\"0\" NumberOfPolys=\"0\">\n      <PointData"
            << (ordinals ? std::string(" GlobalIds=\"") + ordinal_array + "\"" : std::string()) << ">\n";
        for (const auto& a : arrays_)
            xml << "        <DataArray type=\"" << a.type << "\" Name=\"" << gimlet::io::detail::xml_escape(a.name)
                << "\" NumberOfComponents=\"" << a.components << "\" format=\"appended\" offset=\""
                << block(n * std::size_t(a.components) * a.bytes_per_component) << "\"/>\n";
        if (ordinals)
            xml << "        <DataArray type=\"Int64\" IdType=\"1\" Name=\"" << ordinal_array
                << "\" NumberOfComponents=\"1\" format=\"appended\" offset=\"" << block(n * 8) << "\"/>\n";
        xml << "      </PointData>\n      <Points>\n        <DataArray type=\"" << (points64 ? "Float64" : "Float32")
            << "\" Name=\"Points\" NumberOfComponents=\"3\" format=\"appended\" offset=\""
            << block(n * 3 * (points64 ? 8 : 4)) << "\"/>\n      </Points>\n      <Verts>\n";
        xml << "        <DataArray type=\"" << index_type << "\" Name=\"connectivity\" format=\"appended\" offset=\""
            << block(n * index_bytes) << "\"/>\n";
        xml << "        <DataArray type=\"" << index_type << "\" Name=\"offsets\" format=\"appended\" offset=\""
            << block(n * index_bytes) << "\"/>\n";
        xml << "      </Verts>\n    </Piece>\n  </PolyData>\n  <AppendedData encoding=\"raw\">\n   _";
        out << xml.str();

        std::vector<char> bytes;
        auto emit = [&] {
            const std::uint64_t size = bytes.size();
            gimlet::io::detail::write_raw(out, &size, 1);
            gimlet::io::detail::write_raw(out, bytes.data(), bytes.size());
        };
        for (const auto& a : arrays_) {
            a.fill(s, bytes);
            emit();
        }
        if (ordinals) {
            bytes.resize(n * 8);
            if (n) std::memcpy(bytes.data(), ordinals->data(), n * 8);
            emit();
        }
        const auto& x = s.template column<fields::position>();
        if (points64) fill_points<double>(x, bytes);
        else fill_points<float>(x, bytes);
        emit();
        if (wide) fill_indices<std::int64_t>(n, 0, bytes);
        else fill_indices<std::int32_t>(n, 0, bytes);
        emit();
        if (wide) fill_indices<std::int64_t>(n, 1, bytes);
        else fill_indices<std::int32_t>(n, 1, bytes);
        emit();
        out << "\n  </AppendedData>\n</VTKFile>\n";
    }

    // The .pvtp of write_pieces: the arrays' types and names (those of every piece, the
    // ordinals last) and the pieces' files, relative to its directory.
    void write_summary(std::ostream& out, const std::filesystem::path& path, int pieces) const {
        std::ostringstream xml;
        xml << "<?xml version=\"1.0\"?>\n"
            << "<VTKFile type=\"PPolyData\" version=\"1.0\" byte_order=\""
            << (std::endian::native == std::endian::little ? "LittleEndian" : "BigEndian")
            << "\" header_type=\"UInt64\">\n  <PPolyData GhostLevel=\"0\">\n    <PPointData GlobalIds=\""
            << ordinal_array << "\">\n";
        for (const auto& a : arrays_)
            xml << "      <PDataArray type=\"" << a.type << "\" Name=\"" << gimlet::io::detail::xml_escape(a.name)
                << "\" NumberOfComponents=\"" << a.components << "\"/>\n";
        xml << "      <PDataArray type=\"Int64\" IdType=\"1\" Name=\"" << ordinal_array << "\" NumberOfComponents=\"1\"/>\n";
        xml << "    </PPointData>\n    <PPoints>\n      <PDataArray type=\""
            << (points_ == precision::float64 ? "Float64" : "Float32")
            << "\" Name=\"Points\" NumberOfComponents=\"3\"/>\n    </PPoints>\n";
        for (int r = 0; r < pieces; ++r)
            xml << "    <Piece Source=\""
                << gimlet::io::detail::xml_escape(piece_path(path, r).filename().generic_string()) << "\"/>\n";
        xml << "  </PPolyData>\n</VTKFile>\n";
        out << xml.str();
    }

    template <class Out, class Column>
    static void fill_points(const Column& x, std::vector<char>& bytes) {
        bytes.resize(x.size() * 3 * sizeof(Out));
        std::size_t at = 0;
        for (const auto& xi : x)
            for (int k = 0; k < 3; ++k) detail::put(bytes, at, static_cast<Out>(detail::vtk_component(xi, k)));
    }

    // Vertex i is the single point i: connectivity i, end offset i + 1.
    template <class Index>
    static void fill_indices(std::size_t n, std::size_t shift, std::vector<char>& bytes) {
        bytes.resize(n * sizeof(Index));
        std::size_t at = 0;
        for (std::size_t i = 0; i < n; ++i) detail::put(bytes, at, static_cast<Index>(i + shift));
    }

    precision points_;
    std::vector<array> arrays_;
};

/// The snapshot writer for a solver type: `vtp_writer_for<decltype(solver)> vtp;`.
template <class Solver>
using vtp_writer_for = vtp_writer<typename Solver::store_type>;

}  // namespace gimlet::io
