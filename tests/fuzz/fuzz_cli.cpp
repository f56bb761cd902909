// SPDX-License-Identifier: MIT
// libFuzzer harness: the examples' command-line parser (examples/common/cli.hpp) with
// cavity_collapse's scene flags (examples/cavity_collapse/flags.hpp) and its validation, on
// arbitrary argument lists (the input split at NUL bytes). Every list must parse or be refused
// by name (std::invalid_argument or gimlet::invalid_parameter). Left out: --help (it prints and
// exits, by design) and the file flags main reads (--output creates directories).
// docs/robustness.md, "Fuzzing".
#include "fuzz_common.hpp"

#include "cavity_collapse/flags.hpp"

#include <string>
#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    std::vector<std::string> args{"cavity_collapse"};
    std::string current;
    for (std::size_t i = 0; i < size && args.size() < 64; ++i) {
        if (data[i] == 0) {
            args.push_back(current);
            current.clear();
        } else {
            current.push_back(char(data[i]));
        }
    }
    if (!current.empty() || (size > 0 && data[size - 1] == 0)) args.push_back(current);
    for (const auto& a : args)
        if (a == "--help" || a == "-h") return 0;
    std::vector<char*> argv;
    for (auto& a : args) argv.push_back(a.data());
    fuzz::expect_clean<true>([&] {
        example::cli cli(static_cast<int>(argv.size()), argv.data(), cavity_collapse::usage);
        const auto s = cavity_collapse::read_settings(cli);
        cli.finish();
        cavity_collapse::validate(s);
    });
    return 0;
}
