// SPDX-License-Identifier: MIT
// Catch2's main(), compiled once into gimlet_catch_main and linked by every test executable.
#define CATCH_CONFIG_MAIN
#include <catch2/catch.hpp>
