#pragma once
/// \file shape.hpp
/// Particle shapes: `Disk` (2D) and `Sphere` (3D). A shape fixes the dimension of a simulation
/// and how mass and moment of inertia follow from radius and density.
///
/// | shape | volume | moment of inertia |
/// |---|---|---|
/// | `Sphere` | 4/3 pi R^3 | 2/5 m R^2 |
/// | `Disk` (cylinder of length L = `thickness`) | pi R^2 L | 1/2 m R^2 |
/// | `Disk` with `sphere_mass = true` (in-plane spheres) | 4/3 pi R^3 | 2/5 m R^2 |
///
/// Lengths in m, density in kg/m^3, mass in kg, inertia in kg m^2. A 2D simulation with
/// `thickness = 1` (the default) gives mass per metre of depth.

#include <grain/core/error.hpp>
#include <numbers>

namespace grain {

/// A 2D disk: a cylinder of length `thickness` [m] seen end-on, moving in the xy plane.
struct Disk {
  static constexpr int dimension = 2;
  static constexpr const char* name = "disk";
  /// Cylinder length L [m] used for volume and mass.
  double thickness = 1.0;
  /// If true, a disk has the mass and inertia of the sphere of the same radius (the variant of
  /// 2D codes that model in-plane spheres).
  bool sphere_mass = false;

  double volume(double r) const {
    return sphere_mass ? 4.0 / 3.0 * std::numbers::pi * r * r * r
                       : std::numbers::pi * r * r * thickness;
  }
  /// Moment of inertia about the z axis as a fraction of m R^2.
  double inertia_factor() const { return sphere_mass ? 0.4 : 0.5; }
  /// Surface area (lateral surface for a cylinder) [m^2].
  double surface(double r) const {
    return sphere_mass ? 4.0 * std::numbers::pi * r * r : 2.0 * std::numbers::pi * r * thickness;
  }
  void validate() const { detail::require_positive("Disk", "thickness", thickness); }
};

/// A 3D sphere.
struct Sphere {
  static constexpr int dimension = 3;
  static constexpr const char* name = "sphere";
  double volume(double r) const { return 4.0 / 3.0 * std::numbers::pi * r * r * r; }
  double inertia_factor() const { return 0.4; }
  double surface(double r) const { return 4.0 * std::numbers::pi * r * r; }
  void validate() const {}
};

/// A particle shape: a type with a dimension (2 or 3), volume(r) and inertia_factor().
template <class T>
concept ParticleShape = requires(const T& s, double r) {
  { T::dimension } -> std::convertible_to<int>;
  { s.volume(r) } -> std::convertible_to<double>;
  { s.inertia_factor() } -> std::convertible_to<double>;
}
&&(T::dimension == 2 || T::dimension == 3);

} // namespace grain
