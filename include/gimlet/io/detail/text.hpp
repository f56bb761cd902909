// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// Small text helpers of the XML writers: exact number formatting and attribute escaping.

#include <array>
#include <charconv>
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
