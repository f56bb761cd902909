// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// Structure-of-arrays particle storage keyed by field tag.

#include "gimlet/core/fields.hpp"

#include <cstddef>
#include <tuple>
#include <vector>

namespace gimlet {

/// Particle storage, defined for a field_list of tags (the specialisation below).
template <Space S, FieldList Fields>
class particle_store;

/// A handle to one particle of a store: `p.get<fields::velocity>()` is a reference to that
/// particle's velocity. Policies receive particles through it, so they are written once for
/// any store that has the fields they declared.
template <class Store>
class particle_ref {
public:
    /// The store's space.
    using space_type = typename Store::space_type;
    /// The store's field_list.
    using fields_type = typename Store::fields_type;
    /// True if the store has field Tag.
    template <class Tag>
    static constexpr bool has = Store::template has<Tag>;

    /// Particle `index` of `store` (no bounds check; the store must outlive the handle).
    constexpr particle_ref(Store& store, std::size_t index) noexcept : store_(&store), index_(index) {}

    /// A reference to this particle's value of field Tag (const through a const store).
    template <class Tag>
        requires(Store::template has<Tag>)
    [[nodiscard]] decltype(auto) get() const noexcept {
        return store_->template column<Tag>()[index_];
    }
    /// The particle's index in its store.
    [[nodiscard]] std::size_t index() const noexcept { return index_; }

private:
    Store* store_;
    std::size_t index_;
};

/// Particle storage: one contiguous column per field tag in `Fields`.
/// \tparam S      the space (dimension, scalar type).
/// \tparam Fields the field_list of tags the scene needs (the union of the policies' lists).
template <Space S, Field... Tags>
class particle_store<S, field_list<Tags...>> {
public:
    /// The space S.
    using space_type = S;
    /// The field_list of the columns.
    using fields_type = field_list<Tags...>;
    /// True if the store has a column for field Tag.
    template <class Tag>
    static constexpr bool has = contains_field_v<fields_type, Tag>;

    /// The whole column of a field. Columns are addressed by the tag's position, so two tags
    /// with the same value type never collide.
    template <class Tag>
        requires has<Tag>
    [[nodiscard]] auto& column() noexcept {
        return std::get<index_of<Tag>()>(columns_);
    }
    /// The whole column of a field, read-only.
    template <class Tag>
        requires has<Tag>
    [[nodiscard]] const auto& column() const noexcept {
        return std::get<index_of<Tag>()>(columns_);
    }

    /// Number of particles.
    [[nodiscard]] std::size_t size() const noexcept { return size_; }
    /// True if the store has no particles.
    [[nodiscard]] bool empty() const noexcept { return size_ == 0; }

    /// Append one particle with every field at its initial value; returns its index.
    std::size_t add() {
        (std::get<index_of<Tags>()>(columns_).push_back(field_initial_value<Tags, S>()), ...);
        return size_++;
    }
    /// n particles: the first min(n, size()) kept, any new ones with every field at its initial
    /// value.
    void resize(std::size_t n) {
        (std::get<index_of<Tags>()>(columns_).resize(n, field_initial_value<Tags, S>()), ...);
        size_ = n;
    }
    /// Reserve room for n particles in every column.
    void reserve(std::size_t n) { (std::get<index_of<Tags>()>(columns_).reserve(n), ...); }
    /// Give back the room beyond size() in every column (after the store shrank).
    void shrink_to_fit() { (std::get<index_of<Tags>()>(columns_).shrink_to_fit(), ...); }

    /// A handle to particle i (no bounds check).
    [[nodiscard]] particle_ref<particle_store> operator[](std::size_t i) noexcept { return {*this, i}; }
    /// A read-only handle to particle i (no bounds check).
    [[nodiscard]] particle_ref<const particle_store> operator[](std::size_t i) const noexcept {
        return {*this, i};
    }

    /// Apply `f(tag_value, column)` to every column (for I/O and checkpoints).
    template <class F>
    void for_each_column(F&& f) {
        (f(Tags{}, std::get<index_of<Tags>()>(columns_)), ...);
    }
    /// Apply `f(tag_value, column)` to every column, read-only.
    template <class F>
    void for_each_column(F&& f) const {
        (f(Tags{}, std::get<index_of<Tags>()>(columns_)), ...);
    }

private:
    template <class Tag>
    static constexpr std::size_t index_of() {
        std::size_t i = 0, found = sizeof...(Tags);
        ((std::is_same_v<Tag, Tags> ? (found = i, ++i) : ++i), ...);
        return found;
    }
    std::tuple<std::vector<typename Tags::template type<S>>...> columns_;
    std::size_t size_ = 0;
};

}  // namespace gimlet
