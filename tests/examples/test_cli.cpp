// SPDX-License-Identifier: MIT
// The examples' flag parser (examples/common/cli.hpp): every bad flag is refused with a message
// naming the flag and its valid range. tests/examples/cli.cmake runs the example binaries
// themselves with bad flags and checks that they exit non-zero with these messages.
#include "common/cli.hpp"

#include <catch2/catch.hpp>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

using Catch::Matchers::Contains;
namespace fs = std::filesystem;

namespace {

/// A parser over these arguments (program name first, as in argv).
example::cli parse(std::vector<std::string> args) {
    args.insert(args.begin(), "prog");
    std::vector<char*> argv;
    for (auto& a : args) argv.push_back(a.data());
    return example::cli(static_cast<int>(argv.size()), argv.data(), "usage: prog [--cell H] [--output DIR]");
}

/// A fresh scratch directory under the system temporary directory, removed at the end.
struct scratch {
    fs::path dir = fs::temp_directory_path() /
                   ("gimlet_test_cli_" + std::to_string(std::chrono::steady_clock::now().time_since_epoch().count()));
    scratch() { fs::create_directories(dir); }
    ~scratch() {
        std::error_code ec;
        fs::remove_all(dir, ec);
    }
};

}  // namespace

TEST_CASE("real flags: accepted in range, refused outside it naming the flag and the range", "[examples][cli]") {
    CHECK(parse({"--cell", "0.25"}).real("cell", 0.1, 0.0, 1.0) == 0.25);
    CHECK(parse({"--cell=0.25"}).real("cell", 0.1, 0.0, 1.0) == 0.25);
    CHECK(parse({}).real("cell", 0.1, 0.0, 1.0) == 0.1);
    CHECK(parse({"--velocity", "-5"}).real("velocity", 1.0, -10.0, 10.0) == -5.0);
    CHECK(parse({"--threads", "0"}).real("threads", 1.0, 0.0, 256.0, true) == 0.0);
    for (const std::string bad : {"0", "-0.1", "1.5", "nan", "inf", "-inf", "0.1mm", "abc", "", "1e999"}) {
        INFO("--cell '" << bad << "'");
        CHECK_THROWS_AS(parse({"--cell", bad}).real("cell", 0.1, 0.0, 1.0), std::invalid_argument);
        CHECK_THROWS_WITH(parse({"--cell", bad}).real("cell", 0.1, 0.0, 1.0),
                          Contains("--cell = ") && Contains(" is invalid; valid range: (0, 1]"));
    }
    CHECK_THROWS_WITH(parse({"--threads", "-1"}).real("threads", 0.0, 0.0, 256.0, true),
                      Contains("--threads = -1 is invalid; valid range: [0, 256]"));
}

TEST_CASE("whole-number flags: a fraction or a word is refused, not truncated", "[examples][cli]") {
    CHECK(parse({"--threads", "2"}).integer("threads", 0, 0, 256) == 2);
    CHECK(parse({}).integer("threads", 3, 0, 256) == 3);
    for (const std::string bad : {"2.5", "-1", "257", "two", "", "2x"}) {
        INFO("--threads '" << bad << "'");
        CHECK_THROWS_WITH(parse({"--threads", bad}).integer("threads", 0, 0, 256),
                          Contains("--threads = ") && Contains(" is invalid; valid: a whole number in [0, 256]"));
    }
}

TEST_CASE("malformed command lines are refused", "[examples][cli]") {
    CHECK_THROWS_WITH(parse({"--cell"}), Contains("flag --cell needs a value") && Contains("usage: prog"));
    CHECK_THROWS_WITH(parse({"--cell", "0.1", "--cell", "0.2"}), Contains("flag --cell is given more than once"));
    CHECK_THROWS_WITH(parse({"--cell=0.1", "--cell", "0.2"}), Contains("flag --cell is given more than once"));
    CHECK_THROWS_WITH(parse({"0.1"}), Contains("unexpected argument '0.1'"));
    CHECK_THROWS_WITH(parse({"-c", "0.1"}), Contains("unexpected argument '-c'"));
    CHECK_THROWS_WITH(parse({"--", "0.1"}), Contains("unexpected argument '--'"));
    // A flag nobody reads is an error, never ignored.
    auto args = parse({"--cell", "0.2", "--cel", "0.3"});
    (void)args.real("cell", 0.1, 0.0, 1.0);
    CHECK_THROWS_WITH(args.finish(), Contains("unknown flag --cel") && Contains("usage: prog"));
    auto fine = parse({"--cell", "0.2"});
    (void)fine.real("cell", 0.1, 0.0, 1.0);
    CHECK_NOTHROW(fine.finish());
}

TEST_CASE("choice flags list the valid words", "[examples][cli]") {
    CHECK(parse({"--scheme", "usl"}).choice("scheme", "usf", {"usf", "musl", "usl"}) == "usl");
    CHECK_THROWS_WITH(parse({"--scheme", "USL"}).choice("scheme", "usf", {"usf", "musl", "usl"}),
                      Contains("--scheme = USL is invalid; valid: usf|musl|usl"));
}

TEST_CASE("output directories are created, or refused with the reason", "[examples][cli]") {
    scratch s;
    const fs::path nested = s.dir / "a" / "b";
    CHECK(parse({"--output", nested.string()}).directory("output", "unused") == nested);
    CHECK(fs::is_directory(nested));
    CHECK(fs::is_empty(nested));  // the write probe is removed

    const fs::path file = s.dir / "a_file";
    std::ofstream(file) << "not a directory\n";
    CHECK_THROWS_WITH(parse({"--output", file.string()}).directory("output", "unused"),
                      Contains("--output = " + file.string() + " is invalid; valid: a directory that can be created and written") &&
                          Contains("it exists and is not a directory"));
    CHECK_THROWS_WITH(parse({"--output", (file / "out").string()}).directory("output", "unused"),
                      Contains("--output = " + (file / "out").string() + " is invalid") && Contains("cannot create it"));
    CHECK_THROWS_WITH(parse({"--output", ""}).directory("output", "unused"),
                      Contains("--output = '' is invalid") && Contains("empty path"));
}
