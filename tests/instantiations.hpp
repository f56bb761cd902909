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

#include <type_traits>

/// The list: ELASTIC(contact, partition) and HMX(contact, partition) name a 2-D double uGIMP
/// solver of gimlet::elastic_material or of gimlet::presets::hmx_material<> (its defaults).
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

/// Their contact-independent parts (gimlet::solver_core), which hold most of a solver type's code:
/// one per material, field list and partition. A law of the solvers' list with the same fields
/// as one of this list's shares its core (Bardenhagen's and the distance law: no fields of
/// their own). Named by a contact policy of the solvers' list; checked below.
#define GIMLET_TESTS_SHARED_CORES(ELASTIC, HMX)                                                  \
    ELASTIC(single_field, by_body)                                                                \
    ELASTIC(distance, by_body)                                                                    \
    HMX(single_field, by_body)                                                                    \
    HMX(distance, by_body)                                                                        \
    HMX(distance, self_contact)

#define GIMLET_TESTS_CORE_TYPE(MATERIAL, CONTACT, PARTITION)                                      \
    gimlet::solver_core<gimlet::space<2, double>, gimlet::shape::ugimp, MATERIAL,                 \
                        gimlet::solver_fields_t<gimlet::space<2, double>, gimlet::shape::ugimp, MATERIAL, \
                                                gimlet::contact::CONTACT, gimlet::field_list<>,   \
                                                gimlet::multi_field::PARTITION>,                  \
                        gimlet::contact::CONTACT::multi_field, gimlet::multi_field::PARTITION>

#define GIMLET_TESTS_EXTERN_ELASTIC(C, P) extern template class GIMLET_TESTS_SOLVER_TYPE(gimlet::elastic_material, C, P);
#define GIMLET_TESTS_EXTERN_HMX(C, P) \
    extern template class GIMLET_TESTS_SOLVER_TYPE(gimlet::presets::hmx_material<>, C, P);
GIMLET_TESTS_SHARED_SOLVERS(GIMLET_TESTS_EXTERN_ELASTIC, GIMLET_TESTS_EXTERN_HMX)
#undef GIMLET_TESTS_EXTERN_ELASTIC
#undef GIMLET_TESTS_EXTERN_HMX
#define GIMLET_TESTS_EXTERN_ELASTIC(C, P) extern template class GIMLET_TESTS_CORE_TYPE(gimlet::elastic_material, C, P);
#define GIMLET_TESTS_EXTERN_HMX(C, P) \
    extern template class GIMLET_TESTS_CORE_TYPE(gimlet::presets::hmx_material<>, C, P);
GIMLET_TESTS_SHARED_CORES(GIMLET_TESTS_EXTERN_ELASTIC, GIMLET_TESTS_EXTERN_HMX)
#undef GIMLET_TESTS_EXTERN_ELASTIC
#undef GIMLET_TESTS_EXTERN_HMX

// Every solver of the list has its core in the cores' list (else its core would be compiled in
// every unit that uses it).
namespace gimlet_tests_instantiations {
#define GIMLET_TESTS_CORE_ELASTIC(C, P) GIMLET_TESTS_CORE_TYPE(gimlet::elastic_material, C, P),
#define GIMLET_TESTS_CORE_HMX(C, P) GIMLET_TESTS_CORE_TYPE(gimlet::presets::hmx_material<>, C, P),
template <class... T>
struct type_list {};
using shared_cores = type_list<GIMLET_TESTS_SHARED_CORES(GIMLET_TESTS_CORE_ELASTIC, GIMLET_TESTS_CORE_HMX) void>;
#undef GIMLET_TESTS_CORE_ELASTIC
#undef GIMLET_TESTS_CORE_HMX
template <class Core, class... Listed>
constexpr bool listed(type_list<Listed...>*) {
    return (std::is_same_v<Core, Listed> || ...);
}
#define GIMLET_TESTS_LISTED_ELASTIC(C, P)                                                            \
    static_assert(listed<GIMLET_TESTS_SOLVER_TYPE(gimlet::elastic_material, C, P)::core_type>(          \
                      static_cast<shared_cores*>(nullptr)),                                          \
                  "tests/instantiations.hpp: add the core of ELASTIC(" #C ", " #P ") to the cores' list");
#define GIMLET_TESTS_LISTED_HMX(C, P)                                                                \
    static_assert(listed<GIMLET_TESTS_SOLVER_TYPE(gimlet::presets::hmx_material<>, C, P)::core_type>( \
                      static_cast<shared_cores*>(nullptr)),                                          \
                  "tests/instantiations.hpp: add the core of HMX(" #C ", " #P ") to the cores' list");
GIMLET_TESTS_SHARED_SOLVERS(GIMLET_TESTS_LISTED_ELASTIC, GIMLET_TESTS_LISTED_HMX)
#undef GIMLET_TESTS_LISTED_ELASTIC
#undef GIMLET_TESTS_LISTED_HMX
}  // namespace gimlet_tests_instantiations
