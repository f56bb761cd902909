// SPDX-License-Identifier: MIT
#pragma once
// Minimal command-line parsing shared by the examples: --name value pairs, each validated, with
// a message that names the flag and its valid range. Not part of the library.

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <map>
#include <stdexcept>
#include <string>

namespace example {

class cli {
public:
    cli(int argc, char** argv, std::string usage) : usage_(std::move(usage)) {
        for (int i = 1; i < argc; ++i) {
            std::string a = argv[i];
            if (a == "--help" || a == "-h") throw std::runtime_error(usage_);
            if (a.rfind("--", 0) != 0 || i + 1 >= argc)
                throw std::invalid_argument("unexpected argument '" + a + "'\n" + usage_);
            values_[a.substr(2)] = argv[++i];
        }
    }

    /// A real-valued flag in (lo, hi] or [lo, hi] (closed_low), with a default.
    double real(const std::string& name, double fallback, double lo, double hi, bool closed_low = false) {
        const auto it = take(name);
        if (!it) return fallback;
        char* end = nullptr;
        const double v = std::strtod(it->c_str(), &end);
        const bool ok = end && *end == '\0' && std::isfinite(v) && (closed_low ? v >= lo : v > lo) && v <= hi;
        if (!ok)
            throw std::invalid_argument("--" + name + " = " + *it + " is invalid; valid range: " +
                                        (closed_low ? "[" : "(") + text(lo) + ", " + text(hi) + "]");
        return v;
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

    /// An output directory flag: created if missing, must be writable.
    std::filesystem::path directory(const std::string& name, const std::string& fallback) {
        const auto it = take(name);
        const std::filesystem::path dir = it ? *it : fallback;
        std::error_code ec;
        std::filesystem::create_directories(dir, ec);
        const auto probe = dir / ".write_test";
        std::ofstream f(probe);
        if (ec || !f)
            throw std::invalid_argument("--" + name + " = " + dir.string() + " is invalid; valid: a directory that can be created and written");
        f.close();
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
