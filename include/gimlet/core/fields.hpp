// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// Particle fields as tag types. A tag names a per-particle quantity and its value type for a
/// given space; storage is keyed by the tag, never by index or by value type. Every policy
/// declares the tags it needs; the particle store holds their union.
///
/// Users add their own fields by writing a tag with the same two members:
/// \code
/// struct damage {
///     template <class S> using type = typename S::real;
///     static constexpr const char* name = "damage";
/// };
/// \endcode
/// An optional `template <class S> static type<S> initial()` gives the value a new particle
/// starts with; without it the value is zero.

#include "gimlet/core/space.hpp"

#include <concepts>
#include <cstdint>
#include <type_traits>

namespace gimlet {

/// A field tag: a value type per space and a name (used in output and error messages).
template <class Tag>
concept Field = requires {
    typename Tag::template type<space<2, double>>;
    typename Tag::template type<space<3, double>>;
    { Tag::name } -> std::convertible_to<const char*>;
};

/// True if Tag is a field tag (gimlet::Field); otherwise the compiler stops here with one
/// message per missing requirement: `static_assert(gimlet::check_field<my_field>());`
template <class Tag>
consteval bool check_field() {
    static_assert(requires { typename Tag::template type<space<2, double>>; } &&
                      requires { typename Tag::template type<space<3, double>>; },
                  "field tag: needs `template <class S> using type = ...;` (the value type per space, e.g. "
                  "`typename S::real` or `typename S::vector`)");
    static_assert(requires {
        { Tag::name } -> std::convertible_to<const char*>;
    }, "field tag: needs `static constexpr const char* name = \"...\";` (used in output and error messages)");
    return Field<Tag>;
}

/// An ordered set of field tags.
template <Field... Tags>
struct field_list {
    /// Number of tags in the list.
    static constexpr std::size_t size = sizeof...(Tags);
};

namespace detail {

template <class List, class Tag>
struct list_contains;
template <class... Ts, class Tag>
struct list_contains<field_list<Ts...>, Tag> : std::bool_constant<(std::is_same_v<Ts, Tag> || ...)> {};

template <class Acc, class... Tags>
struct append_unique;
template <class Acc>
struct append_unique<Acc> {
    using type = Acc;
};
template <class... As, class T, class... Rest>
struct append_unique<field_list<As...>, T, Rest...> {
    using next = std::conditional_t<list_contains<field_list<As...>, T>::value, field_list<As...>,
                                    field_list<As..., T>>;
    using type = typename append_unique<next, Rest...>::type;
};

template <class Acc, class... Lists>
struct union_of;
template <class Acc>
struct union_of<Acc> {
    using type = Acc;
};
template <class Acc, class... Ts, class... Rest>
struct union_of<Acc, field_list<Ts...>, Rest...> {
    using type = typename union_of<typename append_unique<Acc, Ts...>::type, Rest...>::type;
};

template <class T>
struct is_field_list : std::false_type {};
template <class... Ts>
struct is_field_list<field_list<Ts...>> : std::true_type {};

}  // namespace detail

/// True if `List` contains `Tag`.
template <class List, class Tag>
inline constexpr bool contains_field_v = detail::list_contains<List, Tag>::value;

/// The union of several field lists, first occurrence order, no duplicates.
template <class... Lists>
using field_union_t = typename detail::union_of<field_list<>, Lists...>::type;

/// A type is a field list.
template <class T>
concept FieldList = detail::is_field_list<T>::value;

/// A policy declares `using required_fields = field_list<...>;` (for the checkers of each family).
template <class T>
concept declares_required_fields = requires { typename T::required_fields; } && FieldList<typename T::required_fields>;

/// The value a new particle's field starts with: `Tag::initial<S>()` if given, else zero.
template <Field Tag, Space S>
[[nodiscard]] typename Tag::template type<S> field_initial_value() {
    using T = typename Tag::template type<S>;
    if constexpr (requires { { Tag::template initial<S>() } -> std::convertible_to<T>; }) {
        return Tag::template initial<S>();
    } else if constexpr (requires { T::Zero(); }) {
        return T::Zero();
    } else {
        return T{};
    }
}

/// The fields of the core solver, present in every scene.
namespace fields {

/// Position x_p (m).
struct position {
    /// Per particle: an S::vector.
    template <class S> using type = typename S::vector;
    /// The field's name in output files and error messages.
    static constexpr const char* name = "position";
};
/// Velocity v_p (m/s).
struct velocity {
    /// Per particle: an S::vector.
    template <class S> using type = typename S::vector;
    /// The field's name in output files and error messages.
    static constexpr const char* name = "velocity";
};
/// Mass m_p (kg; per unit thickness in 2-D).
struct mass {
    /// Per particle: an S::real.
    template <class S> using type = typename S::real;
    /// The field's name in output files and error messages.
    static constexpr const char* name = "mass";
};
/// Reference volume V_p^0 (m^3; m^2 per unit thickness in 2-D). Current volume is det(F) V^0.
struct volume0 {
    /// Per particle: an S::real.
    template <class S> using type = typename S::real;
    /// The field's name in output files and error messages.
    static constexpr const char* name = "volume0";
};
/// Deformation gradient F_p (in-plane; F_zz = 1 in plane strain).
struct deformation_gradient {
    /// Per particle: an S::matrix (Dim x Dim).
    template <class S> using type = typename S::matrix;
    /// The field's name in output files and error messages.
    static constexpr const char* name = "deformation_gradient";
    /// A new particle starts undeformed: F = I.
    template <class S> static type<S> initial() { return type<S>::Identity(); }
};
/// Cauchy stress sigma_p (Pa), in-plane components.
struct stress {
    /// Per particle: an S::matrix (Dim x Dim).
    template <class S> using type = typename S::matrix;
    /// The field's name in output files and error messages.
    static constexpr const char* name = "stress";
};
/// Out-of-plane Cauchy stress sigma_zz (Pa); only 2-D (plane strain) scenes carry it.
struct stress_zz {
    /// Per particle: an S::real.
    template <class S> using type = typename S::real;
    /// The field's name in output files and error messages.
    static constexpr const char* name = "stress_zz";
};
/// Specific internal energy e (J/kg), integrated from the stress power sigma:D / rho.
struct specific_internal_energy {
    /// Per particle: an S::real.
    template <class S> using type = typename S::real;
    /// The field's name in output files and error messages.
    static constexpr const char* name = "specific_internal_energy";
};
/// Which body the particle belongs to (index into the scene's bodies).
struct body {
    /// Per particle: a std::uint32_t.
    template <class S> using type = std::uint32_t;
    /// The field's name in output files and error messages.
    static constexpr const char* name = "body";
};
/// Initial half-width of the particle's domain per axis (m); GIMP shape functions need it.
struct domain_half_width {
    /// Per particle: an S::vector.
    template <class S> using type = typename S::vector;
    /// The field's name in output files and error messages.
    static constexpr const char* name = "domain_half_width";
};
/// External acceleration b_p (m/s^2) applied to this particle: the solver adds S_ip m_p b_p to
/// the nodal force when the store has this field (e.g. a manufactured-solution body force). Ask
/// for it through the solver's `ExtraFields`; scenes without it pay nothing.
struct external_acceleration {
    /// Per particle: an S::vector.
    template <class S> using type = typename S::vector;
    /// The field's name in output files and error messages.
    static constexpr const char* name = "external_acceleration";
};
/// The hoop stretch F_thetatheta of an axisymmetric particle (axisymmetric_space; r / R in a
/// continuum), the deformation gradient's out-of-plane entry, integrated from the hoop rate
/// L_thetatheta = sum v_ir T_ip (docs/equations.md, "Axisymmetric GIMP"). The volume is
/// det(F) F_thetatheta V^0 (gimlet::jacobian).
struct hoop_stretch {
    /// Per particle: an S::real.
    template <class S> using type = typename S::real;
    /// The field's name in output files and error messages.
    static constexpr const char* name = "hoop_stretch";
    /// A new particle starts unstretched: 1.
    template <class S> static type<S> initial() { return type<S>(1); }
};
/// Which components of the particle's velocity are driven, a loading: bit d set (1 << d) drives
/// component d with fields::driven_velocity's; the particle moves with it along d and sets it
/// on the nodes it weighs (stages::driven_particles; docs/guide.md, "Driving particles").
/// 0: a free particle (the start); all bits of the space's axes: fully driven. Ask for it, with
/// driven_velocity, through the solver's `ExtraFields`; scenes without it pay nothing.
struct driven {
    /// Per particle: a std::uint8_t.
    template <class S> using type = std::uint8_t;
    /// The field's name in output files and error messages.
    static constexpr const char* name = "driven";
};
/// The velocity v_d (m/s) a driven particle (fields::driven) moves with; the user sets it, and
/// may change it between steps (a ramp). Zero at the start.
struct driven_velocity {
    /// Per particle: an S::vector.
    template <class S> using type = typename S::vector;
    /// The field's name in output files and error messages.
    static constexpr const char* name = "driven_velocity";
};
/// Equivalent plastic strain eps_p (accumulated, dimensionless); plasticity policies keep it.
struct plastic_strain {
    /// Per particle: an S::real.
    template <class S> using type = typename S::real;
    /// The field's name in output files and error messages.
    static constexpr const char* name = "plastic_strain";
};
/// Plastic work per unit mass w_p = int Y d eps_p / rho (J/kg); plasticity policies keep it,
/// the reference paper's Mie-Grueneisen variant reads it.
struct plastic_work {
    /// Per particle: an S::real.
    template <class S> using type = typename S::real;
    /// The field's name in output files and error messages.
    static constexpr const char* name = "plastic_work";
};
/// Volumetric compression rate -tr D of the particle's last update where it compressed, else 0
/// (1/s); viscosity::bulk keeps it for the stable time step.
struct compression_rate {
    /// Per particle: an S::real.
    template <class S> using type = typename S::real;
    /// The field's name in output files and error messages.
    static constexpr const char* name = "compression_rate";
};
/// Temperature T (K); only scenes with a thermal policy carry it.
struct temperature {
    /// Per particle: an S::real.
    template <class S> using type = typename S::real;
    /// The field's name in output files and error messages.
    static constexpr const char* name = "temperature";
};

}  // namespace fields

/// The fields every scene has. 2-D adds the out-of-plane stress of plane strain (the hoop
/// stress sigma_thetatheta in an axisymmetric space, which adds the hoop stretch too).
template <Space S>
using core_fields = std::conditional_t<
    is_axisymmetric_v<S>,
    field_list<fields::position, fields::velocity, fields::mass, fields::volume0,
               fields::deformation_gradient, fields::stress, fields::stress_zz,
               fields::specific_internal_energy, fields::body, fields::hoop_stretch>,
    std::conditional_t<
    S::dim == 2,
    field_list<fields::position, fields::velocity, fields::mass, fields::volume0,
               fields::deformation_gradient, fields::stress, fields::stress_zz,
               fields::specific_internal_energy, fields::body>,
    field_list<fields::position, fields::velocity, fields::mass, fields::volume0,
               fields::deformation_gradient, fields::stress, fields::specific_internal_energy,
               fields::body>>>;

}  // namespace gimlet
