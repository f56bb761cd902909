// SPDX-License-Identifier: MIT
#pragma once
// Minimal command-line parsing shared by the examples: `--name value` (or `--name=value`)
// pairs, each validated, with a message that names the flag and its valid range. A bad flag
// throws std::invalid_argument; the examples print it and exit non-zero. `--help` prints the
// usage and exits 0. Not part of the library.

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <map>
#include <stdexcept>
#include <string>
#include <system_error>

namespace example {

class cli {
public:
    cli(int argc, char** argv, std::string usage) : usage_(std::move(usage)) {
        for (int i = 1; i < argc; ++i) {
            const std::string a = argv[i];
            if (a == "--help" || a == "-h") {
                std::printf("%s\n", usage_.c_str());
                std::exit(0);
            }
            if (a.rfind("--", 0) != 0 || a.size() == 2)
                throw std::invalid_argument("unexpected argument '" + a + "' (flags are --name value)\n" + usage_);
            std::string name = a.substr(2), value;
            if (const auto eq = name.find('='); eq != std::string::npos) {
                value = name.substr(eq + 1);
                name.resize(eq);
            } else if (i + 1 < argc) {
                value = argv[++i];
            } else {
                throw std::invalid_argument("flag --" + name + " needs a value\n" + usage_);
            }
            if (!values_.emplace(name, value).second)
                throw std::invalid_argument("flag --" + name + " is given more than once\n" + usage_);
        }
    }

    /// A real-valued flag in (lo, hi] or [lo, hi] (closed_low), with a default. Anything else
    /// (not a number, trailing characters, nan, inf, out of range) is refused.
    double real(const std::string& name, double fallback, double lo, double hi, bool closed_low = false) {
        const auto it = take(name);
        if (!it) return fallback;
        char* end = nullptr;
        const double v = std::strtod(it->c_str(), &end);
        const bool parsed = end != it->c_str() && *end == '\0';
        const bool ok = parsed && std::isfinite(v) && (closed_low ? v >= lo : v > lo) && v <= hi;
        if (!ok)
            throw std::invalid_argument("--" + name + " = " + (it->empty() ? "''" : *it) +
                                        " is invalid; valid range: " + (closed_low ? "[" : "(") + text(lo) + ", " +
                                        text(hi) + "]");
        return v;
    }

    /// A whole-number flag in [lo, hi], with a default; a fraction is refused, not truncated.
    int integer(const std::string& name, int fallback, int lo, int hi) {
        const auto it = take(name);
        if (!it) return fallback;
        char* end = nullptr;
        const long v = std::strtol(it->c_str(), &end, 10);
        if (end == it->c_str() || *end != '\0' || v < lo || v > hi)
            throw std::invalid_argument("--" + name + " = " + (it->empty() ? "''" : *it) +
                                        " is invalid; valid: a whole number in [" + std::to_string(lo) + ", " +
                                        std::to_string(hi) + "]");
        return static_cast<int>(v);
    }

    /// A flag that takes one of a fixed set of words.
    std::string choice(const std::string& name, const std::string& fallback, std::initializer_list<std::string> allowed) {
        const auto it = take(name);
        if (!it) return fallback;
        std::string list;
        for (const auto& a : allowed) {
            if (*it == a) return a;
            list += (list.empty() ? "" : "|") + a;
        }
        throw std::invalid_argument("--" + name + " = " + *it + " is invalid; valid: " + list);
    }

    /// A file path flag; empty if not given and no fallback. The caller opens the file and
    /// reports what is wrong with it.
    std::string path(const std::string& name, const std::string& fallback = "") {
        const auto it = take(name);
        if (!it) return fallback;
        if (it->empty()) throw std::invalid_argument("--" + name + " = '' is invalid; valid: a file path");
        return *it;
    }

    /// An output directory flag: created if missing, then probed by writing a file into it.
    /// Refused, with the reason, if it cannot be created or written.
    std::filesystem::path directory(const std::string& name, const std::string& fallback) {
        const auto it = take(name);
        const std::filesystem::path dir = it ? *it : fallback;
        const auto refuse = [&](const std::string& why) {
            throw std::invalid_argument("--" + name + " = " + (dir.empty() ? "''" : dir.string()) +
                                        " is invalid; valid: a directory that can be created and written (" + why +
                                        ")");
        };
        if (dir.empty()) refuse("empty path");
        std::error_code ec;
        if (std::filesystem::exists(dir, ec) && !std::filesystem::is_directory(dir, ec))
            refuse("it exists and is not a directory");
        std::filesystem::create_directories(dir, ec);
        if (ec) refuse("cannot create it: " + ec.message());
        const auto probe = dir / ".gimlet_write_test";
        {
            std::ofstream f(probe);
            if (!(f << "probe\n") || !f.flush()) refuse("cannot write a file in it");
        }
        std::filesystem::remove(probe, ec);
        return dir;
    }

    /// Every flag given must have been read: an unknown flag is an error, never ignored.
    void finish() const {
        for (const auto& [k, v] : values_)
            if (!used_.count(k)) throw std::invalid_argument("unknown flag --" + k + "\n" + usage_);
    }

private:
    static std::string text(double v) {
        char buf[32];
        std::snprintf(buf, sizeof buf, "%g", v);
        return buf;
    }
    const std::string* take(const std::string& name) {
        const auto it = values_.find(name);
        if (it == values_.end()) return nullptr;
        used_[name] = true;
        return &it->second;
    }
    std::string usage_;
    std::map<std::string, std::string> values_;
    std::map<std::string, bool> used_;
};

}  // namespace example
