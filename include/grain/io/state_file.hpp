#pragma once
/// \file state_file.hpp
/// Particle state files: the particles of a simulation written to a file and read back as
/// `ParticleSpec`s, so that a packing made once (poured, settled, compacted, heated) starts other
/// runs, in other programs.
///
/// \code
/// io::write_state_csv(sim, "bed.csv");                   // program 1: after the packing settled
///
/// auto state = io::read_state_csv(sim2, "bed.csv");      // program 2: same dimension; the
/// io::load_state(sim2, state);                           // materials of sim2 must exist
/// \endcode
///
/// A CSV state file (`write_state_csv`) holds, for each active particle in the simulation's
/// current order, one line with every column below, after a comment line and a header line:
///
/// \verbatim
/// # grain state, dim=3, time=0.5, step=25000, particles=300
/// id,radius [m],material,x [m],y [m],z [m],vx [m/s],vy [m/s],vz [m/s],omegax [rad/s],omegay [rad/s],omegaz [rad/s],temperature [K],fixed,groups
/// 0,0.001,0,0.0125,-0.003,0.0011,0,0,-0.02,0,0,0,300,0,bottom;hot
/// \endverbatim
///
/// | column | meaning | unit |
/// |---|---|---|
/// | `id` | particle id (-1 or empty: the next free id when loaded) | - |
/// | `radius` | radius, > 0 (required) | m |
/// | `material` | index into the simulation's materials (as add_material returned it) | - |
/// | `x`, `y`, `z` | centre (2D: `x`, `y`) (required) | m |
/// | `vx`, `vy`, `vz` | velocity (2D: `vx`, `vy`) | m/s |
/// | `omegax`, `omegay`, `omegaz` | angular velocity (2D: `omega`, about z) | rad/s |
/// | `temperature` | temperature, >= 0 (thermal simulations only) | K |
/// | `fixed` | 1 for a fixed particle (ParticleSpec::fixed), else 0 | - |
/// | `groups` | the particle's groups, names separated by `;` (only if the simulation has groups) | - |
///
/// Numbers are written with `std::to_chars` (the shortest text that reads back to the same
/// double: positions, velocities, radii and temperatures round-trip bit for bit). A cell that
/// holds a comma or a quote is quoted (`"a,b"`, `""` a quote). The file is written under a
/// temporary name and renamed once complete (io/atomic_file.hpp): a killed run never leaves a
/// part of a state file, and a failed write throws io::WriteError and leaves the file of that
/// name as it was.
///
/// Reading (`read_state_csv`): columns are found by their names in the header line, in any order.
/// A name may carry its unit in brackets (`radius [m]`): it must then be the unit of the table
/// (`[-]` or `[]` for the columns without one); the name alone is accepted too. Columns with other
/// names are ignored, except the names of the other dimension's columns (`z`, `vz`, `omegax`,
/// ... in a 2D file; `omega` in a 3D one), which are an error; a mechanical simulation ignores the
/// `temperature` column. `x`, `y` (and `z`) and `radius` are required; a missing optional column
/// or an empty cell of one gives the ParticleSpec default (velocity 0, material 0, not fixed, the
/// simulation's initial temperature, the next free id), but a vector is given whole or not at all
/// (`vx` without `vy` is an error). Lines that begin with `#` and blank lines are skipped; the
/// comment `# grain state, ...` before the header is read: its `dim` must be the simulation's
/// dimension, its `time` and `step` are returned, and its `particles` must be the number of
/// particle lines (a file cut at the end of a line is found). Line ends may be `\n` or `\r\n`.
///
/// Every value is checked as add_particle checks it: finite centres, velocities and angular
/// velocities, radius in (0, inf), temperature in [0, inf) K, material below the number of
/// materials (when the reader is given the simulation or `StateReadOptions::materials`), ids in
/// [0, 2^63 - 2] or -1 and no id twice; `fixed` is 0 or 1. Anything else, and a file that is
/// missing, empty or not of this form (no header, a line with more or fewer cells than the
/// header), is an `InputError` naming the reader, the file, the line, the column, the value and
/// what is valid:
///
/// \verbatim
/// grain::io::read_state_csv: 'bed.csv' line 7: radius [m] = '-0.001' is invalid; valid range: (0, inf) m
/// \endverbatim
///
/// Groups: the reader returns the groups named in the file (`ParticleState::groups`: the name and
/// the particles, as indices into `ParticleState::particles`); `load_state` adds them with
/// add_group (`StateLoadOptions::groups`). The reserved group "all" is not written; a group's
/// walls are not in the file, nor is a group without an active particle.
///
/// `read_state_vtk` reads the particle files of `write_particles_vtk` (io::vtk's
/// `<prefix>_particles_NNNNNN.vtk`), ASCII or binary: the points (centres), and the point arrays
/// `radius` (required: a file written with fields that leave it out cannot be read), `id`,
/// `material`, `velocity`, `omega` and, in a thermal simulation, `temperature`; the other arrays
/// are read and ignored. ASCII files hold 17 significant digits and binary files the doubles
/// themselves: both give back the written values bit for bit. A VTK file has no `fixed` flag and
/// no groups: its particles are free and in no group. Its dimension is checked where the file
/// shows it: a 2D simulation needs z = 0 for every centre and velocity and (0, 0, w) angular
/// velocities, and the `orientation` array has 1 component in 2D files and 4 in 3D ones. A file
/// that is not a particle file of this form is an InputError naming the file, the place (line,
/// or byte in a binary file) and what was expected; every count is checked against the bytes
/// left in the file before anything is allocated for it.
///
/// What a state file does not hold: contact histories (tangential springs, rolling histories),
/// orientations, forces, per-particle fields of `grain::fields`, creation and destruction times,
/// inactive particles (a creation time still to come), conditions and walls. A simulation loaded
/// from a state starts its contacts anew: from a packing at rest this changes little, but it is
/// not the run continued (a checkpoint, io/checkpoint.hpp, continues a run bit for bit).

#include <grain/conditions/conditions.hpp>
#include <grain/core/error.hpp>
#include <grain/core/vector.hpp>
#include <grain/io/atomic_file.hpp>
#include <grain/io/write_error.hpp>
#include <grain/simulation/params.hpp>

#include <algorithm>
#include <array>
#include <bit>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <optional>
#include <ostream>
#include <string>
#include <string_view>
#include <system_error>
#include <unordered_map>
#include <utility>
#include <vector>

