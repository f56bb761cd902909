// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// The solver types that several test families use, compiled once for the whole suite instead of
/// once in every family's unit (docs/testing.md, "Solver types compiled once"). Every family's
/// unit includes this header first (tests/CMakeLists.txt): its explicit instantiation
/// declarations keep the unit from generating these types' members, and
/// tests/instantiations_*.cpp define them (library gimlet_test_solvers). Adding a type here
/// changes no test; it only moves where the type's code is compiled.

#include <gimlet/gimlet.hpp>

/// The list: ELASTIC(contact, partition) and HMX(contact, partition) name a 2-D double uGIMP
/// solver of gimlet::elastic_material or of gimlet::materials::hmx_material<> (its defaults).
/// Two macro arguments, so that each of the two defining files can take its half of the list.
#define GIMLET_TESTS_SHARED_SOLVERS(ELASTIC, HMX)                                                \
    ELASTIC(single_field, by_body)                                                                \
    ELASTIC(distance, by_body)                                                                    \
    ELASTIC(bardenhagen, by_body)                                                                 \
    HMX(single_field, by_body)                                                                    \
    HMX(distance, by_body)                                                                        \
    HMX(bardenhagen, by_body)                                                                     \
    HMX(distance, self_contact)

#define GIMLET_TESTS_SOLVER_TYPE(MATERIAL, CONTACT, PARTITION)                                    \
    gimlet::solver<gimlet::space<2, double>, gimlet::shape::ugimp, MATERIAL, gimlet::contact::CONTACT, \
                   gimlet::field_list<>, gimlet::multi_field::PARTITION>

#define GIMLET_TESTS_EXTERN_ELASTIC(C, P) extern template class GIMLET_TESTS_SOLVER_TYPE(gimlet::elastic_material, C, P);
#define GIMLET_TESTS_EXTERN_HMX(C, P) \
    extern template class GIMLET_TESTS_SOLVER_TYPE(gimlet::materials::hmx_material<>, C, P);
GIMLET_TESTS_SHARED_SOLVERS(GIMLET_TESTS_EXTERN_ELASTIC, GIMLET_TESTS_EXTERN_HMX)
#undef GIMLET_TESTS_EXTERN_ELASTIC
#undef GIMLET_TESTS_EXTERN_HMX
