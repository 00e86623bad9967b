// The runtime library's argument check (internal; not installed): throws
// std::invalid_argument(message) unless `ok`. Two overloads so that the hot paths (radiance
// checks every query) pass literal messages without building a std::string; lists of
// conditions (Condition) for the query checks; a batch's check of all its queries.
#pragma once

#include <array>
#include <cstddef>
#include <stdexcept>
#include <string>
#include <utility>

namespace scatterlut::detail {

inline void require(bool ok, const char *message) {
    if (!ok) throw std::invalid_argument(message);
}

inline void require(bool ok, const std::string &message) {
    if (!ok) throw std::invalid_argument(message);
}

// A check's condition and the message it throws when it fails. A query type lists its
// checks once, as an array of these: the checking call takes them one by one (require_each:
// the first that fails throws), a fast path all at once (all_hold: no branch per check).
struct Condition {
    bool holds;
    const char *message;
};

template <size_t N>
void require_each(const std::array<Condition, N> &conditions) {
    for (const Condition &c : conditions) require(c.holds, c.message);
}

template <size_t N, size_t... I>
inline bool all_hold(const std::array<Condition, N> &conditions, std::index_sequence<I...>) {
    return (conditions[I].holds & ...); // each by a constant index: the array folds away
}
template <size_t N>
inline bool all_hold(const std::array<Condition, N> &conditions) {
    return all_hold(conditions, std::make_index_sequence<N>{});
}

// A batch's check, before its first query is computed: holds(q) (a query type's conditions
// folded, all_hold) for every query at once, no branch per query; only where one fails,
// check(q) (which throws, naming the field) query by query, rethrown naming the first failing
// query's index ("query 5: ...").
template <class Query, class Holds, class Check>
void require_every_query(const Query *queries, size_t count, Holds holds, Check check) {
    bool all_valid = true;
    for (size_t i = 0; i < count; ++i) all_valid &= holds(queries[i]);
    if (all_valid) return;
    for (size_t i = 0; i < count; ++i) {
        try {
            check(queries[i]);
        } catch (const std::invalid_argument &e) {
            throw std::invalid_argument("query " + std::to_string(i) + ": " + e.what());
        }
    }
}

} // namespace scatterlut::detail