namespace grain::io {

/// A group named in a state file.
struct StateGroup {
  std::string name;                 ///< its name
  std::vector<std::size_t> members; ///< its particles: indices into ParticleState::particles
};

/// What a state file holds.
template <int D>
struct ParticleState {
  std::vector<ParticleSpec<D>> particles; ///< in the order of the file
  std::vector<StateGroup> groups;         ///< in the order they first appear (CSV only)
  /// Time [s] of the simulation that wrote the file; NaN if the file does not say.
  double time = std::numeric_limits<double>::quiet_NaN();
  long step = -1; ///< its step count; -1 if the file does not say (VTK files)
};

/// Options of read_state_csv and read_state_vtk.
struct StateReadOptions {
  /// The number of materials: a material index at or above it is an InputError. Unset: any index
  /// of 32 bits (the readers that take a simulation check against its materials).
  std::optional<std::size_t> materials{};
  /// In a thermal simulation, read the temperatures; false leaves them unset (NaN: the
  /// simulation's initial temperature when loaded).
  bool temperatures = true;
};

/// Options of load_state.
struct StateLoadOptions {
  bool groups = true; ///< add the state's groups to the simulation (add_group)
};

namespace detail {

inline constexpr std::int64_t largest_state_id = std::numeric_limits<std::int64_t>::max() - 1;

/// The bytes of the file `path`; InputError naming `who` if it is missing or cannot be read.
inline std::string read_state_bytes(const char* who, const std::string& path) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::file_status st = fs::status(path, ec);
  const std::string head = std::string(who) + ": file = '" + path + "' is invalid: ";
  if (!fs::exists(st)) throw InputError(head + "it does not exist; valid: a readable file");
  if (!fs::is_regular_file(st))
    throw InputError(head + "it is not a regular file; valid: a readable file");
  errno = 0;
  std::ifstream in(path, std::ios::binary);
  if (!in)
    throw InputError(head + "it cannot be opened (" +
                     (errno != 0 ? std::string(std::strerror(errno)) : std::string("no reason")) +
                     "); valid: a readable file");
  std::string text;
  char buffer[1 << 16];
  while (in.read(buffer, sizeof buffer) || in.gcount() > 0)
    text.append(buffer, static_cast<std::size_t>(in.gcount()));
  if (in.bad()) throw InputError(head + "it cannot be read; valid: a readable file");
  return text;
}

/// Parses the whole of `t` as a double (a leading '+' allowed); false if it is not one.
inline bool parse_state_double(std::string_view t, double& v) {
  if (!t.empty() && t.front() == '+') {
    t.remove_prefix(1);
    if (!t.empty() && (t.front() == '+' || t.front() == '-')) return false;
  }
  if (t.empty()) return false;
  const auto [end, ec] = std::from_chars(t.data(), t.data() + t.size(), v);
  return ec == std::errc() && end == t.data() + t.size();
}
/// Parses the whole of `t` as an integer of type T (a leading '+' allowed); false if it is not
/// one or does not fit.
template <class T>
bool parse_state_integer(std::string_view t, T& v) {
  if (!t.empty() && t.front() == '+') {
    t.remove_prefix(1);
    if (!t.empty() && (t.front() == '+' || t.front() == '-')) return false;
  }
  if (t.empty()) return false;
  const auto [end, ec] = std::from_chars(t.data(), t.data() + t.size(), v);
  return ec == std::errc() && end == t.data() + t.size();
}

/// "valid range: <r>" for a `valid` of the form "range <r>", else "valid: <valid>".
inline std::string state_valid(const std::string& valid) {
  return valid.rfind("range ", 0) == 0 ? "valid range: " + valid.substr(6) : "valid: " + valid;
}

/// The number of material indices a reader accepts, and the text of what is valid.
inline std::pair<std::uint64_t, std::string> state_materials(const StateReadOptions& o) {
  constexpr std::uint64_t any = std::uint64_t{1} << 32;
  if (!o.materials) return {any, "range [0, " + std::to_string(any - 1) + "] (a material index)"};
  const std::uint64_t m = std::min<std::uint64_t>(*o.materials, any);
  if (m == 0) return {0, "none (the simulation has no materials; add them before reading)"};
  return {m, "range [0, " + std::to_string(m - 1) + "] (the indices of the simulation's " +
                 std::to_string(m) + " materials)"};
}

/// `t` without the spaces and tabs at either end.
inline std::string_view trim_state(std::string_view t) {
  while (!t.empty() && (t.front() == ' ' || t.front() == '\t'))
    t.remove_prefix(1);
  while (!t.empty() && (t.back() == ' ' || t.back() == '\t'))
    t.remove_suffix(1);
  return t;
}

/// Appends the shortest text that reads back as `v`.
template <class T>
void append_number(std::string& out, T v) {
  char b[64];
  const auto r = std::to_chars(b, b + sizeof b, v);
  out.append(b, r.ptr);
}

/// A CSV cell: quoted if it holds a comma or a quote.
inline void append_cell(std::string& out, std::string_view s) {
  if (s.find_first_of(",\"") == std::string_view::npos) {
    out.append(s);
    return;
  }
  out += '"';
  for (const char c : s) {
    if (c == '"') out += '"';
    out += c;
  }
  out += '"';
}

/// Splits a CSV line into cells (separated by commas, trimmed of spaces and tabs; a cell in
/// double quotes keeps its text, "" in it a quote). Returns the reason if the line is not one.
inline std::string split_state_cells(std::string_view line, std::vector<std::string>& cells) {
  std::size_t count = 0;
  std::size_t k = 0;
  for (;;) {
    if (cells.size() <= count) cells.emplace_back();
    std::string& cell = cells[count++];
    cell.clear();
    while (k < line.size() && (line[k] == ' ' || line[k] == '\t'))
      ++k;
    if (k < line.size() && line[k] == '"') {
      ++k;
      bool closed = false;
      while (k < line.size()) {
        if (line[k] == '"') {
          if (k + 1 < line.size() && line[k + 1] == '"') {
            cell += '"';
            k += 2;
            continue;
          }
          ++k;
          closed = true;
          break;
        }
        cell += line[k++];
      }
      if (!closed) return "a quote is not closed";
      while (k < line.size() && (line[k] == ' ' || line[k] == '\t'))
        ++k;
      if (k < line.size() && line[k] != ',')
        return "text after the closing quote of cell " + std::to_string(count);
    } else {
      const std::size_t end = std::min(line.find(',', k), line.size());
      cell.assign(trim_state(line.substr(k, end - k)));
      k = end;
    }
    if (k >= line.size()) break;
    ++k; // the comma
  }
  cells.resize(count);
  return {};
}

/// What a column of a state file holds.
enum class StateColumn : std::uint8_t {
  id,
  radius,
  material,
  position,
  velocity,
  omega,
  temperature,
  fixed,
  groups,
  other_dimension, // a column of the other dimension's files: an error
  unknown          // ignored
};

struct StateColumnName {
  const char* name;
  const char* unit;
  StateColumn kind;
  int component;
};

/// The columns of a D-dimensional state file, in the order they are written.
template <int D>
constexpr auto state_columns() {
  if constexpr (D == 3)
    return std::array<StateColumnName, 15>{{{"id", "", StateColumn::id, 0},
                                            {"radius", "m", StateColumn::radius, 0},
                                            {"material", "", StateColumn::material, 0},
                                            {"x", "m", StateColumn::position, 0},
                                            {"y", "m", StateColumn::position, 1},
                                            {"z", "m", StateColumn::position, 2},
                                            {"vx", "m/s", StateColumn::velocity, 0},
                                            {"vy", "m/s", StateColumn::velocity, 1},
                                            {"vz", "m/s", StateColumn::velocity, 2},
                                            {"omegax", "rad/s", StateColumn::omega, 0},
                                            {"omegay", "rad/s", StateColumn::omega, 1},
                                            {"omegaz", "rad/s", StateColumn::omega, 2},
                                            {"temperature", "K", StateColumn::temperature, 0},
                                            {"fixed", "", StateColumn::fixed, 0},
                                            {"groups", "", StateColumn::groups, 0}}};
  else
    return std::array<StateColumnName, 11>{{{"id", "", StateColumn::id, 0},
                                            {"radius", "m", StateColumn::radius, 0},
                                            {"material", "", StateColumn::material, 0},
                                            {"x", "m", StateColumn::position, 0},
                                            {"y", "m", StateColumn::position, 1},
                                            {"vx", "m/s", StateColumn::velocity, 0},
                                            {"vy", "m/s", StateColumn::velocity, 1},
                                            {"omega", "rad/s", StateColumn::omega, 0},
                                            {"temperature", "K", StateColumn::temperature, 0},
                                            {"fixed", "", StateColumn::fixed, 0},
                                            {"groups", "", StateColumn::groups, 0}}};
}

/// The names of the other dimension's columns that this dimension does not have.
template <int D>
constexpr auto other_dimension_columns() {
  if constexpr (D == 3)
    return std::array<const char*, 1>{"omega"};
  else
    return std::array<const char*, 5>{"z", "vz", "omegax", "omegay", "omegaz"};
}

/// The header text of a column: "name [unit]" or "name".
inline std::string state_header(const StateColumnName& c) {
  return *c.unit ? std::string(c.name) + " [" + c.unit + "]" : std::string(c.name);
}

/// A group name the CSV state format can hold: not empty, no ';' or line break, no space or tab
/// at either end (the reader trims them).
inline bool state_group_name_ok(std::string_view name) {
  return !name.empty() && name.find_first_of(";\n\r") == std::string_view::npos &&
         trim_state(name).size() == name.size();
}

/// The reader of a CSV state file: checks every value as it is read.
template <int D>
class StateCsvReader {
public:
  StateCsvReader(const std::string& path, const StateReadOptions& options, bool thermal)
      : path_(path), options_(options), thermal_(thermal), materials_(state_materials(options)) {}

