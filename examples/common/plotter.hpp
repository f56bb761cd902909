// SPDX-License-Identifier: MIT
#pragma once
// An example's figures drawn by a plotting script in a process of its own while the run goes on
// (examples' helper, not part of the library).

#include <csignal>
#include <cstdio>
#include <filesystem>
#include <string>
#include <system_error>
#include <utility>

namespace example {

// A word for the shell, single-quoted: any path, whatever its characters.
inline std::string shell_word(const std::string& s) {
    std::string q = "'";
    for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return q + "'";
}

// The figures drawn while the run goes on: the script (cavity_collapse's `plot.py --follow`)
// reads each snapshot's index and time as its map is written and draws the map from processor
// time the run leaves idle, and draws the rest when the run ends (the line `end`; its input
// closed without it, by a run that threw or was killed, it draws nothing more). Drawn after the
// run, the figures take 12 % of the quickstart's run with outputs off (docs/performance.md,
// "The flagship's outputs").
class plotter {
public:
    // command: the plotter's, its errors sent to log (removed at the end if empty).
    plotter(const std::string& command, std::filesystem::path log) : log_(std::move(log)) {
        // A plotter that cannot start (no python3, no matplotlib) exits; writing to its pipe
        // then fails with EPIPE rather than stopping the run with SIGPIPE. (For the whole
        // process: with its standard output piped into a program that exits early, the run
        // goes on to its end and writes its files.)
        std::signal(SIGPIPE, SIG_IGN);
        pipe_ = popen((command + " 2>" + shell_word(log_.string())).c_str(), "w");
        failed_ = pipe_ == nullptr;
    }
    plotter(const plotter&) = delete;
    plotter& operator=(const plotter&) = delete;
    // Left without finish() (the run threw): the input closed without `end`, the plotter stops.
    ~plotter() {
        if (pipe_) pclose(pipe_), drop_empty_log();
    }
    // A map written: its index and time after contact (the values snapshots/times.csv holds),
    // and whether it is the run's last.
    void map(std::size_t index, double after_contact_us, bool last) {
        if (pipe_ && (std::fprintf(pipe_, "%zu %.17g%s\n", index, after_contact_us, last ? " last" : "") < 0 ||
                      std::fflush(pipe_) != 0))
            failed_ = true;
    }
    // The run has ended and its files are closed: waits for the figures; true if every one was
    // drawn.
    bool finish() {
        if (!pipe_) return !failed_;
        if (std::fputs("end\n", pipe_) < 0) failed_ = true;
        const int status = pclose(pipe_);
        pipe_ = nullptr;
        failed_ = failed_ || status != 0;
        drop_empty_log();
        return !failed_;
    }

private:
    void drop_empty_log() const {
        std::error_code ec;
        if (std::filesystem::file_size(log_, ec) == 0 && !ec) std::filesystem::remove(log_, ec);
    }
    std::filesystem::path log_;
    FILE* pipe_ = nullptr;
    bool failed_ = false;
};

}  // namespace example
