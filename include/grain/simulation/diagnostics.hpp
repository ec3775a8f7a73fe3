#pragma once
/// \file diagnostics.hpp
/// The read-only visits of a Simulation's contacts: `for_each_contact` (geometry, result, heat
/// rate or a `ContactView`), `for_each_conductance` and `contact_counts`. Contacts are evaluated
/// exactly as the contact pass evaluates them (`ContactPass::pair_law`, `wall_law`, `evaluate`,
/// `conductance`), on copies of their histories, so the state is not changed.
///
/// A component of `Simulation` (simulation.hpp): static functions over the simulation's state,
/// which declares it a friend.

#include <grain/contact/frame.hpp>
#include <grain/contact/geometry.hpp>
#include <grain/core/vector.hpp>
#include <grain/simulation/components.hpp>

#include <algorithm>
#include <cstddef>
#include <type_traits>
#include <utility>

namespace grain::detail {

template <class Sim>
struct Diagnostics {
  using Contact = typename Sim::contact_type;
  using V = typename Sim::V;
  using A = typename Sim::A;
  using History = typename Sim::History;
  static constexpr int D = Sim::D;
  static constexpr bool thermal = Sim::thermal;
  using Pass = ContactPass<Sim>;
  using Heat = HeatStep<Sim>;
  using ContactViewType = typename Sim::ContactViewType;

  /// The rows of the neighbour list that name current particles (particles added since the last
  /// build have no row yet).
  static std::size_t listed_rows(const Sim& s) {
    return s.list_.offsets.empty() ? 0 : std::min(s.list_.rows(), s.particles_.size());
  }

  /// Sim::for_each_contact.
  template <class F>
  static void for_each_contact(const Sim& s, F& f) {
    ContactGeometry<D> g;
    const auto& p = s.particles_;
    auto visit = [&](std::size_t i, std::size_t j, bool wall, const typename Pass::Law& law,
                     History h, double cell_radius) {
      auto r = Pass::evaluate(s, g, law, h);
      if constexpr (Contact::cohesive)
        if (!(g.overlap > 0.0) && r.normal.force == 0.0) return; // within reach, not bonded
      using R = decltype(r);
      constexpr bool view = std::is_invocable_v<F&, const ContactViewType&>;
      if constexpr (view || std::is_invocable_v<F&, std::size_t, std::size_t, bool,
                                                const ContactGeometry<D>&, const R&, double>) {
        double q = 0.0;
        if constexpr (thermal) {
          const double tj = wall ? s.walls_[j].temperature : p.temperature[j];
          if (!wall || s.wall_conducts(j))
            q = Pass::conductance(s, g, law, r, h, cell_radius) * (tj - p.temperature[i]);
        }
        if constexpr (view)
          f(ContactViewType{i, j, wall, g, r, h, q, ContactFrame<D>::from_normal(g.normal)});
        else
          f(i, j, wall, std::as_const(g), std::as_const(r), q);
      } else {
        (void)cell_radius;
        f(i, j, wall, std::as_const(g), std::as_const(r));
      }
    };
    for (std::size_t i = 0; i < listed_rows(s); ++i) {
      for (const auto e : s.list_.pair_entries(i)) {
        const auto [a, b] = Pass::oriented(s, i, s.list_.partners[e]);
        if (!Pass::acting_pair(s, a, b, g)) continue;
        visit(a, b, false, Pass::pair_law(s, e, a, b), Sim::history_at(s.hist_.pair, e),
              Heat::cell_radius_pair(s, e));
      }
      for (const auto e : s.list_.wall_entries(i)) {
        const auto w = s.list_.walls[e];
        if (!Pass::acting_wall(s, i, w, g)) continue;
        visit(i, w, true, Pass::wall_law(s, e, i, w), Sim::history_at(s.hist_.wall, e),
              Heat::cell_radius_wall(s, e));
      }
    }
  }

  /// Sim::for_each_conductance. In a thermal analysis the contacts are at rest (particles never
  /// move, whatever velocities they were given).
  template <class F>
  static void for_each_conductance(const Sim& s, F& f) {
    if constexpr (thermal) {
      ContactGeometry<D> g;
      const bool rest = !s.moves();
      auto at_rest = [&](ContactGeometry<D>& c) {
        if (!rest) return;
        c.velocity = c.tangential_velocity = c.slip_velocity = V::Zero();
        c.normal_velocity = 0.0;
        c.omega_rel = c.slip_omega_rel = zero<A>();
      };
      auto touching = [&](const typename Pass::Law& law, History h, double cell_radius) {
        at_rest(g);
        auto r = Pass::evaluate(s, g, law, h);
        return Pass::conductance(s, g, law, r, h, cell_radius);
      };
      for (std::size_t i = 0; i < listed_rows(s); ++i) {
        for (const auto e : s.list_.pair_entries(i)) {
          const auto [a, b] = Pass::oriented(s, i, s.list_.partners[e]);
          double H = 0.0;
          if (Pass::touching_pair(s, a, b, g))
            H = touching(Pass::pair_law(s, e, a, b), Sim::history_at(s.hist_.pair, e),
                         Heat::cell_radius_pair(s, e));
          else if constexpr (Contact::indirect)
            H = Heat::gap_pair_conductance(s, a, b, e, g);
          if (H != 0.0) f(a, b, false, H);
        }
        for (const auto e : s.list_.wall_entries(i)) {
          const auto w = s.list_.walls[e];
          if (!s.wall_conducts(w)) continue;
          double H = 0.0;
          if (Pass::touching_wall(s, i, w, g))
            H = touching(Pass::wall_law(s, e, i, w), Sim::history_at(s.hist_.wall, e),
                         Heat::cell_radius_wall(s, e));
          else if constexpr (Contact::indirect)
            H = Heat::gap_wall_conductance(s, i, w, e, g);
          if (H != 0.0) f(i, static_cast<std::size_t>(w), true, H);
        }
      }
    } else {
      (void)s;
      (void)f;
    }
  }

  /// Sim::contact_counts: touching particle-particle and particle-wall contacts.
  static std::pair<std::size_t, std::size_t> contact_counts(const Sim& s) {
    std::size_t pp = 0, pw = 0;
    ContactGeometry<D> g;
    for (std::size_t i = 0; i < listed_rows(s); ++i) {
      for (const auto e : s.list_.pair_entries(i))
        pp += Pass::touching_pair(s, i, s.list_.partners[e], g);
      for (const auto e : s.list_.wall_entries(i))
        pw += Pass::touching_wall(s, i, s.list_.walls[e], g);
    }
    return {pp, pw};
  }
};

} // namespace grain::detail