  ParticleState<D> read() {
    const std::string text = read_state_bytes(who, path_);
    std::string_view rest(text);
    if (rest.substr(0, 3) == "\xEF\xBB\xBF") rest.remove_prefix(3); // a UTF-8 byte order mark
    ParticleState<D> state;
    std::vector<std::string> cells;
    std::unordered_map<std::int64_t, std::size_t> id_lines;
    std::unordered_map<std::string, std::size_t> group_index;
    std::vector<std::string> names; // of the groups of the particle being read
    bool header = false;
    long declared = -1; // particles=N of the comment
    std::size_t declared_line = 0;
    while (!rest.empty()) {
      const std::size_t end = rest.find('\n');
      std::string_view line = rest.substr(0, end);
      rest.remove_prefix(end == std::string_view::npos ? rest.size() : end + 1);
      ++line_;
      if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
      if (trim_state(line).empty()) continue;
      if (line.front() == '#') {
        if (!header && line.substr(0, 13) == "# grain state") {
          declared = comment(line.substr(13), state);
          if (declared >= 0) declared_line = line_;
        }
        continue;
      }
      if (const std::string why = split_state_cells(line, cells); !why.empty())
        fail("line", quote(line), "a line of comma-separated cells (" + why + ")");
      if (!header) {
        read_header(cells, line);
        header = true;
        continue;
      }
      if (cells.size() != columns_.size())
        fail("cells", std::to_string(cells.size()),
             std::to_string(columns_.size()) + ", one per column of the header on line " +
                 std::to_string(header_line_) +
                 (cells.size() < columns_.size() ? " (a line cut short?)" : ""));
      const std::size_t index = state.particles.size();
      ParticleSpec<D> p;
      names.clear();
      for (std::size_t c = 0; c < cells.size(); ++c)
        read_cell(c, cells[c], p, names);
      if (p.id >= 0) {
        const auto [it, fresh] = id_lines.emplace(p.id, line_);
        if (!fresh)
          fail(header_text_[id_column_], "'" + std::to_string(p.id) + "'",
               "an id no other particle has (line " + std::to_string(it->second) + " has it)");
      }
      for (const auto& name : names) {
        const auto [it, fresh] = group_index.emplace(name, state.groups.size());
        if (fresh) state.groups.push_back({name, {}});
        auto& members = state.groups[it->second].members;
        if (members.empty() || members.back() != index) members.push_back(index);
      }
      state.particles.push_back(p);
    }
    if (!header) {
      line_ = std::max<std::size_t>(line_, 1);
      fail("header", text.empty() ? "'' (the file is empty)" : "none (only comments)",
           "a line naming the columns (x, y" + std::string(D == 3 ? ", z" : "") +
               ", radius, ...) before the particles");
    }
    if (declared >= 0 && static_cast<std::size_t>(declared) != state.particles.size()) {
      line_ = std::max(line_, declared_line);
      fail("particle lines", std::to_string(state.particles.size()),
           std::to_string(declared) + ", the number given on line " +
               std::to_string(declared_line) + " (particles=" + std::to_string(declared) +
               "; a file cut short?)");
    }
    return state;
  }

private:
  static constexpr const char* who = "grain::io::read_state_csv";
  std::string path_;
  StateReadOptions options_;
  bool thermal_;
  std::pair<std::uint64_t, std::string> materials_;
  std::size_t line_ = 0, header_line_ = 0, id_column_ = 0;
  std::vector<StateColumnName> columns_; // one per cell of the header
  std::vector<std::string> header_text_;

  [[noreturn]] void fail(std::string_view name, const std::string& value,
                         const std::string& valid) const {
    throw InputError(std::string(who) + ": '" + path_ + "' line " + std::to_string(line_) + ": " +
                     std::string(name) + " = " + value + " is invalid; " + state_valid(valid));
  }
  static std::string shorten(std::string_view s) {
    return s.size() <= 80 ? std::string(s) : std::string(s.substr(0, 77)) + "...";
  }
  /// 's' (shortened), for messages.
  static std::string quote(std::string_view s) {
    std::string q = "'";
    q += shorten(s);
    q += '\'';
    return q;
  }

