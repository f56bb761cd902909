// SPDX-License-Identifier: MIT
// The HMX half of tests/instantiations.hpp's list, defined once for every test family (two
// files, so that the two halves compile side by side).
#include "instantiations.hpp"

#define GIMLET_TESTS_DEFINE(C, P) template class GIMLET_TESTS_SOLVER_TYPE(gimlet::presets::hmx_material<>, C, P);
#define GIMLET_TESTS_SKIP(C, P)
GIMLET_TESTS_SHARED_SOLVERS(GIMLET_TESTS_SKIP, GIMLET_TESTS_DEFINE)
#undef GIMLET_TESTS_DEFINE
#define GIMLET_TESTS_DEFINE(C, P) template class GIMLET_TESTS_CORE_TYPE(gimlet::presets::hmx_material<>, C, P);
GIMLET_TESTS_SHARED_CORES(GIMLET_TESTS_SKIP, GIMLET_TESTS_DEFINE)
