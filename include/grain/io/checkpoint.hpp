#pragma once
/// \file checkpoint.hpp
/// Checkpoint and restart: `io::save_checkpoint(sim, path)` writes the run state of a simulation
/// to a binary file; `io::load_checkpoint(sim, path)` reads it into a simulation made by the same
/// program (same types, materials and walls; groups, conditions and variable properties added
/// again by the program), which then continues bit-identically to the run that was never
/// interrupted: particles (active and waiting), their contact histories, the neighbour list, the
/// thermal state, walls' positions and temperatures, time and step count, the state of the
/// insertions (added again by the program, like groups, before loading).
///
/// \code
/// auto sim = make_simulation();                 // the program's own set-up
/// if (restart) grain::io::load_checkpoint(sim, "run.ckpt");
/// auto history = grain::io::history("history.csv");
/// history.resume = restart;                     // keeps the rows written before the restart
/// sim.run(1.0 - sim.time(),                     // run() adds to the current time: to t = 1 s
///         grain::io::every(0.01, history, grain::io::vtk("bed", {.resume = restart})),
///         grain::io::every(0.1, grain::io::checkpoint("run.ckpt")));
/// \endcode
///
/// Format (native byte order, doubles as IEEE 754): the magic "GRAINCKP", the format version
/// (`checkpoint_format_version`), the library version, a signature of the simulation type
/// (shape, search, models, integrator, bytes of contact history), the materials' numbers, the
/// numbers of walls and particles, the state, and the end mark "GRAINEND". A file of another
/// format version, of another simulation type, or written with other materials or another number
/// of walls is rejected with an `InputError` that says what differs; a truncated file is too.

#include <grain/core/error.hpp>
#include <grain/io/atomic_file.hpp>
#include <grain/io/console.hpp>
#include <grain/io/write_error.hpp>
#include <grain/simulation.hpp>
#include <grain/version.hpp>

#include <Eigen/Geometry>

#include <array>
#include <cerrno>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>
#include <string>
#include <type_traits>
#include <utility>
#include <variant>
#include <vector>

namespace grain::io {

/// Version of the checkpoint format; files of another version are rejected.
inline constexpr std::uint32_t checkpoint_format_version = 5;

namespace detail {

template <class T>
struct is_vector : std::false_type {};
template <class T, class Alloc>
struct is_vector<std::vector<T, Alloc>> : std::true_type {};
template <class T>
struct is_variant : std::false_type {};
template <class... T>
struct is_variant<std::variant<T...>> : std::true_type {};
template <class T>
struct is_pair : std::false_type {};
template <class A, class B>
struct is_pair<std::pair<A, B>> : std::true_type {};
template <class T>
struct is_array : std::false_type {};
template <class T, std::size_t N>
struct is_array<std::array<T, N>> : std::true_type {};

/// Fields of the types a checkpoint carries that have no serialize member.
template <class Ar, int D>
void serialize_fields(Ar& ar, ParticleSpec<D>& s) {
  ar(s.position, s.radius, s.material, s.velocity, s.omega, s.temperature, s.fixed, s.creation_time,
     s.destruction_time, s.id);
}
template <class Ar>
void serialize_fields(Ar& ar, walls::Segment& g) {
  ar(g.a, g.b);
}
template <class Ar>
void serialize_fields(Ar& ar, walls::Circle& g) {
  ar(g.center, g.radius);
}
template <class Ar>
void serialize_fields(Ar& ar, walls::Plane& g) {
  ar(g.point, g.normal);
}
template <class Ar>
void serialize_fields(Ar& ar, walls::Triangle& g) {
  ar(g.a, g.b, g.c);
  if (g.mesh) ar(g.origin, g.orientation); // an obstacle's pose (its mesh is set-up)
}

/// The fewest bytes an item of type T takes in a checkpoint (1 if not known): a length read for
/// a vector of T is checked against the bytes left with it, so that a corrupt length cannot ask
/// for more memory than the file could fill.
template <class T>
constexpr std::uint64_t min_bytes() {
  if constexpr (std::is_arithmetic_v<T> || std::is_enum_v<T>) {
    return sizeof(T);
  } else if constexpr (std::is_base_of_v<Eigen::MatrixBase<T>, T>) {
    return static_cast<std::uint64_t>(T::SizeAtCompileTime) * sizeof(typename T::Scalar);
  } else if constexpr (std::is_same_v<T, Eigen::Quaterniond>) {
    return 4 * sizeof(double);
  } else if constexpr (is_vector<T>::value || std::is_same_v<T, std::string>) {
    return sizeof(std::uint64_t);
  } else if constexpr (is_array<T>::value) {
    return std::tuple_size_v<T> * min_bytes<typename T::value_type>();
  } else if constexpr (is_pair<T>::value) {
    return min_bytes<typename T::first_type>() + min_bytes<typename T::second_type>();
  } else if constexpr (is_variant<T>::value) {
    return sizeof(std::uint32_t);
  } else {
    return 1;
  }
}

/// Reads (Reading = true) or writes every item given to it.
template <bool Reading>
class Archive {
public:
  static constexpr bool reading = Reading;
  using Stream = std::conditional_t<Reading, std::istream, std::ostream>;

