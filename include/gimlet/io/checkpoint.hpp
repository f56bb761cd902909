// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// Checkpoint and restart: save a solver's particles and clock to one file, and resume a run
/// from it so that it continues bit for bit as if it had never stopped.
///
/// \code
/// gimlet::io::save_checkpoint("run.ckpt", sol, {{"next_output_us", 12.5}});
/// ...                                   // later, another process, same scene and options:
/// solver_type resumed(make_scene(), options);
/// const auto values = gimlet::io::load_checkpoint("run.ckpt", resumed);
/// \endcode
///
/// What is saved is the state the solver carries from one step to the next: every particle
/// column, the time and the step count. The grid, the stencils and the contact scratch space
/// are rebuilt inside every step, and the materials and options come from the scene the caller
/// builds again, so they are not saved.
///
/// File format, version 1 (docs/io.md). All integers and reals in the writer's byte order
/// (recorded by a byte-order mark; a host of the other order refuses the file):
///
///     offset  size  content
///          0     8  magic "GIMLETCK"
///          8     4  u32 format version (1)
///         12     4  u32 byte-order mark 0x01020304
///         16     8  u64 total file size in bytes, checksum included
///         24     4  u32 dimension (2 or 3)
///         28     4  u32 bytes per real (4 or 8)
///         32     8  u64 particle count n
///         40     8  f64 simulated time (s)
///         48     8  u64 steps taken
///         56     4  u32 field count F
///         60     4  u32 value count V (the caller's key-values)
///         64        F x (u32 name length, name, u32 bytes per particle)
///                   V x (u32 key length, key, f64 value)
///                   F columns in the same order, n x bytes per particle each
///                   (Eigen values in Eigen's storage order, column-major)
///    size-8     8  u64 64-bit FNV-1a of every byte before it

#include "gimlet/core/error.hpp"
#include "gimlet/core/fields.hpp"
#include "gimlet/core/processes.hpp"
#include "gimlet/io/detail/file.hpp"
#include "gimlet/io/detail/text.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <ostream>
#include <sstream>
#include <string>
#include <tuple>
#include <type_traits>
#include <utility>
#include <vector>

