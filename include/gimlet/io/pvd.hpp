// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// A ParaView collection (.pvd): the list of (time, snapshot file) of a run, rewritten after
/// every snapshot so that a run stopped at any moment leaves a series ParaView opens.

#include "gimlet/core/error.hpp"
#include "gimlet/core/processes.hpp"
#include "gimlet/io/detail/file.hpp"
#include "gimlet/io/detail/text.hpp"

#include <charconv>
#include <cstdio>
#include <system_error>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <memory>
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
///
/// On many processes (a gimlet::distributed_solver given solver_options::processes), every
/// process makes the series with the solver's processes and calls each member alike (they are collective): the first
/// process writes the .pvd, each snapshot is a `.pvtp` of one piece a process
/// (vtp_writer::write_pieces), nothing gathered, and a failure on any process throws
/// gimlet::processes_stopped on all (with the message below; its bad_input() is true) where one
/// process throws invalid_parameter.
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
    /// is refused before the run starts). `processes`: the solver's on many processes (see the
    /// class), null on one. Throws invalid_parameter naming the path.
    explicit pvd_writer(std::filesystem::path path, std::shared_ptr<gimlet::processes> processes = nullptr)
        : path_(std::move(path)), processes_(std::move(processes)) {
        rewrite();
    }

    /// Continue the series of an interrupted run resumed from a checkpoint taken at `time`:
    /// keeps the entries of the existing file at `path` up to and including `time` and drops
    /// the later ones (the resumed run writes them again). On many processes the first reads
    /// the file and shares its entries. Throws invalid_parameter if the file cannot be read or
    /// holds no collection.
    [[nodiscard]] static pvd_writer resume(std::filesystem::path path, double time,
                                           std::shared_ptr<gimlet::processes> processes = nullptr) {
        std::string text;
        const auto read = [&] {
            std::ifstream in(path, std::ios::binary);
            if (!in)
                throw invalid_parameter("ParaView series file (.pvd)", detail::quoted(path.string()),
                                        "an existing, readable .pvd file to continue");
            text.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
            if (text.find("<Collection") == std::string::npos)
                throw invalid_parameter("ParaView series file (.pvd)", detail::quoted(path.string()),
                                        "a .pvd file holding a <Collection>");
        };
        std::vector<entry> kept;
        const auto keep = [&] {
            for (const auto& e : parse(text, path))
                if (e.time <= time) kept.push_back(e);
        };
        if (processes) {
            const bool first = processes->rank() == 0;
            processes->together([&] { if (first) read(); });
            text = processes->share(first ? &text : nullptr);
            processes->together(keep);  // the same text, so the same outcome on every process
        } else {
            read();
            keep();
        }
        return pvd_writer(std::move(path), std::move(kept), std::move(processes));
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
    ///
    /// On many processes (the series made with the solver's processes) each snapshot is
    /// `<stem>_<NNNNNN>.pvtp` with its pieces `<stem>_<NNNNNN>_<rank>.vtp`
    /// (vtp_writer::write_pieces). Throws invalid_parameter where the series and the solver do
    /// not have the same processes.
    template <class Writer, class Solver>
    std::filesystem::path write(const Writer& writer, const Solver& solver) {
        if (gimlet::detail::processes_of(solver) != processes_.get())
            throw invalid_parameter("ParaView series' processes",
                                    processes_ ? "those given to the series, not the solver's"
                                               : "none, where the solver has processes",
                                    "the solver's (solver_options::processes): make the series with them on every "
                                    "process");
        char number[32];
        std::snprintf(number, sizeof number, processes_ ? "_%06zu.pvtp" : "_%06zu.vtp", entries_.size());
        std::filesystem::path file = path_;
        file.replace_filename(path_.stem().string() + number);
        if constexpr (requires { writer.write_pieces(file, solver); }) {
            if (processes_) writer.write_pieces(file, solver);
            else writer.write(file, solver);
        } else {
            if (processes_)
                throw invalid_parameter("ParaView series' writer", "one without write_pieces",
                                        "a writer of pieces (vtp_writer) on many processes");
            writer.write(file, solver);
        }
        add(double(solver.time()), file);
        return file;
    }

    /// The snapshots recorded so far, in order.
    [[nodiscard]] const std::vector<entry>& entries() const noexcept { return entries_; }
    /// Where the .pvd is written.
    [[nodiscard]] const std::filesystem::path& path() const noexcept { return path_; }

private:
    pvd_writer(std::filesystem::path path, std::vector<entry> entries, std::shared_ptr<gimlet::processes> processes)
        : path_(std::move(path)), entries_(std::move(entries)), processes_(std::move(processes)) {
        rewrite();
    }

    [[nodiscard]] std::string relative_to_series(const std::filesystem::path& file) const {
        const auto dir = std::filesystem::absolute(path_).parent_path().lexically_normal();
        const auto abs = std::filesystem::absolute(file).lexically_normal();
        const auto rel = abs.lexically_relative(dir);
        return (rel.empty() ? abs : rel).generic_string();
    }

    // The whole file is rewritten through a temporary and a rename: the previous complete
    // version stays in place until the new one is. On many processes the first writes it.
    void rewrite() const {
        if (processes_) {
            const bool first = processes_->rank() == 0;
            processes_->together([&] { if (first) rewrite_file(); });
        } else {
            rewrite_file();
        }
    }

    void rewrite_file() const {
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
    std::shared_ptr<gimlet::processes> processes_;
};

}  // namespace gimlet::io
