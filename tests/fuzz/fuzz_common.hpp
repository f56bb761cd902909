// SPDX-License-Identifier: MIT
#pragma once
// What the libFuzzer harnesses share (docs/robustness.md, "Fuzzing"): reading typed values from
// the fuzzer's bytes, a scratch file per process, and the rule every input must obey: it ends in
// a clean result or in one of the named errors (gimlet::invalid_parameter, including
// io::checkpoint_error; gimlet::numerical_error; the examples' std::invalid_argument). Anything
// else (another exception, a crash, a sanitizer report, a hang past -timeout) is a finding:
// the harness aborts and libFuzzer keeps the input.

#include <gimlet/core/error.hpp>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <cmath>
#include <type_traits>
#include <algorithm>
#include <exception>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <unistd.h>

namespace fuzz {

// Consumes the fuzzer's bytes front to back; past the end everything reads as zero.
class bytes {
public:
    bytes(const std::uint8_t* data, std::size_t size) : data_(data), size_(size) {}
    [[nodiscard]] std::size_t left() const { return size_ - at_; }
    std::uint8_t u8() { return at_ < size_ ? data_[at_++] : 0; }
    std::uint32_t u32() {
        std::uint32_t v = 0;
        for (int k = 0; k < 4; ++k) v |= std::uint32_t(u8()) << (8 * k);
        return v;
    }
    // Any double, NaN and infinities included.
    double f64() {
        std::uint64_t v = 0;
        for (int k = 0; k < 8; ++k) v |= std::uint64_t(u8()) << (8 * k);
        double d;
        std::memcpy(&d, &v, sizeof d);
        return d;
    }
    // A double in [lo, hi] from 16 bits, for parameters a scene must keep in range to stay small.
    double in(double lo, double hi) { return lo + (hi - lo) * double(u8() | (u8() << 8)) / 65535.0; }
    // A string of up to `max` bytes, any bytes.
    std::string text(std::size_t max) {
        const std::size_t n = std::min<std::size_t>(u8() % (max + 1), left());
        std::string s(reinterpret_cast<const char*>(data_ + at_), n);
        at_ += n;
        return s;
    }
    // The rest of the input.
    std::string rest() {
        std::string s(reinterpret_cast<const char*>(data_ + at_), left());
        at_ = size_;
        return s;
    }

private:
    const std::uint8_t* data_;
    std::size_t size_, at_ = 0;
};

// A file of this process in the temporary directory (libFuzzer may run several processes).
inline std::filesystem::path scratch(const std::string& name) {
    static const std::filesystem::path dir = [] {
        auto d = std::filesystem::temp_directory_path() / ("gimlet_fuzz_" + std::to_string(::getpid()));
        std::filesystem::create_directories(d);
        return d;
    }();
    return dir / name;
}

// Runs f; a named error is a clean end, anything else aborts with what it was. The library's
// errors are gimlet::invalid_parameter and gimlet::numerical_error; with `examples`, the
// examples' std::invalid_argument too (their flags).
template <bool examples = false, class F>
void expect_clean(F&& f) {
    try {
        f();
    } catch (const gimlet::invalid_parameter&) {
    } catch (const gimlet::numerical_error&) {
    } catch (const std::invalid_argument& e) {
        if (!examples) {
            std::fprintf(stderr, "fuzz: std::invalid_argument that is not gimlet's: %s\n", e.what());
            std::abort();
        }
    } catch (const std::exception& e) {
        std::fprintf(stderr, "fuzz: unexpected exception: %s\n", e.what());
        std::abort();
    } catch (...) {
        std::fprintf(stderr, "fuzz: unexpected exception of an unknown type\n");
        std::abort();
    }
}

// Whether every floating-point value of every particle field of a solver is finite.
template <class Solver>
bool finite_state(const Solver& s) {
    bool ok = true;
    s.particles().for_each_column([&](auto, const auto& column) {
        for (const auto& v : column) {
            if constexpr (std::is_floating_point_v<std::decay_t<decltype(v)>>) ok = ok && std::isfinite(v);
            else if constexpr (requires { v.allFinite(); }) ok = ok && v.allFinite();
        }
    });
    return ok;
}

[[noreturn]] inline void finding(const std::string& what) {
    std::fprintf(stderr, "fuzz: %s\n", what.c_str());
    std::abort();
}

}  // namespace fuzz
