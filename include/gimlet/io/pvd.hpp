// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// A ParaView collection (.pvd): the list of (time, snapshot file) of a run, rewritten after
/// every snapshot so that a run stopped at any moment leaves a series ParaView opens.

#include "gimlet/core/error.hpp"
#include "gimlet/io/detail/file.hpp"
#include "gimlet/io/detail/text.hpp"

#include <charconv>
#include <cstdio>
#include <system_error>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <ostream>
#include <sstream>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace gimlet::io {

/// Writes a .pvd collection of snapshot files, each at its simulated time.
///
/// File names are stored relative to the .pvd's directory, so the output directory can be
/// moved or copied as a whole.
class pvd_writer {
public:
    /// One snapshot: its time (s) and its file, relative to the .pvd's directory.
    struct entry {
        /// Simulated time (s).
        double time;
        /// The snapshot's file name, relative to the .pvd's directory.
        std::string file;
    };

    /// Start a new, empty series at `path` (written at once, so a path that cannot be written
    /// is refused before the run starts). Throws invalid_parameter naming the path.
    explicit pvd_writer(std::filesystem::path path) : path_(std::move(path)) { rewrite(); }

    /// Continue the series of an interrupted run resumed from a checkpoint taken at `time`:
    /// keeps the entries of the existing file at `path` up to and including `time` and drops
    /// the later ones (the resumed run writes them again). Throws invalid_parameter if the file
    /// cannot be read or holds no collection.
    [[nodiscard]] static pvd_writer resume(std::filesystem::path path, double time) {
        std::ifstream in(path, std::ios::binary);
        if (!in)
            throw invalid_parameter("ParaView series file (.pvd)", detail::quoted(path.string()),
                                    "an existing, readable .pvd file to continue");
        const std::string text{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
        if (text.find("<Collection") == std::string::npos)
            throw invalid_parameter("ParaView series file (.pvd)", detail::quoted(path.string()),
                                    "a .pvd file holding a <Collection>");
        std::vector<entry> kept;
        for (const auto& e : parse(text, path))
            if (e.time <= time) kept.push_back(e);
        return pvd_writer(std::move(path), std::move(kept));
    }

    /// Record the snapshot `file` at `time` (s) and rewrite the .pvd. A relative `file` is
    /// taken relative to the working directory, like any path; the .pvd stores it relative to
    /// its own directory. Throws invalid_parameter if the .pvd cannot be written, or for a file
    /// name XML cannot hold (control characters, bytes that are not UTF-8).
    void add(double time, const std::filesystem::path& file) {
        require_finite("snapshot time (s)", time);
        std::string relative = relative_to_series(file);
        if (const auto why = detail::xml_attribute_problem(relative); !why.empty())
            throw invalid_parameter("ParaView snapshot file name", detail::quoted(relative),
                                    "UTF-8 text without control characters (it holds " + why + ")");
        entries_.push_back({time, std::move(relative)});
        rewrite();
    }

    /// Write the next snapshot of `solver` with `writer` (a vtp_writer) as
    /// `<stem>_<NNNNNN>.vtp` next to the .pvd, `<stem>` the .pvd's name without extension and
    /// NNNNNN the number of entries so far, and record it at the solver's time.
    /// Returns the snapshot's path.
    template <class Writer, class Solver>
    std::filesystem::path write(const Writer& writer, const Solver& solver) {
        char number[32];
        std::snprintf(number, sizeof number, "_%06zu.vtp", entries_.size());
        std::filesystem::path file = path_;
        file.replace_filename(path_.stem().string() + number);
        writer.write(file, solver);
        add(double(solver.time()), file);
        return file;
    }

    /// The snapshots recorded so far, in order.
    [[nodiscard]] const std::vector<entry>& entries() const noexcept { return entries_; }
    /// Where the .pvd is written.
    [[nodiscard]] const std::filesystem::path& path() const noexcept { return path_; }

private:
    pvd_writer(std::filesystem::path path, std::vector<entry> entries)
        : path_(std::move(path)), entries_(std::move(entries)) {
        rewrite();
    }

    [[nodiscard]] std::string relative_to_series(const std::filesystem::path& file) const {
        const auto dir = std::filesystem::absolute(path_).parent_path().lexically_normal();
        const auto abs = std::filesystem::absolute(file).lexically_normal();
        const auto rel = abs.lexically_relative(dir);
        return (rel.empty() ? abs : rel).generic_string();
    }

    // The whole file is rewritten through a temporary and a rename: the previous complete
    // version stays in place until the new one is.
    void rewrite() const {
        std::ostringstream xml;
        xml << "<?xml version=\"1.0\"?>\n"
            << "<VTKFile type=\"Collection\" version=\"0.1\">\n  <Collection>\n";
        for (const auto& e : entries_)
            xml << "    <DataSet timestep=\"" << detail::exact_text(e.time) << "\" group=\"\" part=\"0\" file=\""
                << detail::xml_escape(e.file) << "\"/>\n";
        xml << "  </Collection>\n</VTKFile>\n";
        detail::write_atomically(path_, "ParaView series file (.pvd)", [&](std::ostream& out) { out << xml.str(); });
    }

    // The value of attribute `name` in one element's text, unescaped; empty if absent.
    static std::string attribute(std::string_view element, std::string_view name) {
        std::string key(1, ' ');
        key.append(name).append("=\"");
        const auto start = element.find(key);
        if (start == std::string_view::npos) return {};
        const auto from = start + key.size();
        const auto end = element.find('"', from);
        if (end == std::string_view::npos) return {};
        return detail::xml_unescape(element.substr(from, end - from));
    }

    static std::vector<entry> parse(std::string_view text, const std::filesystem::path& path) {
        std::vector<entry> out;
        for (auto at = text.find("<DataSet"); at != std::string_view::npos; at = text.find("<DataSet", at + 1)) {
            const auto end = text.find('>', at);
            const auto element = text.substr(at, end == std::string_view::npos ? std::string_view::npos : end - at);
            const std::string t = attribute(element, "timestep");
            std::string file = attribute(element, "file");
            double time = 0;
            // from_chars, not strtod: independent of the C locale's decimal point.
            const auto [stop, ec] = std::from_chars(t.data(), t.data() + t.size(), time);
            if (t.empty() || ec != std::errc{} || stop != t.data() + t.size() || file.empty())
                throw invalid_parameter("ParaView series file (.pvd)", detail::quoted(path.string()),
                                        "a .pvd whose every DataSet has a numeric timestep and a file (entry " +
                                            std::to_string(out.size()) + " has not)");
            out.push_back({time, std::move(file)});
        }
        return out;
    }

    std::filesystem::path path_;
    std::vector<entry> entries_;
};

}  // namespace gimlet::io