  /// Reads "# grain state, dim=3, time=..., step=..., particles=N"; returns N or -1.
  long comment(std::string_view rest, ParticleState<D>& state) {
    long declared = -1;
    while (!rest.empty()) {
      const std::size_t comma = rest.find(',');
      const std::string_view item = trim_state(rest.substr(0, comma));
      rest.remove_prefix(comma == std::string_view::npos ? rest.size() : comma + 1);
      const std::size_t eq = item.find('=');
      if (eq == std::string_view::npos) continue;
      const std::string_view key = trim_state(item.substr(0, eq));
      const std::string_view value = trim_state(item.substr(eq + 1));
      const std::string shown = quote(value);
      if (key == "dim") {
        int dim = 0;
        if (!parse_state_integer(value, dim) || dim != D)
          fail("dim", shown,
               std::to_string(D) + ", the dimension of the simulation (a " +
                   (D == 3 ? "3D simulation reads files of spheres"
                           : "2D simulation reads files "
                             "of disks") +
                   ")");
      } else if (key == "time") {
        double t = 0.0;
        if (!parse_state_double(value, t) || !std::isfinite(t))
          fail("time", shown, "range a finite number [s]");
        state.time = t;
      } else if (key == "step") {
        long s = 0;
        if (!parse_state_integer(value, s) || s < 0) fail("step", shown, "range [0, inf)");
        state.step = s;
      } else if (key == "particles") {
        long n = 0;
        if (!parse_state_integer(value, n) || n < 0) fail("particles", shown, "range [0, inf)");
        declared = n;
      }
    }
    return declared;
  }

  void read_header(const std::vector<std::string>& cells, std::string_view line) {
    header_line_ = line_;
    constexpr auto known = state_columns<D>();
    constexpr auto other = other_dimension_columns<D>();
    std::array<int, known.size()> found{};
    for (const std::string& cell : cells) {
      std::string_view name = cell, unit;
      bool has_unit = false;
      if (const std::size_t open = name.find('['); open != std::string_view::npos) {
        const std::string_view tail = trim_state(name.substr(open + 1));
        if (!tail.empty() && tail.back() == ']') {
          unit = trim_state(tail.substr(0, tail.size() - 1));
          name = trim_state(name.substr(0, open));
          has_unit = true;
        }
      }
      StateColumnName column{"", "", StateColumn::unknown, 0};
      for (std::size_t k = 0; k < known.size(); ++k) {
        if (name != known[k].name) continue;
        column = known[k];
        if (has_unit && unit != known[k].unit && !(*known[k].unit == 0 && unit == "-"))
          fail("unit of column '" + cell + "'", quote(unit),
               *known[k].unit ? std::string(known[k].unit) + " (SI units)"
                              : std::string("none, '-' or '' (a number without unit)"));
        if (found[k]++) fail("column", quote(cell), "a column named once (it is named twice)");
      }
      for (const char* o : other)
        if (name == o)
          fail("column", quote(cell),
               std::string("a column of a ") + (D == 3 ? "3D" : "2D") +
                   " state file (this column is of " + (D == 3 ? "2D" : "3D") + " files)");
      if (column.kind == StateColumn::temperature && (!thermal_ || !options_.temperatures))
        column.kind = StateColumn::unknown; // not read
      if (column.kind == StateColumn::id) id_column_ = columns_.size();
      columns_.push_back(column);
      header_text_.push_back(cell);
    }
    std::string missing;
    for (std::size_t k = 0; k < known.size(); ++k) {
      const StateColumn kind = known[k].kind;
      const bool required = kind == StateColumn::position || kind == StateColumn::radius;
      bool needed = required && !found[k];
      // a vector whole or not at all
      if (!found[k] && (kind == StateColumn::velocity || kind == StateColumn::omega))
        for (std::size_t j = 0; j < known.size(); ++j)
          needed = needed || (known[j].kind == kind && found[j]);
      if (needed) missing += (missing.empty() ? "'" : ", '") + state_header(known[k]) + "'";
    }
    if (!missing.empty()) {
      std::string all;
      for (const auto& c : known)
        all += (all.empty() ? "" : ", ") + state_header(c);
      fail("header", quote(line),
           "a header with the columns " + missing + " too (columns: " + all + "; x, y" +
               (D == 3 ? ", z" : "") +
               " and radius are required, a vector is given whole or not at all)");
    }
  }

  void read_cell(std::size_t c, const std::string& cell, ParticleSpec<D>& p,
                 std::vector<std::string>& names) const {
    const StateColumnName& col = columns_[c];
    if (col.kind == StateColumn::unknown) return;
    const std::string& head = header_text_[c];
    const auto shown = [&] { return quote(cell); };
    const auto number = [&](const char* range, auto ok) {
      double v = 0.0;
      if (!parse_state_double(cell, v) || !ok(v))
        fail(head, shown(), std::string("range ") + range);
      return v;
    };
    const auto finite = [](double v) { return std::isfinite(v); };
    if (cell.empty() && col.kind != StateColumn::position && col.kind != StateColumn::radius)
      return; // the default
    switch (col.kind) {
    case StateColumn::id: {
      std::int64_t id = 0;
      if (!parse_state_integer(cell, id) || id < -1 || id > largest_state_id)
        fail(head, shown(),
             "range [0, " + std::to_string(largest_state_id) + "], or -1 (the next free id)");
      p.id = id;
      break;
    }
    case StateColumn::radius:
      p.radius = number("(0, inf) m", [](double v) { return std::isfinite(v) && v > 0.0; });
      break;
    case StateColumn::material: {
      std::uint64_t m = 0;
      if (!parse_state_integer(cell, m) || m >= materials_.first)
        fail(head, shown(), materials_.second);
      p.material = static_cast<std::uint32_t>(m);
      break;
    }
    case StateColumn::position:
      p.position[col.component] = number("a finite number [m]", finite);
      break;
    case StateColumn::velocity:
      p.velocity[col.component] = number("a finite number [m/s]", finite);
      break;
    case StateColumn::omega:
      if constexpr (D == 2)
        p.omega = number("a finite number [rad/s]", finite);
      else
        p.omega[col.component] = number("a finite number [rad/s]", finite);
      break;
    case StateColumn::temperature:
      p.temperature = number("[0, inf) K", [](double v) { return std::isfinite(v) && v >= 0.0; });
      break;
    case StateColumn::fixed:
      if (cell != "0" && cell != "1") fail(head, shown(), "0 (free) or 1 (fixed)");
      p.fixed = cell == "1";
      break;
    case StateColumn::groups: {
      std::string_view rest = cell;
      while (!rest.empty()) {
        const std::size_t semi = rest.find(';');
        const std::string_view name = trim_state(rest.substr(0, semi));
        rest.remove_prefix(semi == std::string_view::npos ? rest.size() : semi + 1);
        if (name.empty()) continue;
        if (name == "all")
          fail(head, shown(),
               "group names separated by ';', none of them 'all' (the reserved group of every "
               "particle)");
        if (std::find(names.begin(), names.end(), name) == names.end()) names.emplace_back(name);
      }
      break;
    }
    default:
      break;
    }
  }
};

/// Big-endian unsigned number of n bytes at p.
inline std::uint64_t big_endian(const char* p, int n) {
  std::uint64_t v = 0;
  for (int k = 0; k < n; ++k)
    v = (v << 8) | static_cast<unsigned char>(p[k]);
  return v;
}

/// The reader of a legacy VTK particle file of write_particles_vtk.
template <int D>
class StateVtkReader {
public:
  StateVtkReader(const std::string& path, const StateReadOptions& options, bool thermal)
      : path_(path), options_(options), thermal_(thermal), materials_(state_materials(options)) {}

