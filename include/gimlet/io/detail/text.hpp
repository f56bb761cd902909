// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// Small text helpers of the XML writers: exact number formatting and attribute escaping.

#include <array>
#include <charconv>
#include <cstdint>
#include <cstdio>
#include <string>
#include <string_view>
#include <utility>

namespace gimlet::io::detail {

/// The shortest text that reads back to exactly `v` (std::to_chars), so times written to a
/// .vtp or .pvd survive a round trip bit for bit and a resumed series can compare them.
[[nodiscard]] inline std::string exact_text(double v) {
    std::array<char, 32> buf{};
    const auto r = std::to_chars(buf.data(), buf.data() + buf.size(), v);
    return {buf.data(), r.ptr};
}

/// `s` in single quotes, for naming a path or a name in a message. (Built by appending: GCC 12
/// reports a false -Wrestrict on `"'" + std::string`.)
[[nodiscard]] inline std::string quoted(std::string_view s) {
    std::string out;
    out.reserve(s.size() + 2);
    out += '\'';
    out += s;
    out += '\'';
    return out;
}

/// Why `s` cannot stand in an XML 1.0 attribute even escaped, or empty if it can: a control
/// character (XML 1.0 allows none but tab and line ends, and a parser turns those into
/// spaces), or bytes that are not UTF-8 (overlong forms, surrogates, code points above
/// U+10FFFF, U+FFFE and U+FFFF included). VTK's reader (expat) refuses such a file whole.
[[nodiscard]] inline std::string xml_attribute_problem(std::string_view s) {
    auto byte = [&](std::size_t i) { return static_cast<unsigned char>(s[i]); };
    for (std::size_t i = 0; i < s.size();) {
        const unsigned char c = byte(i);
        if (c < 0x20 || c == 0x7f) {
            char hex[8];
            std::snprintf(hex, sizeof hex, "0x%02x", unsigned(c));
            return std::string("a control character (byte ") + hex + ")";
        }
        if (c < 0x80) {
            ++i;
            continue;
        }
        const std::size_t len = (c >> 5) == 0x6 ? 2 : (c >> 4) == 0xe ? 3 : (c >> 3) == 0x1e ? 4 : 0;
        if (len == 0 || i + len > s.size()) return "bytes that are not UTF-8";
        std::uint32_t cp = c & (0xff >> (len + 1));
        for (std::size_t k = 1; k < len; ++k) {
            if ((byte(i + k) >> 6) != 0x2) return "bytes that are not UTF-8";
            cp = (cp << 6) | (byte(i + k) & 0x3f);
        }
        static constexpr std::uint32_t smallest[5] = {0, 0, 0x80, 0x800, 0x10000};
        if (cp < smallest[len] || cp > 0x10ffff || (cp >= 0xd800 && cp <= 0xdfff) || cp == 0xfffe || cp == 0xffff)
            return "bytes that are not UTF-8";
        i += len;
    }
    return {};
}

/// `s` made safe inside a double-quoted XML attribute.
[[nodiscard]] inline std::string xml_escape(std::string_view s) {
    std::string out;
    out.reserve(s.size());
    for (const char c : s) {
        switch (c) {
            case '&': out += "&amp;"; break;
            case '<': out += "&lt;"; break;
            case '>': out += "&gt;"; break;
            case '"': out += "&quot;"; break;
            case '\'': out += "&apos;"; break;
            default: out += c;
        }
    }
    return out;
}

/// The inverse of xml_escape for the five entities it writes.
[[nodiscard]] inline std::string xml_unescape(std::string_view s) {
    static constexpr std::array<std::pair<std::string_view, char>, 5> entities{
        {{"&amp;", '&'}, {"&lt;", '<'}, {"&gt;", '>'}, {"&quot;", '"'}, {"&apos;", '\''}}};
    std::string out;
    out.reserve(s.size());
    for (std::size_t i = 0; i < s.size();) {
        bool replaced = false;
        if (s[i] == '&') {
            for (const auto& [entity, c] : entities) {
                if (s.substr(i, entity.size()) == entity) {
                    out += c;
                    i += entity.size();
                    replaced = true;
                    break;
                }
            }
        }
        if (!replaced) out += s[i++];
    }
    return out;
}

}  // namespace gimlet::io::detail
