// SPDX-License-Identifier: MIT
#pragma once
// What an example's restart needs besides the library's checkpoint: its text outputs cut back to
// where the checkpoint was written (examples' helper, not part of the library).

#include <cstddef>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>

namespace example {

// Keeps the first `keep` lines of a text file (a header counts as one) and drops the rest: a
// resumed run rewrites what the interrupted one wrote after its checkpoint.
inline void keep_lines(const std::filesystem::path& file, std::size_t keep) {
    std::ifstream in(file);
    if (!in)
        throw std::runtime_error("cannot read " + file.string() +
                                 " to continue it after a restart: --output must name the folder of the run that "
                                 "wrote the checkpoint (it holds series.csv and snapshots/), not a fresh one");
    std::string text, line;
    for (std::size_t n = 0; n < keep && std::getline(in, line); ++n) text += line + '\n';
    in.close();
    std::ofstream os(file, std::ios::trunc);
    if (!(os << text)) throw std::runtime_error("cannot rewrite " + file.string());
}

}  // namespace example