  ParticleState<D> read() {
    text_ = read_state_bytes(who, path_);
    ParticleState<D> state;
    std::string_view line;
    if (!next_line(line) || line.substr(0, 22) != "# vtk DataFile Version")
      fail("'# vtk DataFile Version 3.0' on line 1 (a legacy VTK file; a particle file of "
           "grain::io::write_particles_vtk)");
    if (!next_line(line)) fail("a title on line 2");
    if (line.substr(0, 11) == "grain walls" || line.substr(0, 14) == "grain contacts")
      fail("a particle file (write_particles_vtk, io::vtk's <prefix>_particles_NNNNNN.vtk); "
           "this is a " +
           std::string(line[6] == 'w' ? "wall" : "contact") + " file ('" + shorten(line) + "')");
    if (line.substr(0, 19) == "grain particles t =") {
      double t = 0.0;
      if (parse_state_double(trim_state(line.substr(19)), t) && std::isfinite(t)) state.time = t;
    }
    if (!next_line(line)) fail("ASCII or BINARY on line 3");
    const std::string_view format = trim_state(line);
    if (format != "ASCII" && format != "BINARY")
      fail("ASCII or BINARY on line 3, not '" + shorten(line) + "'");
    binary_ = format == "BINARY";
    auto words = keyword("DATASET POLYDATA");
    if (words.size() != 2 || words[0] != "DATASET" || words[1] != "POLYDATA")
      fail("DATASET POLYDATA (the polydata of write_particles_vtk)");

    std::size_t n = 0; // points
    bool points = false, point_data = false;
    std::vector<double> x;
    struct Array {
      std::string name;
      std::size_t comps = 1;
      Type type = Type::f64;
      std::string where;
      std::vector<double> d;
      std::vector<std::int64_t> i;
    };
    std::vector<Array> arrays;
    std::string points_at;
    std::vector<std::string> seen;
    for (;;) {
      words = keyword(nullptr);
      if (words.empty()) break;
      const std::string at = location();
      const std::string where = std::string(words[0]) + " at " + at;
      if (words[0] == "POINTS" && !points) {
        if (words.size() != 3) fail("POINTS <count> double");
        n = count(words[1], "POINTS <count>");
        if (words[2] != "double")
          fail("POINTS <count> double (the points of write_particles_vtk), not '" +
               std::string(words[2]) + "'");
        check_room(n, 3, Type::f64, "POINTS " + std::to_string(n));
        points_at = where;
        x.reserve(3 * n);
        values(3 * n, Type::f64, [&](double v, std::int64_t) { x.push_back(v); });
        points = true;
      } else if (words[0] == "VERTICES" && points && !point_data) {
        if (words.size() != 3) fail("VERTICES <cells> <size>");
        (void)count(words[1], "VERTICES <cells>");
        const std::size_t size = count(words[2], "VERTICES <cells> <size>");
        check_room(size, 1, Type::i32, "VERTICES with " + std::to_string(size) + " numbers");
        values(size, Type::i32, [](double, std::int64_t) {});
      } else if (words[0] == "POINT_DATA" && points && !point_data) {
        if (words.size() != 2) fail("POINT_DATA <count>");
        const std::size_t m = count(words[1], "POINT_DATA <count>");
        if (m != n)
          fail("POINT_DATA " + std::to_string(n) + " (one value per point), not POINT_DATA " +
               std::to_string(m));
        point_data = true;
      } else if ((words[0] == "SCALARS" || words[0] == "VECTORS") && point_data) {
        const bool vectors = words[0] == "VECTORS";
        if (vectors ? words.size() != 3 : (words.size() != 3 && words.size() != 4))
          fail(vectors ? "VECTORS <name> <type>" : "SCALARS <name> <type> [components]");
        const std::string name(words[1]);
        if (std::find(seen.begin(), seen.end(), name) != seen.end())
          fail("arrays of different names ('" + shorten(name) + "' is there twice)");
        seen.push_back(name);
        const Type type = type_of(words[2]);
        std::size_t comps = vectors ? 3 : 1;
        if (words.size() == 4) {
          comps = count(words[3], "SCALARS <name> <type> <components>");
          if (comps < 1 || comps > 4)
            fail("SCALARS <name> <type> <components>, components in [1, 4], not " +
                 std::to_string(comps));
        }
        if (!vectors) {
          const auto table = keyword("LOOKUP_TABLE <name>");
          if (table.size() != 2 || table[0] != "LOOKUP_TABLE")
            fail("LOOKUP_TABLE <name> after SCALARS " + shorten(name));
        }
        check_room(n, comps, type, "array '" + shorten(name) + "'");
        const bool keep = name == "id" || name == "radius" || name == "velocity" ||
                          name == "omega" || name == "material" ||
                          (name == "temperature" && thermal_ && options_.temperatures);
        if (name == "orientation" && comps != (D == 3 ? 4u : 1u))
          fail(where, "array 'orientation'", std::to_string(comps) + " components",
               std::string(D == 3 ? "4, the quaternion of a sphere (this file is of a 2D "
                                    "simulation: its orientations are angles)"
                                  : "1, the angle of a disk (this file is of a 3D simulation: its "
                                    "orientations are quaternions)"));
        if (!keep) {
          values(n * comps, type, [](double, std::int64_t) {});
          continue;
        }
        Array a{name, comps, type, at, {}, {}};
        const bool integer = type != Type::f64;
        const bool want_integer = name == "id" || name == "material";
        const std::size_t want_comps = name == "velocity" || name == "omega" ? 3 : 1;
        if (integer != want_integer || comps != want_comps)
          fail(where, "array '" + name + "'",
               std::string(words[2]) + " with " + std::to_string(comps) +
                   (comps == 1 ? " component" : " components"),
               std::string(want_integer ? "an integer type (int, long, vtktypeint64)" : "double") +
                   " with " + std::to_string(want_comps) +
                   (want_comps == 1 ? " component" : " components") +
                   ", as write_particles_vtk writes it");
        if (integer)
          a.i.reserve(n);
        else
          a.d.reserve(n * comps);
        values(n * comps, type, [&](double v, std::int64_t k) {
          if (integer)
            a.i.push_back(k);
          else
            a.d.push_back(v);
        });
        arrays.push_back(std::move(a));
      } else {
        fail("POINTS, VERTICES, POINT_DATA, SCALARS or VECTORS, in this order (the sections of a "
             "particle file), not '" +
             shorten(words[0]) + "'" +
             (words[0] == "LINES" || words[0] == "POLYGONS" || words[0] == "CELL_DATA"
                  ? " (a wall or contact file?)"
                  : ""));
      }
    }
    if (!points) fail("POINTS <count> double (the particle centres)");
    const auto find = [&](const char* name) -> const Array* {
      for (const auto& a : arrays)
        if (a.name == name) return &a;
      return nullptr;
    };
    const Array* radius = find("radius");
    if (!radius)
      fail("a point array 'radius' (write the file with io::fields::radius, or every field)");
    const Array* id = find("id");
    const Array* material = find("material");
    const Array* velocity = find("velocity");
    const Array* omega = find("omega");
    const Array* temperature = find("temperature");
    state.particles.resize(n);
    std::unordered_map<std::int64_t, std::size_t> ids;
    for (std::size_t k = 0; k < n; ++k) {
      ParticleSpec<D>& p = state.particles[k];
      const auto bad = [&](const Array* a, const std::string& name, const std::string& value,
                           const std::string& valid) {
        fail(a ? "array '" + a->name + "' at " + a->where : points_at,
             "point " + std::to_string(k) + ": " + name, value, valid);
      };
      for (int d = 0; d < 3; ++d) {
        const double v = x[3 * k + d];
        if (d < D) {
          if (!std::isfinite(v))
            bad(nullptr, std::string(1, "xyz"[d]), to_text(v), "range a finite number [m]");
          p.position[d] = v;
        } else if (v != 0.0) {
          bad(nullptr, "z", to_text(v),
              "0 (a 2D simulation reads the files of disks, whose centres lie in z = 0)");
        }
      }
      p.radius = radius->d[k];
      if (!(std::isfinite(p.radius) && p.radius > 0.0))
        bad(radius, "radius", to_text(p.radius), "range (0, inf) m");
      if (id) {
        const std::int64_t v = id->i[k];
        if (v < -1 || v > largest_state_id)
          bad(id, "id", std::to_string(v),
              "range [0, " + std::to_string(largest_state_id) + "], or -1 (the next free id)");
        if (v >= 0) {
          const auto [it, fresh] = ids.emplace(v, k);
          if (!fresh)
            bad(id, "id", std::to_string(v),
                "an id no other point has (point " + std::to_string(it->second) + " has it)");
        }
        p.id = v;
      }
      if (material) {
        const std::int64_t v = material->i[k];
        if (v < 0 || static_cast<std::uint64_t>(v) >= materials_.first)
          bad(material, "material", std::to_string(v), materials_.second);
        p.material = static_cast<std::uint32_t>(v);
      }
      const auto vector = [&](const Array* a, const char* name, const char* unit, auto& out) {
        if (!a) return;
        for (int d = 0; d < 3; ++d) {
          const double v = a->d[3 * k + d];
          const std::string component = std::string(name) + " " + "xyz"[d];
          if (!std::isfinite(v))
            bad(a, component, to_text(v), std::string("range a finite number [") + unit + "]");
          const bool in_plane = std::string_view(name) == "velocity" ? d < 2 : d == 2;
          if constexpr (D == 2) {
            if (!in_plane && v != 0.0)
              bad(a, component, to_text(v),
                  "0 (a 2D simulation reads the files of disks: velocities (vx, vy, 0), angular "
                  "velocities (0, 0, w))");
            if (in_plane) {
              if constexpr (std::is_same_v<std::decay_t<decltype(out)>, double>)
                out = v;
              else
                out[d] = v;
            }
          } else {
            out[d] = v;
          }
        }
      };
      vector(velocity, "velocity", "m/s", p.velocity);
      vector(omega, "omega", "rad/s", p.omega);
      if (temperature) {
        const double t = temperature->d[k];
        if (!(std::isfinite(t) && t >= 0.0))
          bad(temperature, "temperature", to_text(t), "range [0, inf) K");
        p.temperature = t;
      }
    }
    return state;
  }

private:
  enum class Type : std::uint8_t { f64, i32, i64 };
  static constexpr const char* who = "grain::io::read_state_vtk";
  std::string path_;
  StateReadOptions options_;
  bool thermal_;
  std::pair<std::uint64_t, std::string> materials_;
  std::string text_{};
  std::size_t pos_ = 0, line_ = 1;
  std::size_t at_line_ = 1, at_byte_ = 0; // where the last line or number read began
  bool binary_ = false;

