#pragma once
/// \file facets.hpp
/// Multi-node facets: walls whose corners are nodes that move independently (a deformable
/// membrane, a conveyor belt driven through its nodes), as a simulation stage
/// (`grain::stages<grain::Facets<D>>`, see docs/facets.md).
///
/// A facet is a triangle (3D) or a segment (2D) wall of the simulation whose D corners are nodes
/// of the stage. A node is either *driven* (its velocity is a time function; mass 0) or *free*
/// (mass m > 0, moved by the contact loads of its facets, gravity and the loads a program adds
/// with `add_node_force`). Each step, with velocity Verlet:
///
/// - `before_search`: free nodes get a half kick and drift, driven nodes move with their velocity
///   at mid-step, x += v(t + dt/2) dt; each facet takes its nodes' positions, and, as its
///   surface velocity, the barycentric interpolation of the velocities its nodes will have at the
///   end of the step (the velocity the contact models see);
/// - `after_forces`: the force each touching particle exerts on a facet, at the contact point p,
///   is spread over the facet's nodes by the barycentric coordinates of p (projected on the facet
///   and clamped to it, q): F_k = lambda_k(q) F, so that sum_k F_k = F and
///   sum_k x_k x F_k = q x F; free nodes then get their second half kick with F_k + m g, driven
///   nodes the velocity of t + dt.
///
/// Units: SI (m, kg, s, N).

#include <grain/core/error.hpp>
#include <grain/core/stages.hpp>
#include <grain/core/time_function.hpp>
#include <grain/core/vector.hpp>
#include <grain/walls/walls.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>
#include <string>
#include <vector>

namespace grain {

/// A node of multi-node facets.
template <int D>
struct FacetNode {
  Vec<D> position = Vec<D>::Zero(); ///< [m]
  Vec<D> velocity = Vec<D>::Zero(); ///< initial velocity [m/s] (of a free node)
  /// Mass [kg]: > 0 for a free node; 0 for a driven node, which moves with `driven_velocity`
  /// (the zero vector when not given: a node at rest).
  double mass = 0.0;
  std::optional<VectorTimeFunction<D>> driven_velocity{};
};

/// The facet stage: nodes, facets (walls of the simulation) and the transfer of loads.
template <int D>
class Facets {
public:
  using V = Vec<D>;
  using Corners = std::array<std::size_t, D>;
  using WallShape = std::conditional_t<D == 2, walls::Segment, walls::Triangle>;

  /// Adds a node; returns its index. Throws InputError for a negative or non-finite mass or a
  /// non-finite position or velocity.
  std::size_t add_node(const FacetNode<D>& n) {
    const std::string obj = "Facet node " + std::to_string(nodes_.size());
    detail::require(n.position.allFinite(), obj, "position", n.position.transpose(),
                    "finite coordinates [m]");
    detail::require(n.velocity.allFinite(), obj, "velocity", n.velocity.transpose(),
                    "finite [m/s]");
    detail::require(std::isfinite(n.mass) && n.mass >= 0.0, obj, "mass", n.mass,
                    "0 (driven) or (0, inf) kg (free)");
    detail::require(!(n.mass > 0.0 && n.driven_velocity), obj, "driven_velocity",
                    "(given for a free node)", "only for a node of mass 0");
    nodes_.push_back(n);
    force_.push_back(V::Zero());
    extra_.push_back(V::Zero());
    load_.push_back(V::Zero());
    return nodes_.size() - 1;
  }

  /// Adds a facet on these nodes (2D: a segment a-b; 3D: a triangle a-b-c) as a wall of `sim`;
  /// returns the wall's index. Call before the run starts or between runs.
  template <class Sim>
  std::size_t add_facet(Sim& sim, const Corners& corners, WallOptions<D> options = {}) {
    const std::string obj = "Facet '" + options.name + "'";
    for (std::size_t k = 0; k < D; ++k)
      detail::require(corners[k] < nodes_.size(), obj, "node index", corners[k],
                      "[0, " + std::to_string(nodes_.size()) + ") (indices of add_node)");
    options.velocity = V::Zero();
    options.omega = zero<Angular<D>>();
    const auto w = sim.add_wall(shape_of(corners), options);
    facets_.push_back({corners, w});
    std::array<V, D> u;
    for (std::size_t k = 0; k < D; ++k) {
      auto& node = nodes_[corners[k]];
      if (!(node.mass > 0.0)) node.velocity = driven(node, sim.time());
      u[k] = node.velocity;
    }
    sim.walls()[w].node_velocity = u;
    return w;
  }

  std::size_t node_count() const { return nodes_.size(); }
  std::size_t facet_count() const { return facets_.size(); }
  const V& position(std::size_t n) const { return nodes_[n].position; }
  const V& velocity(std::size_t n) const { return nodes_[n].velocity; }
  /// Contact load the particles put on node n at the last force evaluation [N].
  const V& contact_load(std::size_t n) const { return load_[n]; }
  /// Adds a force [N] on free node n for the current force evaluation (from an `after_forces`
  /// hook of a stage listed before this one, e.g. membrane springs).
  void add_node_force(std::size_t n, const V& f) { extra_[n] += f; }

