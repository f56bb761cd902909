// SPDX-License-Identifier: MIT
// io/csv.hpp: numbers written through exact_numbers read back bit for bit, in the shortest text.
#include <gimlet/io/csv.hpp>

#include <catch2/catch.hpp>

#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

TEST_CASE("exact_numbers: every double reads back exactly, in its shortest text", "[io]") {
    std::ostringstream os;
    os.precision(3);  // ignored for floating-point values once exact_numbers is on
    gimlet::io::exact_numbers(os);
    const std::vector<double> values = {0.1,     1.0 / 3.0, 300.0, -2.5e-7, 1e-300, 6.02214076e23,
                                        4.9e-324, std::numeric_limits<double>::max(), -0.0};
    for (double v : values) os << v << ',';
    os << 0.1f << ',' << 42 << ',' << std::uint64_t(7) << ",text";
    const std::string text = os.str();
    std::istringstream in(text);
    std::string cell;
    std::vector<std::string> cells;
    while (std::getline(in, cell, ',')) cells.push_back(cell);
    REQUIRE(cells.size() == values.size() + 4);
    for (std::size_t k = 0; k < values.size(); ++k) {
        INFO(cells[k]);
        CHECK(std::bit_cast<std::uint64_t>(std::strtod(cells[k].c_str(), nullptr)) == std::bit_cast<std::uint64_t>(values[k]));
    }
    CHECK(cells[0] == "0.1");    // shortest, where precision 17 would write 0.10000000000000001
    CHECK(cells[2] == "300");
    CHECK(float(std::strtod(cells[values.size()].c_str(), nullptr)) == 0.1f);  // a float comes back as itself
    CHECK(cells[values.size() + 1] == "42");
    CHECK(cells[values.size() + 2] == "7");
    CHECK(cells[values.size() + 3] == "text");
}

TEST_CASE("exact_numbers: infinities and NaN are written as words a CSV reader takes", "[io]") {
    std::ostringstream os;
    gimlet::io::exact_numbers(os);
    os << std::numeric_limits<double>::infinity() << ',' << -std::numeric_limits<double>::infinity() << ','
       << std::numeric_limits<double>::quiet_NaN();
    CHECK(os.str() == "inf,-inf,nan");
}