  Archive(Stream& s, std::string path) : s_(s), path_(std::move(path)) {}

  template <class... T>
  void operator()(T&... items) {
    (item(items), ...);
  }

  void item(std::string& x) {
    std::uint64_t n = x.size();
    raw(n);
    if constexpr (Reading) {
      check_size(n, 1);
      x.resize(n);
    }
    bytes(x.data(), x.size());
  }

  template <class T>
  void item(T& x) {
    if constexpr (std::is_same_v<T, bool> && Reading) {
      unsigned char b = 0; // a byte other than 0 or 1 is no bool
      raw(b);
      if (b > 1) corrupt("a truth value of " + std::to_string(b));
      x = b == 1;
    } else if constexpr (std::is_arithmetic_v<T> || std::is_enum_v<T>) {
      raw(x);
    } else if constexpr (std::is_base_of_v<Eigen::MatrixBase<T>, T>) {
      static_assert(T::SizeAtCompileTime > 0, "checkpoint: fixed-size Eigen types only");
      for (Eigen::Index k = 0; k < x.size(); ++k)
        raw(x.data()[k]);
    } else if constexpr (std::is_same_v<T, Eigen::Quaterniond>) {
      for (int k = 0; k < 4; ++k)
        raw(x.coeffs()[k]);
    } else if constexpr (is_vector<T>::value) {
      std::uint64_t n = x.size();
      raw(n);
      if constexpr (Reading) {
        check_size(n,
                   std::is_same_v<T, std::vector<bool>> ? 1 : min_bytes<typename T::value_type>());
        if (depth_ == 0 && per_particle_ > 0) {
          --per_particle_;
          if (n != particles_)
            corrupt("a per-particle array of " + std::to_string(n) + " entries for " +
                    std::to_string(particles_) + " particles");
        }
        x.resize(n);
      }
      ++depth_;
      if constexpr (std::is_same_v<T, std::vector<bool>>) {
        for (std::size_t k = 0; k < x.size(); ++k) {
          bool b = x[k];
          item(b);
          x[k] = b;
        }
      } else {
        for (auto& e : x)
          item(e);
      }
      --depth_;
    } else if constexpr (is_array<T>::value) {
      for (auto& e : x)
        item(e);
    } else if constexpr (is_pair<T>::value) {
      item(x.first);
      item(x.second);
    } else if constexpr (is_variant<T>::value) {
      std::uint32_t k = static_cast<std::uint32_t>(x.index());
      raw(k);
      if constexpr (Reading) {
        if (k >= std::variant_size_v<T>) corrupt("variant index");
        // an alternative of the right kind keeps what the set-up gave it (a triangle's mesh)
        if (k != x.index()) emplace<T>(x, k, std::make_index_sequence<std::variant_size_v<T>>{});
      }
      std::visit([&](auto& v) { item(v); }, x);
    } else if constexpr (requires { x.serialize(*this); }) {
      x.serialize(*this);
    } else if constexpr (requires { serialize_fields(*this, x); }) {
      serialize_fields(*this, x);
    } else {
      static_assert(std::is_trivially_copyable_v<T>,
                    "grain checkpoint: this type needs a serialize member or serialize_fields");
      bytes(&x, sizeof(T));
    }
  }

  /// Fails with the file name and what was being read.
  [[noreturn]] void corrupt(const std::string& what) const {
    throw InputError("checkpoint '" + path_ + "': " + what +
                     " is invalid; valid: a complete file written by io::save_checkpoint "
                     "(the file is truncated or corrupt)");
  }

  const std::string& path() const { return path_; }

  /// Reading: the next `arrays` vectors read at the top level hold one entry per particle, and
  /// there are `particles` particles (a length that differs is corrupt).
  void expect_per_particle(std::size_t arrays, std::uint64_t particles) {
    per_particle_ = arrays;
    particles_ = particles;
  }

private:
  template <class T, std::size_t... I>
  static void emplace(T& x, std::size_t k, std::index_sequence<I...>) {
    ((k == I ? (void)x.template emplace<I>() : (void)0), ...);
  }

