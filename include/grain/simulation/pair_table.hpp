#pragma once
/// \file pair_table.hpp
/// `PairTable<Contact>`: the materials of a simulation and what every pair of them gives a
/// contact: the mixed properties (`PairProperties::mix`, with the pair's overrides of
/// restitution and friction), the contact-model parameters of the pair (the simulation's
/// default, or the pair's own from `set_pair_parameters`), and those parameters resolved against
/// the pair's properties (`Contact::resolve`), which the contact pass reads.
///
/// Tables are nm x nm, row-major, symmetric: entry a * nm + b is the pair of materials a and b.

#include <grain/core/error.hpp>
#include <grain/particles/material.hpp>

#include <cstddef>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace grain {

template <class Contact>
class PairTable {
public:
  using ContactParams = typename Contact::Params;

  /// `defaults`: the contact parameters of every pair not given its own; `fluid_conductivity`
  /// [W/(m K)]: the interstitial fluid's, copied into every pair's properties.
  explicit PairTable(ContactParams defaults = {}, double fluid_conductivity = 0.0)
      : defaults_(std::move(defaults)), fluid_conductivity_(fluid_conductivity) {}

  /// Adds a validated material; returns its index. New pairs take the default parameters.
  std::uint32_t add_material(const Material& m) {
    m.validate();
    const auto n0 = materials_.size();
    std::vector<PairOverride> grown((n0 + 1) * (n0 + 1));
    std::vector<ContactParams> grown_params((n0 + 1) * (n0 + 1), defaults_);
    for (std::size_t a = 0; a < n0; ++a)
      for (std::size_t b = 0; b < n0; ++b) {
        grown[a * (n0 + 1) + b] = overrides_[a * n0 + b];
        grown_params[a * (n0 + 1) + b] = params_[a * n0 + b];
      }
    overrides_.swap(grown);
    params_.swap(grown_params);
    materials_.push_back(m);
    mix();
    return static_cast<std::uint32_t>(materials_.size() - 1);
  }

  /// Overrides the mixed restitution / friction of one pair (a negative value keeps the mixed
  /// one). Throws InputError naming `who` for an unknown material or a bad value.
  void set_override(std::uint32_t a, std::uint32_t b, const PairOverride& o,
                    const std::string& who = "Simulation::set_pair") {
    check_material(a, who);
    check_material(b, who);
    detail::require(o.restitution < 0.0 || (o.restitution > 0.0 && o.restitution <= 1.0), who,
                    "restitution", o.restitution, "(0, 1], or < 0 for the mixed value");
    for (const auto& [name, v] :
         {std::pair{"friction", o.friction}, std::pair{"friction_static", o.friction_static},
          std::pair{"rolling_friction", o.rolling_friction}})
      detail::require(std::isfinite(v), who, name, v, "[0, inf), or < 0 for the mixed value");
    const auto n = materials_.size();
    overrides_[a * n + b] = overrides_[b * n + a] = o;
    mix();
  }

  /// Gives one pair of materials (either order) its own contact parameters. Throws InputError
  /// naming the pair for invalid parameters or materials.
  void set_parameters(std::uint32_t a, std::uint32_t b, const ContactParams& p,
                      const std::string& who = "Simulation::set_pair_parameters") {
    check_material(a, who);
    check_material(b, who);
    try {
      Contact::validate(p);
    } catch (const InputError& e) {
      throw InputError(who + " (materials '" + materials_[a].name + "' and '" + materials_[b].name +
                       "'): " + e.what());
    }
    const auto n = materials_.size();
    params_[a * n + b] = params_[b * n + a] = p;
    resolve();
  }

  /// Per-particle contact properties (variable properties): the resolved parameters are then
  /// the given ones, which the contact laws resolve per contact.
  void set_per_particle(bool on) {
    per_particle_ = on;
    resolve();
  }
  bool per_particle() const { return per_particle_; }

  /// Throws InputError naming `obj` unless m is the index of a material.
  void check_material(std::uint32_t m, const std::string& obj) const {
    if (m >= materials_.size())
      throw InputError(obj + ": material = " + std::to_string(m) +
                       " is invalid; valid range: [0, " + std::to_string(materials_.size()) +
                       ") (indices returned by add_material)");
  }

  std::size_t size() const { return materials_.size(); }
  bool empty() const { return materials_.empty(); }
  const std::vector<Material>& materials() const { return materials_; }
  const Material& material(std::size_t k) const { return materials_[k]; }
  /// Index of the pair (a, b) in the tables.
  std::size_t index(std::size_t a, std::size_t b) const { return a * materials_.size() + b; }
  const PairOverride& override_of(std::size_t a, std::size_t b) const {
    return overrides_[index(a, b)];
  }
  /// Mixed properties of the pair (a, b).
  const PairProperties& properties(std::size_t a, std::size_t b) const {
    return pairs_[index(a, b)];
  }
  const PairProperties& properties(std::size_t k) const { return pairs_[k]; }
  /// Contact parameters of the pair (a, b), as given.
  const ContactParams& parameters(std::size_t a, std::size_t b) const {
    return params_[index(a, b)];
  }
  /// Contact parameters of pair k, as the contact pass uses them (see the file comment).
  const ContactParams& resolved(std::size_t k) const { return resolved_[k]; }
  /// Every pair's parameters as given (nm x nm).
  const std::vector<ContactParams>& all_parameters() const { return params_; }
  /// Properties of two materials mixed with the pair's overrides (for per-particle materials).
  PairProperties mix_of(const Material& a, const Material& b, std::size_t k) const {
    PairProperties pp = PairProperties::mix(a, b, overrides_[k]);
    pp.fluid_conductivity = fluid_conductivity_;
    return pp;
  }
  double fluid_conductivity() const { return fluid_conductivity_; }

private:
  void mix() {
    const auto nm = materials_.size();
    pairs_.resize(nm * nm);
    for (std::size_t a = 0; a < nm; ++a)
      for (std::size_t b = 0; b < nm; ++b)
        pairs_[a * nm + b] =
            PairProperties::mix(materials_[a], materials_[b], overrides_[a * nm + b]);
    for (auto& pp : pairs_)
      pp.fluid_conductivity = fluid_conductivity_;
    resolve();
  }
  /// The contact parameters of each pair with their per-pair constants worked out (left as
  /// given while a variable property changes contact properties per particle).
  void resolve() {
    resolved_.resize(params_.size());
    for (std::size_t k = 0; k < params_.size(); ++k)
      resolved_[k] = per_particle_ ? params_[k] : Contact::resolve(params_[k], pairs_[k]);
  }

  ContactParams defaults_;
  double fluid_conductivity_ = 0.0;
  bool per_particle_ = false;
  std::vector<Material> materials_;
  std::vector<PairOverride> overrides_;
  std::vector<PairProperties> pairs_;
  std::vector<ContactParams> params_;
  std::vector<ContactParams> resolved_;
};

} // namespace grain