  // ------------------------------------------------------------------ hooks
  template <class Sim>
  void before_search(Sim& sim) {
    static_assert(Sim::integrator_type::drift_before_forces,
                  "grain::Facets: nodes are integrated with velocity Verlet; use "
                  "integrate::VelocityVerlet (the default) as the simulation's integrator");
    in_step_ = true; // a step that moves (not the initial evaluation, not a thermal analysis)
    const double h = sim.time_step(), t = sim.time();
    for (std::size_t n = 0; n < nodes_.size(); ++n) {
      auto& node = nodes_[n];
      if (node.mass > 0.0) {
        node.velocity += (0.5 * h / node.mass) * force_[n];
        node.position += h * node.velocity;
      } else {
        node.position += h * driven(node, t + 0.5 * h);
        node.velocity = driven(node, t + h);
      }
    }
    // velocities at the end of the step as the forces see them
    auto& v = predicted_;
    v.resize(nodes_.size());
    for (std::size_t n = 0; n < nodes_.size(); ++n)
      v[n] = nodes_[n].mass > 0.0 ? V(nodes_[n].velocity + (0.5 * h / nodes_[n].mass) * force_[n])
                                  : nodes_[n].velocity;
    for (const auto& f : facets_) {
      auto& wall = sim.walls()[f.wall];
      auto& g = std::get<WallShape>(wall.geometry); // corners only: other data of the shape stays
      g.a = nodes_[f.corners[0]].position;
      g.b = nodes_[f.corners[1]].position;
      if constexpr (D == 3) g.c = nodes_[f.corners[2]].position;
      std::array<V, D> u;
      for (std::size_t k = 0; k < D; ++k)
        u[k] = v[f.corners[k]];
      wall.node_velocity = u;
    }
  }

  template <class Sim>
  void after_forces(Sim& sim) {
    std::fill(load_.begin(), load_.end(), V::Zero());
    // the facet of each wall index (walls that are not facets: none)
    if (facet_of_.size() != sim.walls().size()) {
      facet_of_.assign(sim.walls().size(), none);
      for (std::size_t k = 0; k < facets_.size(); ++k)
        facet_of_[facets_[k].wall] = k;
    }
    sim.for_each_wall_load([&](std::int64_t, std::size_t w, const V& p, const V& f) {
      const std::size_t k = facet_of_[w];
      if (k == none) return;
      std::array<V, D> x;
      for (std::size_t c = 0; c < D; ++c)
        x[c] = nodes_[facets_[k].corners[c]].position;
      const auto lambda = detail::barycentric(x, p);
      for (std::size_t c = 0; c < D; ++c)
        load_[facets_[k].corners[c]] += lambda[c] * f;
    });
    const V g = sim.gravity();
    const double h = sim.time_step(), t = sim.time();
    for (std::size_t n = 0; n < nodes_.size(); ++n) {
      auto& node = nodes_[n];
      if (node.mass > 0.0) {
        force_[n] = load_[n] + node.mass * g + extra_[n];
        extra_[n] = V::Zero(); // loads added by other stages count for one evaluation
        if (in_step_) node.velocity += (0.5 * h / node.mass) * force_[n];
      } else {
        node.velocity = driven(node, in_step_ ? t + h : t);
      }
    }
    for (const auto& f : facets_) {
      std::array<V, D> u;
      for (std::size_t k = 0; k < D; ++k)
        u[k] = nodes_[f.corners[k]].velocity;
      sim.walls()[f.wall].node_velocity = u;
    }
  }

  template <class Sim>
  void end_of_step(Sim&) {
    in_step_ = false;
  }

  /// The nodes' state in a checkpoint (the program makes the same nodes and facets again before
  /// loading).
  template <class Archive>
  void serialize(Archive& ar) {
    std::uint64_t n = nodes_.size();
    ar(n);
    if (n != nodes_.size())
      throw InputError("checkpoint: facet nodes = " + std::to_string(n) +
                       " is invalid; valid: " + std::to_string(nodes_.size()) +
                       " (the nodes this program adds, in the same order)");
    std::vector<V> x, v;
    for (const auto& n : nodes_) {
      x.push_back(n.position);
      v.push_back(n.velocity);
    }
    ar(x, v, force_, load_);
    for (std::size_t n = 0; n < nodes_.size() && n < x.size(); ++n) {
      nodes_[n].position = x[n];
      nodes_[n].velocity = v[n];
    }
  }

private:
  static constexpr std::size_t none = static_cast<std::size_t>(-1);
  struct Facet {
    Corners corners;
    std::size_t wall;
  };
  WallShape shape_of(const Corners& c) const {
    if constexpr (D == 2)
      return walls::Segment{nodes_[c[0]].position, nodes_[c[1]].position};
    else
      return walls::Triangle{nodes_[c[0]].position, nodes_[c[1]].position, nodes_[c[2]].position};
  }
  static V driven(const FacetNode<D>& n, double t) {
    return n.driven_velocity ? V((*n.driven_velocity)(t)) : V(V::Zero());
  }

  std::vector<FacetNode<D>> nodes_;
  std::vector<V> force_;     ///< total force on each free node at the last evaluation [N]
  std::vector<V> extra_;     ///< forces added by other stages for the current evaluation [N]
  std::vector<V> load_;      ///< contact loads of the last evaluation [N]
  std::vector<V> predicted_; ///< node velocities the forces of the step see (work space) [m/s]
  std::vector<Facet> facets_;
  std::vector<std::size_t> facet_of_;
  bool in_step_ = false;
};

} // namespace grain
