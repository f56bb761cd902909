// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// The solver on many processes (a gimlet::distributed_solver given solver_options::processes),
/// and the seeding and gathering every solver has: each process the particles whose
/// stencils start in its slabs, in ordinal order, so that every slab pass sums each node in the
/// one-process order (processes::after_colour) and the run gives one process's bits.

#include "gimlet/core/describe.hpp"
#include "gimlet/solver/core.hpp"

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <functional>
#include <limits>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

namespace gimlet {

template <Space S, shape::Shape Sh, Material M, FieldList Fields, bool MultiField, multi_field::Partition Part, bool Distributed>
void solver_core<S, Sh, M, Fields, MultiField, Part, Distributed>::together(const std::function<void()>& f) {
    // As processes::together, but where several processes fail the lowest-numbered particle's
    // failure is the one reported, as one process reports it, named by its ordinal.
    std::string message;
    bool failed = false, bad_input = false;
    double key = std::numeric_limits<double>::max();  // a failure that names no particle
    try {
        f();
    } catch (const processes_stopped&) {
        throw;  // agreed on every process already
    } catch (const invalid_parameter& e) {
        failed = true, bad_input = true, message = with_ordinal(e.what(), &key);
    } catch (const std::exception& e) {
        failed = true, message = with_ordinal(e.what(), &key);
    } catch (...) {
        failed = true, message = "an exception that is not a std::exception";
    }
    auto* p = &many();
    detail::agree([&](double x) { return p->min(x); }, [&](const std::string* text) { return p->share(text); },
                  p->rank(), p->size(), failed, key, message, bad_input);
}

template <Space S, shape::Shape Sh, Material M, FieldList Fields, bool MultiField, multi_field::Partition Part, bool Distributed>
std::string solver_core<S, Sh, M, Fields, MultiField, Part, Distributed>::with_ordinal(const std::string& message, double* key) const {
    // describe_particle's "particle <index> (body": the index in this process's store.
    const auto named = detail::find_named_particle(message);
    if (!named || named->index >= particles_.size()) return message;
    const std::uint64_t n = ordinal(named->index);
    if (key) *key = double(n);  // ordinals are below 2^53: exact
    return message.substr(0, named->at) + std::to_string(n) + message.substr(named->at + named->digits);
}

template <Space S, shape::Shape Sh, Material M, FieldList Fields, bool MultiField, multi_field::Partition Part, bool Distributed>
void solver_core<S, Sh, M, Fields, MultiField, Part, Distributed>::count_health_across() {
    auto& p = many();
    detail::pending_health& pending = pending_health_;
    // Whether every process has the guards of this step (a process whose particles were touched
    // since has none: then none counts them, as one process would not).
    const bool mine = pending.valid && pending.step == steps_;
    pending.valid = false;
    if (p.min(mine ? 1.0 : 0.0) == 0) return;
    for (std::size_t k = 0; k < health_events::kinds; ++k) {
        const std::uint64_t count = p.sum(pending.count[k]);
        if (count == 0) continue;
        health_.count[k] += count;
        if (!health_.first[k].empty()) continue;
        // The lowest ordinal that met the guard (ordinals are below 2^53: exact as doubles).
        const double first = pending.count[k] ? double(ordinal(std::size_t(pending.first[k]))) : 1e300;
        const double lowest = p.min(first);
        const std::string text =
            pending.count[k] && first == lowest
                ? with_ordinal(describe_particle(particles_[std::size_t(pending.first[k])], steps_, double(time_)))
                : std::string();
        health_.first[k] = p.share(pending.count[k] && first == lowest ? &text : nullptr) + ": " + health_events::what[k];
    }
}

template <Space S, shape::Shape Sh, Material M, FieldList Fields, bool MultiField, multi_field::Partition Part, bool Distributed>
void solver_core<S, Sh, M, Fields, MultiField, Part, Distributed>::set_window() {
    auto& p = many();
    const int slabs = slabs_.slabs(), me = p.rank();
    int first = slabs, last = -1;  // this process's slabs [first, last]
    for (int s = 0; s < slabs; ++s)
        if (p.owner(s) == me) first = std::min(first, s), last = std::max(last, s);
    const auto per_row = std::size_t(grid_.stride(dim - 1));
    window_.clear();
    if (last < 0) return;
    // The band above: the first rows of the next slab (on a periodic axis, of slab 0 after the last).
    int end = slabs_.end_row(last);
    if (last + 1 < slabs) end = std::min(slabs_.end_row(last + 1), end + slabs_.slab_rows);
    window_.push_back({std::size_t(slabs_.first_row(first)) * per_row, std::size_t(end) * per_row});
    if (last + 1 == slabs && slabs_.periodic() && slabs > 1 && first > 0)
        window_.insert(window_.begin(), {0, std::size_t(std::min(slabs_.end_row(0), slabs_.slab_rows)) * per_row});
}

// A particle's record for another process: its ordinal, then each column's value, byte for byte.
template <Space S, shape::Shape Sh, Material M, FieldList Fields, bool MultiField, multi_field::Partition Part, bool Distributed>
std::size_t solver_core<S, Sh, M, Fields, MultiField, Part, Distributed>::record_bytes() const {
    std::size_t bytes = sizeof(std::uint64_t);
    particles_.for_each_column([&](auto, const auto& column) { bytes += sizeof(column[0]); });
    return bytes;
}

template <Space S, shape::Shape Sh, Material M, FieldList Fields, bool MultiField, multi_field::Partition Part, bool Distributed>
void solver_core<S, Sh, M, Fields, MultiField, Part, Distributed>::append_record(std::size_t i, std::size_t record,
                                                                    std::vector<std::byte>& out) const {
    std::size_t at = out.size();
    out.resize(at + record);
    std::memcpy(out.data() + at, &ordinal_[i], sizeof(std::uint64_t));
    at += sizeof(std::uint64_t);
    particles_.for_each_column([&](auto, const auto& column) {
        std::memcpy(out.data() + at, &column[i], sizeof(column[i]));
        at += sizeof(column[i]);
    });
}

template <Space S, shape::Shape Sh, Material M, FieldList Fields, bool MultiField, multi_field::Partition Part, bool Distributed>
void solver_core<S, Sh, M, Fields, MultiField, Part, Distributed>::read_record(const std::byte* record, store_type& to, std::size_t k) {
    std::size_t at = sizeof(std::uint64_t);
    to.for_each_column([&](auto, auto& column) {
        std::memcpy(static_cast<void*>(&column[k]), record + at, sizeof(column[k]));
        at += sizeof(column[k]);
    });
}

template <Space S, shape::Shape Sh, Material M, FieldList Fields, bool MultiField, multi_field::Partition Part, bool Distributed>
void solver_core<S, Sh, M, Fields, MultiField, Part, Distributed>::copy_particle(const store_type& from, std::size_t i, store_type& to,
                                                                    std::size_t k) {
    from.for_each_column([&](auto tag, const auto& column) { to.template column<decltype(tag)>()[k] = column[i]; });
}

template <Space S, shape::Shape Sh, Material M, FieldList Fields, bool MultiField, multi_field::Partition Part, bool Distributed>
void solver_core<S, Sh, M, Fields, MultiField, Part, Distributed>::seed(const scene::scene<S, M>& sc) {
    // One call for one process and many (a hook that keeps every particle on one process), so
    // that the seeding is compiled once.
    auto* p = processes();
    ordinal_.clear();
    std::uint64_t seeded = 0;
    detail::seed_particles(sc, grid_, particles_, [&](store_type&, std::size_t first) {
        if constexpr (!Distributed) return (void)first;  // a plain solver compiles no thinning
        if (!p) return;
        const std::size_t batch = particles_.size() - first;
        keep_own_from(first, seeded);
        seeded += batch;
    });
    if (p) compute_stencils();
}

template <Space S, shape::Shape Sh, Material M, FieldList Fields, bool MultiField, multi_field::Partition Part, bool Distributed>
void solver_core<S, Sh, M, Fields, MultiField, Part, Distributed>::keep_own_particles() {
    ordinal_.clear();
    keep_own_from(0, 0);
    particles_.shrink_to_fit();  // the room the whole run's particles took
    stencils_.resize(particles_.size());
    stencils_.shrink_to_fit();
    compute_stencils();
}

template <Space S, shape::Shape Sh, Material M, FieldList Fields, bool MultiField, multi_field::Partition Part, bool Distributed>
void solver_core<S, Sh, M, Fields, MultiField, Part, Distributed>::keep_own_from(std::size_t first, std::uint64_t ordinal) {
    compute_stencils(first);
    const int me = many().rank();
    std::size_t kept = first;
    for (std::size_t i = first; i < particles_.size(); ++i, ++ordinal) {
        if (many().owner(int(slabs_.slab_of()[i])) != me) continue;
        if (kept != i) copy_particle(particles_, i, particles_, kept);
        ordinal_.push_back(ordinal);
        ++kept;
    }
    particles_.resize(kept);
}

template <Space S, shape::Shape Sh, Material M, FieldList Fields, bool MultiField, multi_field::Partition Part, bool Distributed>
void solver_core<S, Sh, M, Fields, MultiField, Part, Distributed>::migrate() {
    auto& p = many();
    const int me = p.rank();
    const auto ranks = std::size_t(p.size());
    const auto& slab = slabs_.slab_of();
    const std::size_t record = record_bytes();
    std::vector<std::vector<std::byte>> out(ranks);
    std::vector<std::size_t> staying;
    staying.reserve(particles_.size());
    for (std::size_t i = 0; i < particles_.size(); ++i) {
        const int to = p.owner(int(slab[i]));
        if (to == me) {
            staying.push_back(i);
            continue;
        }
        append_record(i, record, out[std::size_t(to)]);
    }
    const auto in = p.all_to_all(out);
    std::size_t arriving = 0;
    for (const auto& bytes : in) arriving += bytes.size() / record;
    if (arriving == 0 && staying.size() == particles_.size()) return;  // nobody moved here
    // The staying particles and the arrivals, merged in ordinal order: (ordinal, source), the
    // source an index into the store, or particles_.size() + k for the k-th arrival.
    std::vector<const std::byte*> arrival;
    arrival.reserve(arriving);
    for (const auto& bytes : in)
        for (std::size_t at = 0; at < bytes.size(); at += record) arrival.push_back(bytes.data() + at);
    std::vector<std::pair<std::uint64_t, std::size_t>> order;
    order.reserve(staying.size() + arrival.size());
    for (std::size_t i : staying) order.push_back({ordinal_[i], i});
    for (std::size_t k = 0; k < arrival.size(); ++k) {
        std::uint64_t n = 0;
        std::memcpy(&n, arrival[k], sizeof n);
        order.push_back({n, particles_.size() + k});
    }
    std::sort(order.begin(), order.end());
    store_type merged;
    merged.resize(order.size());
    for (std::size_t k = 0; k < order.size(); ++k) {
        const std::size_t from = order[k].second;
        if (from < particles_.size()) copy_particle(particles_, from, merged, k);
        else read_record(arrival[from - particles_.size()], merged, k);
    }
    particles_ = std::move(merged);
    ordinal_.resize(order.size());
    for (std::size_t k = 0; k < order.size(); ++k) ordinal_[k] = order[k].first;
    compute_stencils();
}

template <Space S, shape::Shape Sh, Material M, FieldList Fields, bool MultiField, multi_field::Partition Part, bool Distributed>
void solver_core<S, Sh, M, Fields, MultiField, Part, Distributed>::renumber() {
    const std::uint64_t below = many().exclusive_sum(particles_.size());
    for (std::size_t k = 0; k < ordinal_.size(); ++k) ordinal_[k] = below + k;
}

template <Space S, shape::Shape Sh, Material M, FieldList Fields, bool MultiField, multi_field::Partition Part, bool Distributed>
auto solver_core<S, Sh, M, Fields, MultiField, Part, Distributed>::gathered_particles() const -> store_type {
    auto* p = processes();
    if (!p) return particles_;
    const std::size_t record = record_bytes();
    std::vector<std::vector<std::byte>> out(std::size_t(p->size()));
    out[0].reserve(particles_.size() * record);
    for (std::size_t i = 0; i < particles_.size(); ++i) append_record(i, record, out[0]);
    const auto in = p->all_to_all(out);
    store_type whole;
    if (p->rank() != 0) return whole;
    std::size_t total = 0;
    for (const auto& b : in) total += b.size() / record;
    whole.resize(total);
    // Ordinals are 0 .. total - 1: each record goes to its ordinal's place.
    for (const auto& b : in)
        for (std::size_t r = 0; r < b.size(); r += record) {
            std::uint64_t n = 0;
            std::memcpy(&n, b.data() + r, sizeof n);
            read_record(b.data() + r, whole, std::size_t(n));
        }
    return whole;
}

template <Space S, shape::Shape Sh, Material M, FieldList Fields, bool MultiField, multi_field::Partition Part, bool Distributed>
void solver_core<S, Sh, M, Fields, MultiField, Part, Distributed>::replace_particles(store_type whole) {
    particles_ = std::move(whole);  // moved in where the caller gives it up: one copy of the whole run, not two
    state_touched_ = true;
    pending_health_.valid = false;
    if constexpr (Distributed)
        if (processes()) keep_own_particles();
}

template <Space S, shape::Shape Sh, Material M, FieldList Fields, bool MultiField, multi_field::Partition Part, bool Distributed>
template <class Get, class Merge>
void solver_core<S, Sh, M, Fields, MultiField, Part, Distributed>::merge_shared(std::size_t blocks, Get& get, Merge& merge) {
    using value = std::remove_cvref_t<std::invoke_result_t<Get&, std::size_t>>;
    static_assert(std::is_trivially_copyable_v<value>, "across.merge_shared: get(e) returns a value copied byte for byte");
    auto* p = processes();
    if (!p) return;
    const auto bands = p->bands();
    const std::size_t nodes = grid_.size();
    std::vector<std::vector<std::byte>> out(bands.size());
    for (std::size_t b = 0; b < bands.size(); ++b) {
        out[b].resize(blocks * bands[b].count * sizeof(value));
        std::byte* at = out[b].data();
        for (std::size_t k = 0; k < blocks; ++k)
            for (std::size_t node = bands[b].first; node < bands[b].first + bands[b].count; ++node, at += sizeof(value)) {
                const value v = get(k * nodes + node);
                std::memcpy(at, &v, sizeof(value));
            }
    }
    const auto in = p->swap(out);
    for (std::size_t b = 0; b < bands.size(); ++b) {
        // Both processes pass the same blocks of the same band (the exchange sizes them alike).
        if (in[b].size() != out[b].size())
            throw numerical_error("across.merge_shared: the process sharing a band sent " + std::to_string(in[b].size()) +
                                  " bytes for " + std::to_string(out[b].size()) +
                                  ": every process must pass the same number of blocks");
        const std::byte* at = in[b].data();
        for (std::size_t k = 0; k < blocks; ++k)
            for (std::size_t node = bands[b].first; node < bands[b].first + bands[b].count; ++node, at += sizeof(value)) {
                value theirs;
                std::memcpy(&theirs, at, sizeof(value));
                merge(k * nodes + node, std::as_const(theirs));
            }
    }
}

template <Space S, shape::Shape Sh, Material M, FieldList Fields, bool MultiField, multi_field::Partition Part, bool Distributed>
bool solver_core<S, Sh, M, Fields, MultiField, Part, Distributed>::owns_node(std::size_t node) const {
    auto* p = processes();
    if (!p) return true;
    const int row = int(node / std::size_t(grid_.stride(dim - 1)));
    return p->owner(std::min(row / slabs_.slab_rows, slabs_.slabs() - 1)) == p->rank();
}

}  // namespace gimlet