  template <class T>
  void raw(T& x) {
    bytes(&x, sizeof(T));
  }
  void bytes(void* p, std::size_t n) {
    if (n == 0) return;
    if constexpr (Reading) {
      s_.read(static_cast<char*>(p), static_cast<std::streamsize>(n));
      if (!s_) corrupt("the data");
    } else {
      errno = 0;
      s_.write(static_cast<const char*>(p), static_cast<std::streamsize>(n));
      if (!s_)
        throw write_error("grain::io::save_checkpoint", path_, errno,
                          "; the file is removed and a checkpoint under the final name is left "
                          "as it was");
    }
  }
  void check_size(std::uint64_t n, std::uint64_t each) {
    // a size larger than the rest of the file is corrupt (and would exhaust memory)
    const auto here = s_.tellg();
    s_.seekg(0, std::ios::end);
    const auto end = s_.tellg();
    s_.seekg(here);
    if (here < 0 || end < here || n > static_cast<std::uint64_t>(end - here) / each)
      corrupt("a length of " + std::to_string(n));
  }

  Stream& s_;
  std::string path_;
  int depth_ = 0;                ///< vectors being read around the current item
  std::size_t per_particle_ = 0; ///< top-level vectors still to come with one entry per particle
  std::uint64_t particles_ = 0;
};

/// The number of user stages and the sizes of the per-particle fields of a simulation type
/// ("" without either).
template <class... S, class... F>
std::string stage_signature(grain::stages<S...>, grain::fields<F...>) {
  std::string s;
  if (sizeof...(S) > 0) s += ", " + std::to_string(sizeof...(S)) + " stages";
  if (sizeof...(F) > 0) {
    s += ", fields of";
    ((s += " " + std::to_string(sizeof(F))), ...);
    s += " bytes";
  }
  return s;
}

/// What identifies the type of a simulation in a checkpoint.
template <class Sim>
std::string signature() {
  using C = typename Sim::contact_type;
  return std::string(Sim::shape_type::name) + " " + std::to_string(Sim::dimension) + "D, " +
         describe_contact<C>() + ", search " + Sim::search_type::name + ", integrator " +
         Sim::integrator_type::name + ", history " + std::to_string(sizeof(typename Sim::History)) +
         " bytes" + (Sim::thermal ? ", thermal" : "") +
         stage_signature(typename Sim::StageList{}, typename Sim::FieldList{});
}

/// The numbers of the materials, to check that a restart uses the same ones.
inline std::vector<double> material_numbers(const std::vector<Material>& ms) {
  std::vector<double> v;
  for (const auto& m : ms)
    v.insert(v.end(), {m.density, m.young, m.poisson, m.shear, m.young_real, m.restitution,
                       m.friction, m.friction_static, m.rolling_friction, m.conductivity,
                       m.heat_capacity, m.emissivity});
  return v;
}

/// The number of per-particle fields of a simulation type.
template <class... F>
constexpr std::size_t count_fields(grain::fields<F...>) {
  return sizeof...(F);
}

inline constexpr char magic[8] = {'G', 'R', 'A', 'I', 'N', 'C', 'K', 'P'};
inline constexpr char end_mark[8] = {'G', 'R', 'A', 'I', 'N', 'E', 'N', 'D'};

} // namespace detail

/// Writes the run state of an initialised simulation (one that has run, or whose initialize() was
/// called) to `path`. The file is written to `path`.tmp, closed and checked, and only then renamed
/// to `path` (io/atomic_file.hpp), so that neither an interrupted write (a killed run) nor a
/// failed one (a full disk) leaves a broken checkpoint under the final name: a failed write
/// removes the temporary file, keeps the previous checkpoint at `path` and throws io::WriteError
/// naming the writer, the files and the reason.
template <class Sim>
void save_checkpoint(const Sim& sim, const std::string& path) {
  sim.require_whole_steps("grain::io::save_checkpoint");
  if (!sim.initialized())
    throw InputError("grain::io::save_checkpoint: simulation = not initialised is invalid; valid: "
                     "a simulation after initialize() or a run");
  detail::require_output_folder("grain::io::save_checkpoint", path);
  detail::AtomicFile file("grain::io::save_checkpoint", path, true);
  try {
    detail::Archive<false> ar(file.stream(), path);
    char m[8];
    std::memcpy(m, detail::magic, 8);
    std::uint32_t version = checkpoint_format_version;
    std::string lib = GRAIN_VERSION_STRING, sig = detail::signature<Sim>();
    auto numbers = detail::material_numbers(sim.materials());
    std::uint64_t walls = sim.walls().size(), particles = sim.size();
    ar(m, version, lib, sig, numbers, walls, particles);
    const_cast<Sim&>(sim).serialize(ar); // writing only reads the state
    std::memcpy(m, detail::end_mark, 8);
    ar(m);
  } catch (const WriteError& e) { // a write in the middle failed: the same message as at the end
    file.fail(e.error_number());
  }
  // the last bytes reach the file when it is closed: only a file still good after the close
  // holds the whole checkpoint, and only then is it renamed
  file.commit();
}

/// Reads a checkpoint written by save_checkpoint into `sim`, a simulation of the same type set up
/// by the same program (same materials and walls; its particles are replaced by those of the
/// checkpoint). Throws InputError when the file does not fit.
template <class Sim>
void load_checkpoint(Sim& sim, const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in)
    throw InputError("checkpoint '" + path +
                     "': file = missing or unreadable is invalid; valid: a file written by "
                     "io::save_checkpoint");
  detail::Archive<true> ar(in, path);
  char m[8] = {};
  ar(m);
  if (std::memcmp(m, detail::magic, 8) != 0)
    throw InputError("checkpoint '" + path +
                     "': file type is invalid; valid: a grain checkpoint (starts with GRAINCKP)");
  std::uint32_t version = 0;
  ar(version);
  if (version != checkpoint_format_version)
    throw InputError("checkpoint '" + path + "': format version = " + std::to_string(version) +
                     " is invalid; valid: " + std::to_string(checkpoint_format_version) +
                     " (this build of grain, " + GRAIN_VERSION_STRING + ")");
  std::string lib, sig;
  std::vector<double> numbers;
  std::uint64_t walls = 0, particles = 0;
  ar(lib, sig, numbers, walls, particles);
  const std::string expected = detail::signature<Sim>();
  if (sig != expected)
    throw InputError("checkpoint '" + path + "': simulation type = '" + sig +
                     "' is invalid; valid: '" + expected + "' (the type of this simulation)");
  if (numbers != detail::material_numbers(sim.materials()))
    throw InputError("checkpoint '" + path + "': materials = the " +
                     std::to_string(numbers.size() / 11) +
                     " materials of the run that wrote it differ from this simulation's " +
                     std::to_string(sim.materials().size()) +
                     "; valid: the same materials, added in the same order");
  if (walls != sim.walls().size())
    throw InputError("checkpoint '" + path + "': walls = " + std::to_string(walls) +
                     " is invalid; valid: " + std::to_string(sim.walls().size()) +
                     " (the walls of this simulation, added in the same order)");
  // The state is read into `sim` directly. Should the file turn out truncated or not to fit (a
  // stage's count, the end mark), `sim` is put back as it was given, from a copy of it (or, for
  // a simulation that cannot be copied, a stage holding a stream say, from a copy of its run
  // state in memory, which loses the loads of the last step on walls and removals requested
  // since it).
  auto read = [&] {
    // Simulation::serialize reads the particle arrays first: id, position, velocity, omega,
    // orientation, force, torque, radius, mass, inv_mass, inertia, inv_inertia and material
    // (13), the 4 thermal ones, then one per field
    ar.expect_per_particle(
        13 + (Sim::thermal ? 4 : 0) + detail::count_fields(typename Sim::FieldList{}), particles);
    sim.serialize(ar);
    ar(m);
    if (std::memcmp(m, detail::end_mark, 8) != 0) ar.corrupt("the end mark");
  };
  if constexpr (std::is_copy_assignable_v<Sim> && std::is_copy_constructible_v<Sim>) {
    Sim before(sim);
    try {
      read();
    } catch (...) {
      sim = std::move(before);
      throw;
    }
  } else {
    std::stringstream before;
    {
      detail::Archive<false> copy(before, path);
      sim.serialize(copy);
    }
    try {
      read();
    } catch (...) {
      detail::Archive<true> back(before, path);
      sim.serialize(back);
      throw;
    }
  }
}

/// An observer that writes a checkpoint each time it is called (use with io::every).
struct Checkpoint {
  std::string path;
  template <class Sim>
  void operator()(const Sim& sim) const {
    save_checkpoint(sim, path);
  }
};
inline Checkpoint checkpoint(std::string path) { return {std::move(path)}; }

} // namespace grain::io
