// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// Output files that are complete or absent: written under a temporary name in the same
/// directory, checked, then renamed over the final name.

#include "gimlet/core/error.hpp"
#include "gimlet/io/detail/text.hpp"

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <system_error>
#if __has_include(<unistd.h>)
#include <unistd.h>
#endif

namespace gimlet::io::detail {

/// The error for an output path that cannot be written.
[[nodiscard]] inline invalid_parameter unwritable(const std::string& what, const std::filesystem::path& path,
                                                  const std::string& why) {
    return invalid_parameter(what, detail::quoted(path.string()),
                             "a writable file (its directory must exist and allow writing; " + why + ")");
}

/// Remove a temporary file that will not be used; a failure to remove it must not hide the
/// error that made it useless.
inline void discard(const std::filesystem::path& tmp) noexcept {
    std::error_code ignored;
    std::filesystem::remove(tmp, ignored);
}

/// The temporary name write_atomically writes `path` under: `<path>.tmp.<process id>` (where the
/// system has process ids), of this process alone, so that processes writing the same path at
/// once (each its complete file) never rename each other's half-written one.
[[nodiscard]] inline std::filesystem::path temporary_for(const std::filesystem::path& path) {
    std::filesystem::path tmp = path;
    tmp += ".tmp";
#if __has_include(<unistd.h>)
    tmp += "." + std::to_string(::getpid());
#endif
    return tmp;
}

/// Write `path` through `fill(std::ofstream&)`. The bytes go to temporary_for(path) first and are
/// renamed over `path` only once the stream reported no error after closing, so a reader (or a
/// run resumed after a crash) never finds a half-written file under the final name. rename()
/// within one directory is atomic on POSIX file systems; it does not guard against power loss
/// (no fsync: the standard library has none).
template <class Fill>
void write_atomically(const std::filesystem::path& path, const std::string& what, Fill&& fill) {
    if (path.empty()) throw unwritable(what, path, "the path is empty");
    const std::filesystem::path tmp = temporary_for(path);
    {
        std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
        if (!out) throw unwritable(what, path, "could not create " + tmp.filename().string());
        bool written = false;
        try {
            fill(out);
            out.flush();
            written = bool(out);
            out.close();
        } catch (...) {
            out.close();
            discard(tmp);
            throw;
        }
        if (!written || out.fail()) {
            discard(tmp);
            throw unwritable(what, path, "writing failed, e.g. the disk is full");
        }
    }
    std::error_code ec;
    std::filesystem::rename(tmp, path, ec);
    if (ec) {
        discard(tmp);
        throw unwritable(what, path, "renaming the finished file failed: " + ec.message());
    }
}

/// Write the object representation of `n` values (the host's byte order).
template <class T>
void write_raw(std::ostream& out, const T* data, std::size_t n) {
    out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(n * sizeof(T)));
}

/// 64-bit FNV-1a (Fowler, Noll & Vo): a few lines, no table, and any flipped or missing byte
/// changes it; it detects damage, it is not a defence against tampering.
class fnv1a64 {
public:
    void add(const char* data, std::size_t n) noexcept {
        for (std::size_t i = 0; i < n; ++i) {
            h_ ^= static_cast<unsigned char>(data[i]);
            h_ *= 0x100000001b3ULL;
        }
    }
    [[nodiscard]] std::uint64_t value() const noexcept { return h_; }

private:
    std::uint64_t h_ = 0xcbf29ce484222325ULL;
};

}  // namespace gimlet::io::detail