  static std::string to_text(double v) { return grain::detail::to_text(v); }
  static std::string shorten(std::string_view s) {
    std::string out;
    for (const char c : s.substr(0, 60))
      out += (c >= 32 && c < 127) ? c : '?';
    return s.size() > 60 ? out + "..." : out;
  }
  /// Where the reader is: the line, or in a binary file the byte.
  std::string location() const {
    return binary_ ? "byte " + std::to_string(at_byte_) : "line " + std::to_string(at_line_);
  }
  [[noreturn]] void fail(const std::string& expected) const {
    throw InputError(std::string(who) + ": '" + path_ + "' " + location() + ": the file is not " +
                     "a particle file of grain::io::write_particles_vtk; expected " + expected);
  }
  [[noreturn]] void fail(const std::string& where, const std::string& name,
                         const std::string& value, const std::string& valid) const {
    throw InputError(std::string(who) + ": '" + path_ + "' " + where + ", " + name + " = " + value +
                     " is invalid; " + state_valid(valid));
  }

  /// The next line without its end; false at the end of the file.
  bool next_line(std::string_view& line) {
    at_line_ = line_;
    at_byte_ = pos_;
    if (pos_ >= text_.size()) return false;
    const std::size_t end = text_.find('\n', pos_);
    const std::size_t stop = end == std::string::npos ? text_.size() : end;
    line = std::string_view(text_).substr(pos_, stop - pos_);
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    pos_ = end == std::string::npos ? text_.size() : end + 1;
    if (end != std::string::npos) ++line_;
    return true;
  }
  /// Skips spaces, tabs and line ends.
  void skip_space() {
    while (pos_ < text_.size() && (text_[pos_] == ' ' || text_[pos_] == '\t' ||
                                   text_[pos_] == '\r' || text_[pos_] == '\n')) {
      if (text_[pos_] == '\n') ++line_;
      ++pos_;
    }
  }
  /// The words of the next line that is not blank; none at the end of the file (an error if
  /// `expected` names what must come).
  std::vector<std::string_view> keyword(const char* expected) {
    skip_space();
    std::vector<std::string_view> words;
    std::string_view line;
    if (!next_line(line)) {
      if (expected) fail(std::string(expected) + ", not the end of the file");
      return words;
    }
    std::size_t k = 0;
    while (k < line.size() && words.size() <= 8) {
      while (k < line.size() && (line[k] == ' ' || line[k] == '\t'))
        ++k;
      const std::size_t start = k;
      while (k < line.size() && line[k] != ' ' && line[k] != '\t')
        ++k;
      if (k > start) words.push_back(line.substr(start, k - start));
    }
    return words;
  }
  /// A count of a keyword line.
  std::size_t count(std::string_view word, const char* what) const {
    std::size_t v = 0;
    if (!parse_state_integer(word, v))
      fail(std::string(what) + ", a count, not '" + shorten(word) + "'");
    return v;
  }
  Type type_of(std::string_view word) const {
    if (word == "double") return Type::f64;
    if (word == "int") return Type::i32;
    if (word == "vtktypeint64" || (word == "long" && !binary_)) return Type::i64;
    fail(std::string("an array of type double, int or ") +
         (binary_ ? "vtktypeint64 (a binary file of write_particles_vtk)"
                  : "long (an ASCII file of write_particles_vtk)") +
         ", not '" + shorten(word) + "'");
  }
  static std::size_t bytes_of(Type t) { return t == Type::i32 ? 4 : 8; }
  /// Fails unless the rest of the file can hold n tuples of `comps` numbers of type t (at least
  /// 2 characters a number in an ASCII file).
  void check_room(std::size_t n, std::size_t comps, Type t, const std::string& what) const {
    const std::size_t left = text_.size() - pos_;
    const std::size_t each = comps * (binary_ ? bytes_of(t) : 2);
    const std::size_t most = binary_ ? left / each : (left + 1) / each;
    if (n > most)
      fail(what + " with at most " + std::to_string(most) + " tuples: the " + std::to_string(left) +
           " bytes left in the file cannot hold " + std::to_string(n));
  }
  /// Reads n numbers of type t and hands each to sink(as double, as integer).
  template <class Sink>
  void values(std::size_t n, Type t, Sink&& sink) {
    if (binary_) {
      const std::size_t b = bytes_of(t);
      if (n > (text_.size() - pos_) / b)
        fail(std::to_string(n) + " numbers, not the end of the file");
      at_byte_ = pos_;
      const char* p = text_.data() + pos_;
      for (std::size_t k = 0; k < n; ++k, p += b) {
        if (t == Type::f64)
          sink(std::bit_cast<double>(big_endian(p, 8)), 0);
        else if (t == Type::i32)
          sink(0.0, static_cast<std::int32_t>(static_cast<std::uint32_t>(big_endian(p, 4))));
        else
          sink(0.0, static_cast<std::int64_t>(big_endian(p, 8)));
      }
      pos_ += n * b;
      return;
    }
    for (std::size_t k = 0; k < n; ++k) {
      skip_space();
      const std::size_t start = pos_;
      at_line_ = line_;
      while (pos_ < text_.size() && text_[pos_] != ' ' && text_[pos_] != '\t' &&
             text_[pos_] != '\r' && text_[pos_] != '\n')
        ++pos_;
      const std::string_view token = std::string_view(text_).substr(start, pos_ - start);
      if (token.empty()) fail(std::to_string(n) + " numbers, not the end of the file");
      if (t == Type::f64) {
        double v = 0.0;
        if (!parse_state_double(token, v)) fail("a number, not '" + shorten(token) + "'");
        sink(v, 0);
      } else if (t == Type::i32) {
        std::int32_t v = 0;
        if (!parse_state_integer(token, v)) fail("a 32-bit integer, not '" + shorten(token) + "'");
        sink(0.0, v);
      } else {
        std::int64_t v = 0;
        if (!parse_state_integer(token, v)) fail("a 64-bit integer, not '" + shorten(token) + "'");
        sink(0.0, v);
      }
    }
  }
};

} // namespace detail