namespace gimlet::io {

/// A checkpoint that cannot be loaded: missing, truncated, corrupt, of another format version,
/// or written by a solver whose particles do not match. The message names the file and the
/// problem. It is an invalid_parameter (parameter "checkpoint file"), so code that reports bad
/// input catches it too.
class checkpoint_error : public invalid_parameter {
public:
    /// \param file the checkpoint's path; \param problem what is wrong with it, in words.
    checkpoint_error(const std::filesystem::path& file, const std::string& problem)
        : invalid_parameter("checkpoint file", detail::quoted(file.string()), problem),
          message_(std::string("checkpoint file ") + detail::quoted(file.string()) + " refused: " + problem),
          problem_(problem) {}
    /// The whole message: the file (quoted), "refused:", and the problem.
    [[nodiscard]] const char* what() const noexcept override { return message_.c_str(); }
    /// The problem alone, without the file name.
    [[nodiscard]] const std::string& problem() const noexcept { return problem_; }

private:
    std::string message_;
    std::string problem_;
};

/// The caller's own small state saved with a checkpoint, e.g. an observer's next output time.
/// Values are doubles (integers up to 2^53 are exact).
using checkpoint_values = std::map<std::string, double>;

/// One particle field as a checkpoint records it.
struct checkpoint_field {
    /// The field's name (its tag's `name`).
    std::string name;
    /// Bytes one particle's value takes (e.g. 24 for a 3-D vector of doubles).
    std::size_t bytes_per_particle = 0;
    /// Equal names and sizes.
    friend bool operator==(const checkpoint_field&, const checkpoint_field&) = default;
};

/// What a checkpoint file holds, besides the particle columns.
struct checkpoint_info {
    /// 2 or 3.
    int dimension = 0;
    /// Bytes per real: 4 (float) or 8 (double).
    std::size_t real_bytes = 0;
    /// Number of particles n.
    std::uint64_t particles = 0;
    /// Simulated time at the save (s).
    double time = 0;
    /// Steps taken at the save.
    std::uint64_t steps = 0;
    /// The particle columns, in the file's order.
    std::vector<checkpoint_field> fields;
    /// The caller's key-values saved with it.
    checkpoint_values values;
};

/// A solver save_checkpoint and load_checkpoint work with (gimlet::solver).
template <class Solver>
concept Checkpointable = requires(Solver& s, const Solver& cs) {
    typename Solver::space_type;
    cs.particles().size();
    cs.time();
    { cs.steps() } -> std::convertible_to<std::uint64_t>;
    s.resume_at(cs.time(), std::uint64_t{});
};

namespace detail {

inline constexpr char checkpoint_magic[8] = {'G', 'I', 'M', 'L', 'E', 'T', 'C', 'K'};
inline constexpr std::uint32_t checkpoint_version = 1;
inline constexpr std::uint32_t byte_order_mark = 0x01020304;
inline constexpr std::size_t checkpoint_fixed_header = 64;
inline constexpr std::size_t checksum_bytes = 8;

template <class T>
concept eigen_fixed = requires {
    typename T::Scalar;
    T::SizeAtCompileTime;
} && (T::SizeAtCompileTime > 0);

template <class T>
inline constexpr bool always_false = false;

// Bytes one particle's value of type T takes in the file.
template <class T>
constexpr std::size_t element_bytes() {
    if constexpr (std::is_arithmetic_v<T>) {
        return sizeof(T);
    } else if constexpr (eigen_fixed<T>) {
        static_assert(std::is_arithmetic_v<typename T::Scalar>, "checkpoint: Eigen fields must hold arithmetic scalars");
        return std::size_t(T::SizeAtCompileTime) * sizeof(typename T::Scalar);
    } else {
        static_assert(always_false<T>,
                      "checkpoint: a particle field must be arithmetic or a fixed-size Eigen type");
        return 0;
    }
}

// Writes to a stream and hashes what it wrote.
class hashing_sink {
public:
    explicit hashing_sink(std::ostream& out) : out_(out) {}
    void bytes(const void* data, std::size_t n) {
        out_.write(static_cast<const char*>(data), static_cast<std::streamsize>(n));
        hash_.add(static_cast<const char*>(data), n);
    }
    template <class T>
    void value(const T& v) {
        bytes(&v, sizeof(T));
    }
    void text(const std::string& s) {
        value(static_cast<std::uint32_t>(s.size()));
        bytes(s.data(), s.size());
    }
    [[nodiscard]] std::uint64_t hash() const noexcept { return hash_.value(); }

private:
    std::ostream& out_;
    fnv1a64 hash_;
};

// Reads from an in-memory file; running past its end is a malformed file (the size and the
// checksum were checked before, so only a file crafted with a valid checksum gets here).
class byte_reader {
public:
    byte_reader(const std::vector<char>& bytes, std::size_t end, const std::filesystem::path& file)
        : bytes_(bytes), end_(end), file_(file) {}
    template <class T>
    T value() {
        T v;
        std::memcpy(&v, take(sizeof(T)), sizeof(T));
        return v;
    }
    std::string text() {
        const auto n = value<std::uint32_t>();
        const char* p = take(n);
        return {p, n};
    }
    const char* take(std::size_t n) {
        if (n > end_ - at_)
            throw checkpoint_error(file_, "malformed: its header describes more bytes than the file holds (at byte " +
                                              std::to_string(at_) + ")");
        const char* p = bytes_.data() + at_;
        at_ += n;
        return p;
    }
    [[nodiscard]] std::size_t position() const noexcept { return at_; }
    void seek(std::size_t at) noexcept { at_ = at; }

private:
    const std::vector<char>& bytes_;
    std::size_t end_;
    std::size_t at_ = 0;
    const std::filesystem::path& file_;
};

template <class Store>
std::vector<checkpoint_field> layout_of(const Store& store) {
    std::vector<checkpoint_field> fields;
    store.for_each_column([&](auto tag, const auto& column) {
        using T = typename std::remove_cvref_t<decltype(column)>::value_type;
        fields.push_back({decltype(tag)::name, element_bytes<T>()});
    });
    return fields;
}

template <class T>
void write_column(hashing_sink& sink, const std::vector<T>& column) {
    if constexpr (std::is_arithmetic_v<T>) {
        sink.bytes(column.data(), column.size() * sizeof(T));
    } else {
        for (const auto& v : column) sink.bytes(v.data(), element_bytes<T>());
    }
}

// Eigen values are copied scalar by scalar through data(): their storage is a plain array of
// scalars, but the Eigen types themselves are not trivially copyable.
template <class T>
void read_column(const char* from, std::vector<T>& column) {
    if constexpr (std::is_arithmetic_v<T>) {
        if (!column.empty()) std::memcpy(column.data(), from, column.size() * sizeof(T));
    } else {
        for (std::size_t i = 0; i < column.size(); ++i)
            std::memcpy(column[i].data(), from + i * element_bytes<T>(), element_bytes<T>());
    }
}

[[nodiscard]] inline std::string describe_layout(const std::vector<checkpoint_field>& fields) {
    std::string s;
    for (const auto& f : fields) s += (s.empty() ? "" : ", ") + f.name + " (" + std::to_string(f.bytes_per_particle) + " B)";
    return "[" + s + "]";
}

// What differs between two field layouts, in words.
[[nodiscard]] inline std::string layout_difference(const std::vector<checkpoint_field>& file,
                                                   const std::vector<checkpoint_field>& solver) {
    auto names_not_in = [](const std::vector<checkpoint_field>& a, const std::vector<checkpoint_field>& b) {
        std::string s;
        for (const auto& f : a) {
            bool found = false;
            for (const auto& g : b) found = found || g.name == f.name;
            if (!found) s += (s.empty() ? "" : ", ") + f.name;
        }
        return s;
    };
    std::string what;
    const std::string only_file = names_not_in(file, solver), only_solver = names_not_in(solver, file);
    if (!only_file.empty()) what += "fields only in the file: " + only_file + "; ";
    if (!only_solver.empty()) what += "fields only in the solver: " + only_solver + "; ";
    if (what.empty()) {
        for (std::size_t i = 0; i < file.size() && what.empty(); ++i) {
            if (file[i].name != solver[i].name)
                what = "the same fields in another order (field " + std::to_string(i) + " is " + file[i].name +
                       " in the file, " + solver[i].name + " in the solver); ";
            else if (file[i].bytes_per_particle != solver[i].bytes_per_particle)
                what = "field " + file[i].name + " has " + std::to_string(file[i].bytes_per_particle) +
                       " bytes per particle in the file, " + std::to_string(solver[i].bytes_per_particle) +
                       " in the solver; ";
        }
    }
    return "particle field layout differs (the checkpoint comes from a solver of another type): " + what +
           "file " + describe_layout(file) + ", solver " + describe_layout(solver);
}

// A parsed and verified file: its description, and where the columns start.
struct parsed_checkpoint {
    checkpoint_info info;
    std::size_t columns_at = 0;
};

[[nodiscard]] inline std::vector<char> read_whole_file(const std::filesystem::path& file) {
    std::ifstream in(file, std::ios::binary);
    if (!in) throw checkpoint_error(file, "cannot be opened for reading (missing, or no permission)");
    std::vector<char> bytes{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
    if (in.bad()) throw checkpoint_error(file, "reading it failed");
    return bytes;
}

// Checks everything the file can check on its own: magic, byte order, version, size
// (truncation), checksum, and the consistency of its header.
[[nodiscard]] inline parsed_checkpoint parse_checkpoint(const std::vector<char>& bytes,
                                                        const std::filesystem::path& file) {
    const std::size_t size = bytes.size();
    const std::size_t magic_seen = std::min(size, sizeof checkpoint_magic);
    if (magic_seen > 0 && std::memcmp(bytes.data(), checkpoint_magic, magic_seen) != 0)
        throw checkpoint_error(file, "not a gimlet checkpoint (wrong magic: its first bytes are not \"GIMLETCK\")");
    if (size < checkpoint_fixed_header + checksum_bytes)
        throw checkpoint_error(file, "truncated: " + std::to_string(size) + " bytes, shorter than the " +
                                         std::to_string(checkpoint_fixed_header + checksum_bytes) +
                                         "-byte minimum (header and checksum)");
    byte_reader in(bytes, size, file);
    in.seek(sizeof checkpoint_magic);
    const auto version = in.value<std::uint32_t>();
    const auto mark = in.value<std::uint32_t>();
    if (mark != byte_order_mark)
        throw checkpoint_error(file, "written on a host of the other byte order (or corrupt): checkpoints are read "
                                     "on hosts of the writer's byte order only");
    if (version != checkpoint_version)
        throw checkpoint_error(file, "format version " + std::to_string(version) + "; this gimlet reads version " +
                                         std::to_string(checkpoint_version));
    const auto total = in.value<std::uint64_t>();
    if (size < total)
        throw checkpoint_error(file, "truncated: " + std::to_string(size) + " of its " + std::to_string(total) +
                                         " bytes (an interrupted copy or a full disk?)");
    if (size > total)
        throw checkpoint_error(file, std::to_string(size - total) + " unexpected bytes after its end (" +
                                         std::to_string(total) + " bytes expected)");
    fnv1a64 hash;
    hash.add(bytes.data(), size - checksum_bytes);
    std::uint64_t stored = 0;
    std::memcpy(&stored, bytes.data() + size - checksum_bytes, checksum_bytes);
    if (stored != hash.value())
        throw checkpoint_error(file, "checksum mismatch: the file is corrupt (stored FNV-1a " + std::to_string(stored) +
                                         ", computed " + std::to_string(hash.value()) + ")");

    byte_reader body(bytes, size - checksum_bytes, file);
    body.seek(24);  // past magic, version, byte-order mark and total size, all checked above
    parsed_checkpoint r;
    auto& info = r.info;
    info.dimension = int(body.value<std::uint32_t>());
    info.real_bytes = body.value<std::uint32_t>();
    info.particles = body.value<std::uint64_t>();
    info.time = body.value<double>();
    info.steps = body.value<std::uint64_t>();
    const auto field_count = body.value<std::uint32_t>();
    const auto value_count = body.value<std::uint32_t>();
    for (std::uint32_t i = 0; i < field_count; ++i) {
        std::string name = body.text();
        const auto per_particle = body.value<std::uint32_t>();
        info.fields.push_back({std::move(name), per_particle});
    }
    for (std::uint32_t i = 0; i < value_count; ++i) {
        std::string key = body.text();
        info.values[std::move(key)] = body.value<double>();
    }
    r.columns_at = body.position();
    std::uint64_t column_bytes = 0;
    for (const auto& f : info.fields) column_bytes += info.particles * f.bytes_per_particle;
    if (r.columns_at + column_bytes + checksum_bytes != size)
        throw checkpoint_error(file, "malformed: " + std::to_string(info.particles) + " particles of " +
                                         describe_layout(info.fields) + " do not fill the file");
    if (!(std::isfinite(info.time) && info.time >= 0))
        throw checkpoint_error(file, "malformed: its time " + gimlet::detail::to_text(info.time) +
                                         " s is not finite and >= 0");
    return r;
}

}  // namespace detail

namespace detail {
// The file of a store's particles, time and step count (save_checkpoint's format).
template <class S, class Store>
void write_checkpoint(const std::filesystem::path& path, const Store& store, double time, std::uint64_t steps,
                      const checkpoint_values& values) {
    const auto fields = detail::layout_of(store);
    const std::uint64_t n = store.size();

    std::uint64_t total = detail::checkpoint_fixed_header + detail::checksum_bytes;
    for (const auto& f : fields) total += 4 + f.name.size() + 4 + n * f.bytes_per_particle;
    for (const auto& [key, v] : values) total += 4 + key.size() + sizeof v;

    detail::write_atomically(path, "checkpoint file", [&](std::ostream& out) {
        detail::hashing_sink sink(out);
        sink.bytes(detail::checkpoint_magic, sizeof detail::checkpoint_magic);
        sink.value(detail::checkpoint_version);
        sink.value(detail::byte_order_mark);
        sink.value(total);
        sink.value(static_cast<std::uint32_t>(S::dim));
        sink.value(static_cast<std::uint32_t>(sizeof(typename S::real)));
        sink.value(n);
        sink.value(time);
        sink.value(steps);
        sink.value(static_cast<std::uint32_t>(fields.size()));
        sink.value(static_cast<std::uint32_t>(values.size()));
        for (const auto& f : fields) {
            sink.text(f.name);
            sink.value(static_cast<std::uint32_t>(f.bytes_per_particle));
        }
        for (const auto& [key, v] : values) {
            sink.text(key);
            sink.value(v);
        }
        store.for_each_column([&](auto, const auto& column) { detail::write_column(sink, column); });
        const std::uint64_t hash = sink.hash();
        out.write(reinterpret_cast<const char*>(&hash), sizeof hash);
    });
}
}  // namespace detail

/// Save `solver`'s particles, time and step count to `path`, with the caller's `values`.
/// The file is written under a temporary name in the same directory and renamed when complete,
/// so a crash never leaves a half-written checkpoint under `path` (an older one stays intact).
/// Throws invalid_parameter if `path` cannot be written.
///
/// On many processes (solver_options::processes) it is collective: the particles are gathered in
/// ordinal order and the first process writes the file, the one a single process would write
/// (so it restarts on any number of processes); a failure to write throws on every process.
template <Checkpointable Solver>
void save_checkpoint(const std::filesystem::path& path, const Solver& solver, const checkpoint_values& values = {}) {
    using S = typename Solver::space_type;
    if (gimlet::processes* p = gimlet::detail::processes_of(solver)) {
        const auto whole = solver.gathered_particles();
        p->together([&] {
            if (p->rank() == 0)
                detail::write_checkpoint<S>(path, whole, double(solver.time()), std::uint64_t(solver.steps()), values);
        });
        return;
    }
    detail::write_checkpoint<S>(path, solver.particles(), double(solver.time()), std::uint64_t(solver.steps()), values);
}

/// Read and verify the description of the checkpoint at `path` (everything but the columns),
/// without a solver. Throws checkpoint_error as load_checkpoint does for the file's own problems.
[[nodiscard]] inline checkpoint_info read_checkpoint_info(const std::filesystem::path& path) {
    return detail::parse_checkpoint(detail::read_whole_file(path), path).info;
}

/// Resume `solver` from the checkpoint at `path`: its particles, time and step count become
/// those saved. Build `solver` from the same scene, options and contact parameters as the run
/// that saved it; the run then continues bit for bit as the uninterrupted one. Returns the
/// caller's values saved with it.
///
/// The whole file is read and checked before the solver is touched: a file that is missing,
/// truncated, corrupt (checksum), of another version or byte order, or whose dimension, real
/// type, particle fields or particle count differ from the solver's, or whose particles' bodies,
/// masses or reference volumes are not the solver's (another scene), throws checkpoint_error
/// naming the file and the problem, and leaves the solver as it was.
namespace detail {
// The checks of load_checkpoint against `current` (the solver's particles, or on many processes
// all of them gathered), before anything is touched; throws checkpoint_error.
template <class S, class Store>
void check_checkpoint(const std::filesystem::path& path, const std::vector<char>& bytes, const parsed_checkpoint& parsed,
                      const Store& current) {
    const auto& info = parsed.info;
    if (info.dimension != S::dim)
        throw checkpoint_error(path, "dimension differs: the file is " + std::to_string(info.dimension) +
                                         "-D, the solver " + std::to_string(S::dim) + "-D");
    if (info.real_bytes != sizeof(typename S::real))
        throw checkpoint_error(path, "real type differs: the file has " + std::to_string(info.real_bytes) +
                                         "-byte reals, the solver " + std::to_string(sizeof(typename S::real)) +
                                         "-byte");
    const auto fields = detail::layout_of(current);
    if (info.fields != fields) throw checkpoint_error(path, detail::layout_difference(info.fields, fields));
    if (info.particles != current.size())
        throw checkpoint_error(path, "particle count differs: the file holds " + std::to_string(info.particles) +
                                         " particles, the solver " + std::to_string(current.size()) +
                                         " (build the solver from the same scene as the saved run)");

    // A run never changes a particle's body, mass or reference volume, so the file's must be
    // those of the solver's scene (in any order: sorting by cell permutes the particles).
    using real = typename S::real;
    using key = std::tuple<std::uint32_t, real, real>;
    std::vector<std::uint32_t> body(current.size());
    std::vector<real> mass(current.size()), volume(current.size());
    const char* at = bytes.data() + parsed.columns_at;
    current.for_each_column([&](auto tag, const auto& column) {
        using F = decltype(tag);
        using T = typename std::remove_cvref_t<decltype(column)>::value_type;
        if constexpr (std::is_same_v<F, fields::body>) detail::read_column(at, body);
        if constexpr (std::is_same_v<F, fields::mass>) detail::read_column(at, mass);
        if constexpr (std::is_same_v<F, fields::volume0>) detail::read_column(at, volume);
        at += column.size() * detail::element_bytes<T>();
    });
    std::vector<key> in_file(current.size()), in_solver(current.size());
    const auto& b = current.template column<fields::body>();
    const auto& m = current.template column<fields::mass>();
    const auto& v = current.template column<fields::volume0>();
    for (std::size_t i = 0; i < current.size(); ++i) {
        in_file[i] = {body[i], mass[i], volume[i]};
        in_solver[i] = {b[i], m[i], v[i]};
    }
    std::sort(in_file.begin(), in_file.end());
    std::sort(in_solver.begin(), in_solver.end());
    const auto differ = std::mismatch(in_file.begin(), in_file.end(), in_solver.begin());
    if (differ.first != in_file.end())
        throw checkpoint_error(
            path, "its particles are not the solver's scene: bodies, masses or reference volumes differ (e.g. a "
                  "particle of body " + std::to_string(std::get<0>(*differ.first)) + " with mass " +
                      gimlet::detail::to_text(std::get<1>(*differ.first)) + " and volume " +
                      gimlet::detail::to_text(std::get<2>(*differ.first)) +
                      " in the file has no match in the solver; build the solver from the same scene as the "
                      "saved run)");
}

// The file's columns into `store` (of the file's particle count).
template <class Store>
void read_columns(const std::vector<char>& bytes, const parsed_checkpoint& parsed, Store& store) {
    const char* at = bytes.data() + parsed.columns_at;
    store.for_each_column([&](auto, auto& column) {
        using T = typename std::remove_cvref_t<decltype(column)>::value_type;
        detail::read_column(at, column);
        at += column.size() * detail::element_bytes<T>();
    });
}
}  // namespace detail

/// Resume `solver` from the checkpoint at `path`: its particles, time and step count become
/// those saved. Build `solver` from the same scene, options and contact parameters as the run
/// that saved it; the run then continues bit for bit as the uninterrupted one. Returns the
/// caller's values saved with it.
///
/// The whole file is read and checked before the solver is touched: a file that is missing,
/// truncated, corrupt (checksum), of another version or byte order, or whose dimension, real
/// type, particle fields or particle count differ from the solver's, or whose particles' bodies,
/// masses or reference volumes are not the solver's (another scene), throws checkpoint_error
/// naming the file and the problem, and leaves the solver as it was.
///
/// On many processes (solver_options::processes) it is collective: every process reads the
/// file, the checks run on the particles of all of them (gathered in ordinal order), and each
/// keeps the particles of its own slabs, so a checkpoint written on any number of processes
/// resumes on any other, bit for bit; a failed check throws on every process.
template <Checkpointable Solver>
checkpoint_values load_checkpoint(const std::filesystem::path& path, Solver& solver) {
    using S = typename Solver::space_type;
    if (gimlet::processes* p = gimlet::detail::processes_of(solver)) {
        std::vector<char> bytes;
        detail::parsed_checkpoint parsed;
        const auto current = std::as_const(solver).gathered_particles();  // the whole run's on process 0
        p->together([&] {
            bytes = detail::read_whole_file(path);
            parsed = detail::parse_checkpoint(bytes, path);
            if (p->rank() == 0) detail::check_checkpoint<S>(path, bytes, parsed, current);
        });
        std::remove_cvref_t<decltype(current)> whole;
        whole.resize(parsed.info.particles);
        detail::read_columns(bytes, parsed, whole);
        solver.replace_particles(std::move(whole));
        solver.resume_at(static_cast<typename S::real>(parsed.info.time), parsed.info.steps);
        return parsed.info.values;
    }
    const std::vector<char> bytes = detail::read_whole_file(path);
    const auto parsed = detail::parse_checkpoint(bytes, path);
    detail::check_checkpoint<S>(path, bytes, parsed, std::as_const(solver).particles());
    // Nothing can fail from here on: the copy is all or nothing.
    detail::read_columns(bytes, parsed, solver.particles());
    solver.resume_at(static_cast<typename S::real>(parsed.info.time), parsed.info.steps);
    return parsed.info.values;
}

}  // namespace gimlet::io
