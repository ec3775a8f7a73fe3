#pragma once
/// \file sums.hpp
/// The order in which a particle's contact loads are summed: a `Simulation` option
/// `grain::sums<Order>` (docs/sums.md).
///
/// - `grain::by_list` (the default): the loads are added while the neighbour list is walked, in
///   deterministic chunks of rows. The result is the same bits for any number of threads; it
///   depends on the order of the list, which follows the cell sort of the particles (so on the
///   skin, the cell size and the steps at which the list is rebuilt).
/// - `grain::by_id`: every pair is evaluated with the particle of lower id first (geometry,
///   mixing, history orientation), its loads are kept per list entry, and each particle then
///   sums its own: its start value (gravity, damping), its walls in wall order, then its pairs in
///   ascending partner id. The result is the same bits for any number of threads and any order of
///   the list: another skin, cell size or rebuild schedule, and (distributed runs) any number of
///   processes. It costs a second pass over the contacts.

#include <type_traits>

namespace grain {

/// Contact loads summed in the order of the neighbour list (default; see sums.hpp).
struct by_list {};
/// Contact loads summed per particle in ascending partner id (see sums.hpp).
struct by_id {};

/// The summation order of the contact loads, a Simulation option: `grain::sums<grain::by_id>`.
template <class Order>
struct sums {
  static_assert(std::is_same_v<Order, by_list> || std::is_same_v<Order, by_id>,
                "grain::sums<Order>: the order is grain::by_list (the default) or grain::by_id");
  using order = Order;
};

namespace detail {
template <class T>
struct is_sums : std::false_type {};
template <class Order>
struct is_sums<sums<Order>> : std::true_type {};
} // namespace detail

} // namespace grain