/// Writes the active particles of a simulation (of the group `group` only, if one is named) to a
/// CSV state file (see the file comment), in their current order. Throws InputError for a group
/// name the format cannot hold (empty, with ';' or a line break, or spaces at an end) or an
/// unknown group, and io::WriteError if the file cannot be written (leaving the file of that name
/// as it was).
template <class Sim>
void write_state_csv(const Sim& sim, const std::string& path, const std::string& group = "") {
  constexpr int D = Sim::dimension;
  const std::string who = "grain::io::write_state_csv";
  const auto& p = sim.particles();
  const std::vector<std::uint32_t>* subset = group.empty() ? nullptr : &sim.group_indices(group);
  // the groups of each particle (the reserved group "all" aside)
  std::vector<std::string> names;
  std::vector<std::vector<std::uint32_t>> member_of;
  for (const Group& g : sim.groups()) {
    if (g.everything) continue;
    const auto& members = sim.group_indices(g.name);
    if (members.empty()) continue;
    if (!detail::state_group_name_ok(g.name))
      throw InputError(who + ": group name = '" + g.name +
                       "' is invalid for a state file; valid: a name without ';' or line breaks "
                       "and without spaces at its ends");
    if (member_of.empty()) member_of.resize(p.size());
    for (const auto i : members)
      member_of[i].push_back(static_cast<std::uint32_t>(names.size()));
    names.push_back(g.name);
  }
  detail::require_output_folder(who, path);
  const std::size_t n = subset ? subset->size() : p.size();
  std::string line = "# grain state, dim=" + std::to_string(D) + ", time=";
  detail::append_number(line, sim.time());
  line += ", step=" + std::to_string(sim.step_count()) + ", particles=" + std::to_string(n) + "\n";
  for (const auto& c : detail::state_columns<D>()) {
    if (c.kind == detail::StateColumn::temperature && !Sim::thermal) continue;
    if (c.kind == detail::StateColumn::groups && names.empty()) continue;
    if (c.kind != detail::StateColumn::id) line += ',';
    line += detail::state_header(c);
  }
  line += '\n';
  detail::AtomicFile file(who, path);
  std::ostream& out = file.stream();
  out << line;
  for (std::size_t k = 0; k < n; ++k) {
    const std::size_t i = subset ? (*subset)[k] : k;
    line.clear();
    detail::append_number(line, p.id[i]);
    line += ',';
    detail::append_number(line, p.radius[i]);
    line += ',';
    detail::append_number(line, p.material[i]);
    for (int d = 0; d < D; ++d) {
      line += ',';
      detail::append_number(line, p.position[i][d]);
    }
    for (int d = 0; d < D; ++d) {
      line += ',';
      detail::append_number(line, p.velocity[i][d]);
    }
    if constexpr (D == 2) {
      line += ',';
      detail::append_number(line, p.omega[i]);
    } else {
      for (int d = 0; d < 3; ++d) {
        line += ',';
        detail::append_number(line, p.omega[i][d]);
      }
    }
    if constexpr (Sim::thermal) {
      line += ',';
      detail::append_number(line, p.temperature[i]);
    }
    line += sim.fixed_particle(i) ? ",1" : ",0";
    if (!names.empty()) {
      line += ',';
      std::string cell;
      for (const auto g : member_of[i])
        cell += (cell.empty() ? "" : ";") + names[g];
      detail::append_cell(line, cell);
    }
    line += '\n';
    out << line;
  }
  file.commit();
}

/// Reads a CSV state file for a simulation of type Sim (see the file comment): InputError naming
/// the file, the line, the column, the value and what is valid for anything add_particle would
/// refuse or the format does not allow.
template <class Sim>
ParticleState<Sim::dimension> read_state_csv(const std::string& path,
                                             const StateReadOptions& options = {}) {
  return detail::StateCsvReader<Sim::dimension>(path, options, Sim::thermal).read();
}
/// As read_state_csv<Sim>(path, options), with the materials checked against the simulation's.
template <class Sim>
ParticleState<Sim::dimension> read_state_csv(const Sim& sim, const std::string& path,
                                             StateReadOptions options = {}) {
  options.materials = sim.materials().size();
  return read_state_csv<Sim>(path, options);
}

/// Reads a legacy VTK particle file of write_particles_vtk (ASCII or binary) for a simulation of
/// type Sim (see the file comment): InputError naming the file, the place and what was expected
/// for a file of another form, and for any value add_particle would refuse.
template <class Sim>
ParticleState<Sim::dimension> read_state_vtk(const std::string& path,
                                             const StateReadOptions& options = {}) {
  return detail::StateVtkReader<Sim::dimension>(path, options, Sim::thermal).read();
}
/// As read_state_vtk<Sim>(path, options), with the materials checked against the simulation's.
template <class Sim>
ParticleState<Sim::dimension> read_state_vtk(const Sim& sim, const std::string& path,
                                             StateReadOptions options = {}) {
  options.materials = sim.materials().size();
  return read_state_vtk<Sim>(path, options);
}

/// Adds the particles of a state to a simulation (add_particle, in their order) and, with
/// `options.groups`, its groups (add_group, with the ids the particles got); returns the number
/// of particles added. Everything add_particle and add_group check is checked first, before
/// anything is added: a material the simulation does not have, a temperature in a mechanical
/// simulation, an id that a particle of the simulation has or had, an id twice, a group name
/// the simulation uses, are an InputError naming the particle (its index in the state) and leave
/// the simulation as it was. (Only an id that a particle waiting for its creation time has is
/// found by add_particle itself, after the particles before it were added.)
template <class Sim>
std::size_t load_state(Sim& sim, const ParticleState<Sim::dimension>& state,
                       const StateLoadOptions& options = {}) {
  const std::string who = "grain::io::load_state";
  const auto& ps = state.particles;
  std::vector<std::int64_t> taken = sim.particles().id;
  taken.insert(taken.end(), sim.removed_ids().begin(), sim.removed_ids().end());
  std::sort(taken.begin(), taken.end());
  std::unordered_map<std::int64_t, std::size_t> mine;
  for (std::size_t k = 0; k < ps.size(); ++k) {
    const auto& p = ps[k];
    const std::string obj =
        who + ": particle " + std::to_string(k) + " (id " + std::to_string(p.id) + ") of the state";
    if (p.id >= 0) {
      if (std::binary_search(taken.begin(), taken.end(), p.id))
        throw InputError(obj + ": id = " + std::to_string(p.id) +
                         " is invalid; valid: an id no particle of the simulation has or had");
      const auto [it, fresh] = mine.emplace(p.id, k);
      if (!fresh)
        throw InputError(obj + ": id = " + std::to_string(p.id) +
                         " is invalid; valid: an id no other particle of the state has (particle " +
                         std::to_string(it->second) + " has it)");
    }
    if (p.id > detail::largest_state_id)
      throw InputError(obj + ": id = " + std::to_string(p.id) + " is invalid; valid range: [0, " +
                       std::to_string(detail::largest_state_id) + "] or -1");
    if (!all_finite(p.position) || !all_finite(p.velocity) || !all_finite(p.omega))
      throw InputError(obj + ": position, velocity or omega is invalid (not finite); valid: "
                             "finite components");
    grain::detail::require_positive(obj, "radius", p.radius);
    if (p.material >= sim.materials().size())
      throw InputError(obj + ": material = " + std::to_string(p.material) +
                       " is invalid; valid range: [0, " + std::to_string(sim.materials().size()) +
                       ") (the indices of the simulation's materials)");
    if constexpr (Sim::thermal) {
      if (!std::isnan(p.temperature))
        grain::detail::require_non_negative(obj, "temperature [K]", p.temperature);
    } else if (!std::isnan(p.temperature)) {
      throw InputError(obj + ": temperature = " + grain::detail::to_text(p.temperature) +
                       " K is invalid: the simulation is mechanical; valid: unset (NaN), or read "
                       "the file with the mechanical simulation's type");
    }
    if (!(p.creation_time < std::numeric_limits<double>::infinity()) ||
        !(p.destruction_time > p.creation_time) || !(p.destruction_time > sim.time()))
      throw InputError(
          obj + ": creation_time, destruction_time = " + grain::detail::to_text(p.creation_time) +
          ", " + grain::detail::to_text(p.destruction_time) +
          " s is invalid; valid: creation_time < destruction_time, creation_time < "
          "inf, destruction_time > the simulation's time " +
          grain::detail::to_text(sim.time()) + " s");
  }
  if (options.groups) {
    for (std::size_t g = 0; g < state.groups.size(); ++g) {
      const auto& group = state.groups[g];
      const std::string obj = who + ": group '" + group.name + "' of the state";
      for (const auto& h : sim.groups())
        if (h.name == group.name)
          throw InputError(obj + ": name = '" + group.name +
                           "' is invalid; valid: a name no group of the simulation has");
      if (group.name.empty())
        throw InputError(obj + ": name = '' is invalid; valid: a non-empty name");
      for (std::size_t h = 0; h < g; ++h)
        if (state.groups[h].name == group.name)
          throw InputError(obj + ": name is invalid; valid: a name no other group of the state "
                                 "has");
      for (const auto m : group.members)
        if (m >= ps.size())
          throw InputError(obj + ": member = " + std::to_string(m) +
                           " is invalid; valid range: [0, " + std::to_string(ps.size()) +
                           ") (indices into the state's particles)");
    }
  }
  std::vector<std::int64_t> ids;
  ids.reserve(ps.size());
  for (const auto& p : ps)
    ids.push_back(sim.add_particle(p));
  if (options.groups) {
    for (const auto& group : state.groups) {
      std::vector<std::int64_t> members;
      members.reserve(group.members.size());
      for (const auto m : group.members)
        members.push_back(ids[m]);
      sim.add_group(group.name, std::move(members));
    }
  }
  return ps.size();
}

/// Adds the particles to a simulation (load_state of a state without groups).
template <class Sim>
std::size_t load_state(Sim& sim, const std::vector<ParticleSpec<Sim::dimension>>& particles) {
  ParticleState<Sim::dimension> state;
  state.particles = particles;
  return load_state(sim, state);
}

} // namespace grain::io
