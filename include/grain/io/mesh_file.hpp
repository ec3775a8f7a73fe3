#pragma once
/// \file mesh_file.hpp
/// Triangle meshes from and to files: `io::read_stl`, `io::read_obj` and `io::read_mesh` (by the
/// extension) give a `walls::TriangleMesh` for `add_obstacle`; `io::write_stl` writes one.
///
/// \code
/// auto hopper = grain::io::read_stl("hopper.stl", {.scale = 1e-3}); // a CAD file in mm
/// grain::add_obstacle(sim, hopper, {.name = "hopper", .material = steel});
/// \endcode
///
/// Formats
/// - STL, the stereolithography format of 3D Systems (its 1989 specification), binary or ASCII.
///   Binary: an 80-byte header (ignored), the facet count n as a little-endian 32-bit unsigned
///   integer, then n records of 50 bytes: the facet normal and the three corners as 12
///   little-endian IEEE-754 single-precision numbers, and a 16-bit attribute count (ignored). The
///   file has exactly 84 + 50 n bytes. ASCII: `solid <name>`, facets of `facet normal nx ny nz`,
///   `outer loop`, three `vertex x y z`, `endloop`, `endfacet`, then `endsolid <name>`; keywords
///   in any case, tokens separated by any white space (Windows line ends too), several solids
///   one after the other. A file is read as binary if its size is 84 + 50 n for the count n of
///   its header, also when the header starts with "solid" (as many binary writers' headers do);
///   otherwise as ASCII if it starts with the word "solid"; otherwise it is an error that names
///   the count and the size. The stored normals are ignored (an obstacle is touched from both
///   sides; any number is accepted there); the corners keep their order.
/// - Wavefront OBJ, the geometry statements of the OBJ format of Wavefront's Advanced Visualizer:
///   `v x y z [w]` (also `v x y z r g b`, vertex colours; w and the colours are ignored) and
///   `f c1 c2 c3 ...` with corners `v`, `v/vt`, `v/vt/vn` or `v//vn`. Vertex indices count from
///   1 in the order of the `v` lines; a negative index counts back from the last vertex defined
///   before the line (-1 is that vertex). A face of m > 3 corners is split into the fan
///   (c1, ck, ck+1), k = 2 ... m - 1. Texture and normal indices are checked to be integers and
///   otherwise ignored. Ignored statements: `vt`, `vn`, `vp`, `g`, `o`, `s`, `mg`, `usemtl`,
///   `mtllib`, `usemap`, `maplib`, `lod`, `bevel`, `c_interp`, `d_interp`, `shadow_obj`,
///   `trace_obj`, points and lines (`p`, `l`: no surface), comments (from `#` to the end of the
///   line) and blank lines. Any other statement (free-form curves and surfaces, a misspelling) is
///   an error. A line continued with a backslash is not supported.
///
/// Units: every coordinate of the file is multiplied by `MeshReadOptions::scale` (file units to
/// m: 1e-3 for a file in mm); all checks are made on the scaled coordinates [m].
///
/// Vertices: with `merge_vertices` (the default) corners with exactly equal scaled coordinates
/// become one vertex (an STL file repeats the corners of every facet), numbered in the order of
/// their first appearance in the triangles, so that a closed surface becomes a connected mesh
/// whose neighbouring triangles share their edges' vertices, as obstacles require
/// (walls/mesh_features.hpp). Without it an STL file gives three vertices per facet and an OBJ
/// file its `v` lines as they are (unused ones too). Triangles are in the order of the file.
///
/// Errors: `grain::InputError`, before anything is returned, naming the file, the place (the
/// line for ASCII STL and OBJ files, counted from 1; the facet for binary STL files, counted from
/// 0 as the triangles of the mesh are), the value and what is valid:
/// - a file that does not exist, a folder, a file that cannot be read;
/// - a binary STL whose size is not 84 + 50 n for the count n of its header (a truncated file);
/// - a line that does not fit the format: an unknown keyword, a missing one, a number that does
///   not parse or lies outside the range of double, a face with fewer than 3 corners, a vertex
///   index 0 or out of range;
/// - a corner with a coordinate that is not finite (in the file, or after scaling);
/// - a degenerate triangle: two equal corners, an area at or below `min_area`, or an area at or
///   below 1e-10 times half its longest edge squared (collinear corners; the limit of
///   `add_obstacle`, so that a mesh read is one that an obstacle accepts);
/// - a mesh without triangles (an empty file);
/// - `scale` not finite and positive, `min_area` not finite and non-negative.
/// A reader never allocates more than the file's size asks for: a binary header's count is
/// checked against the file size before any facet is read.
///
/// Writing: `write_stl` writes ASCII (coordinates in the shortest form that reads back to the
/// same double) or binary (coordinates rounded to single precision), with the normal
/// (b - a) x (c - a) / |...| of each triangle abc (0 0 0 for a degenerate one), through
/// io::detail::AtomicFile (io/atomic_file.hpp): a failed write throws io::WriteError and leaves
/// any previous file at the path as it was. A mesh that cannot be written as a valid file (no
/// triangles, an index out of range, a corner that is not finite, or beyond single precision for
/// a binary file) is refused with an InputError before anything is written.

#include <grain/core/error.hpp>
#include <grain/core/vector.hpp>
#include <grain/io/atomic_file.hpp>
#include <grain/io/write_error.hpp>
#include <grain/walls/mesh_features.hpp>

#include <algorithm>
#include <array>
#include <bit>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <istream>
#include <limits>
#include <ostream>
#include <string>
#include <string_view>
#include <system_error>
#include <unordered_map>
#include <utility>
#include <vector>

namespace grain::io {

/// How a mesh file is read.
struct MeshReadOptions {
  /// Factor from the file's units to m (1e-3 for a file in mm); finite and > 0.
  double scale = 1.0;
  /// [m^2] triangles whose area (after scaling) is at or below this are degenerate; >= 0.
  double min_area = 0.0;
  /// Corners with exactly equal coordinates become one vertex (see the file comment).
  bool merge_vertices = true;
};

namespace detail::mesh_file {

inline constexpr std::string_view space = " \t\r\n\v\f";

/// A line or token for a message: in quotes, at most 80 bytes, bytes other than printable ASCII
/// and tabs as \xNN.
inline std::string shown(std::string_view s) {
  while (!s.empty() && (s.back() == '\r' || s.back() == '\n'))
    s.remove_suffix(1);
  std::string out = "'";
  std::size_t n = 0;
  for (const char ch : s) {
    if (n++ == 80) {
      out += "...";
      break;
    }
    const auto c = static_cast<unsigned char>(ch);
    if ((c >= 0x20 && c < 0x7f) || c == '\t') {
      out += ch;
    } else {
      char hex[8];
      std::snprintf(hex, sizeof hex, "\\x%02X", static_cast<unsigned>(c));
      out += hex;
    }
  }
  return out + "'";
}

/// True if `s` holds bytes that a text file does not (control characters other than white space,
/// bytes above 0x7E are taken as text: UTF-8).
inline bool has_binary_bytes(std::string_view s) {
  for (const char ch : s) {
    const auto c = static_cast<unsigned char>(ch);
    if (c < 0x20 && space.find(ch) == std::string_view::npos) return true;
    if (c == 0x7f) return true;
  }
  return false;
}

/// "(x, y, z)" with 10 significant digits.
inline std::string point_text(const Vec3& p) { return walls::detail::mesh_point_text(p); }

/// Case-insensitive equality of a token and a lower-case keyword.
inline bool is_word(std::string_view token, std::string_view word) {
  if (token.size() != word.size()) return false;
  for (std::size_t k = 0; k < token.size(); ++k)
    if (std::tolower(static_cast<unsigned char>(token[k])) != word[k]) return false;
  return true;
}

enum class Parse { ok, not_a_number, out_of_range };

/// A number of the whole token (decimal or exponent form, an optional sign, nan and inf too).
inline Parse parse_double(std::string_view t, double& v) {
  if (!t.empty() && t.front() == '+') {
    t.remove_prefix(1);
    if (!t.empty() && (t.front() == '+' || t.front() == '-')) return Parse::not_a_number;
  }
  if (t.empty()) return Parse::not_a_number;
  const auto [end, ec] = std::from_chars(t.data(), t.data() + t.size(), v);
  if (ec == std::errc::invalid_argument || end != t.data() + t.size()) return Parse::not_a_number;
  if (ec == std::errc::result_out_of_range) return Parse::out_of_range;
  return ec == std::errc() ? Parse::ok : Parse::not_a_number;
}

/// An integer of the whole token (an optional sign).
inline Parse parse_integer(std::string_view t, long long& v) {
  if (!t.empty() && t.front() == '+') {
    t.remove_prefix(1);
    if (!t.empty() && (t.front() == '+' || t.front() == '-')) return Parse::not_a_number;
  }
  if (t.empty()) return Parse::not_a_number;
  const auto [end, ec] = std::from_chars(t.data(), t.data() + t.size(), v);
  if (ec == std::errc::invalid_argument || end != t.data() + t.size()) return Parse::not_a_number;
  if (ec == std::errc::result_out_of_range) return Parse::out_of_range;
  return ec == std::errc() ? Parse::ok : Parse::not_a_number;
}

/// What a token that is not a number is, for a message.
inline std::string not_a_number(std::string_view token, Parse p) {
  return shown(token) +
         (p == Parse::out_of_range ? " is outside the range of double" : " is not a number");
}

/// Throws InputError unless the options are valid.
inline void check_options(const std::string& label, const MeshReadOptions& o) {
  grain::require(std::isfinite(o.scale) && o.scale > 0.0, label, "scale", o.scale,
                 "(0, inf) (file units to m, e.g. 1e-3 for a file in mm)");
  grain::require(std::isfinite(o.min_area) && o.min_area >= 0.0, label, "min_area", o.min_area,
                 "[0, inf) m^2");
}

/// The size of the file at `path` [bytes]; throws InputError naming `label` if it is missing,
/// a folder or not a regular file.
inline std::uintmax_t file_size(const std::string& label, const std::string& path) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::file_status st = fs::status(path, ec);
  if (!fs::exists(st)) throw InputError(label + ": the file does not exist");
  if (fs::is_directory(st)) throw InputError(label + ": the path is a folder, not a file");
  if (!fs::is_regular_file(st)) throw InputError(label + ": the path is not a regular file");
  const std::uintmax_t size = fs::file_size(path, ec);
  if (ec) throw InputError(label + ": the file's size cannot be read (" + ec.message() + ")");
  return size;
}

/// Opens `path` for reading (after file_size has checked it).
inline void open(std::ifstream& in, const std::string& label, const std::string& path) {
  in.open(path, std::ios::in | std::ios::binary);
  if (!in) throw InputError(label + ": the file cannot be opened for reading");
}

/// A corner read from the file, scaled to m; throws InputError naming `where()` (e.g. "line 7
/// vertex") unless it is finite before and after scaling.
template <class Where>
Vec3 scaled_point(const std::string& label, const Where& where, double x, double y, double z,
                  double scale) {
  const Vec3 raw(x, y, z);
  if (!raw.allFinite())
    throw InputError(label + ": " + where() + " = " + point_text(raw) +
                     " is invalid; valid range: finite coordinates");
  const Vec3 p = scale * raw;
  if (!p.allFinite())
    throw InputError(label + ": " + where() + " times scale = " + point_text(p) +
                     " is invalid; valid range: finite coordinates [m] (the file's " +
                     point_text(raw) + " times scale = " + grain::detail::to_text(scale) + ")");
  return p;
}

/// Throws InputError naming `where()` (e.g. "facet 3") unless abc is a proper triangle: three
/// different corners, an area above min_area and above 1e-10 times half the longest edge squared
/// (the test of walls::MeshFeatures, evaluated the same way).
template <class Where>
void check_triangle(const std::string& label, const Where& where, const Vec3& a, const Vec3& b,
                    const Vec3& c, double min_area) {
  const auto corners = [&] { return point_text(a) + ", " + point_text(b) + ", " + point_text(c); };
  if (a == b || b == c || c == a)
    throw InputError(label + ": " + where() + " corners = " + corners() +
                     " is invalid; valid range: three different points (two corners are equal: "
                     "a degenerate triangle)");
  const Vec3 n = (b - a).cross(c - a);
  const double longest =
      std::max({(b - a).squaredNorm(), (c - b).squaredNorm(), (a - c).squaredNorm()});
  const double area = 0.5 * n.norm();
  if (!(n.norm() > 1e-10 * longest) || !(area > min_area) || !std::isfinite(area)) {
    const double floor = std::max(min_area, 0.5e-10 * longest);
    throw InputError(label + ": " + where() + " area = " + grain::detail::to_text(area) +
                     " is invalid; valid range: (" + grain::detail::to_text(floor) +
                     ", inf) m^2 (above min_area = " + grain::detail::to_text(min_area) +
                     " m^2 and above 1e-10 times half the longest edge squared; corners " +
                     corners() + ")");
  }
}

/// Exact coordinates as a hash key (-0 and +0 are one point; no NaN reaches it).
struct PointKey {
  std::array<double, 3> x;
  bool operator==(const PointKey& o) const { return x == o.x; }
};
struct PointHash {
  std::size_t operator()(const PointKey& k) const noexcept {
    std::uint64_t h = 0;
    for (const double v : k.x) {
      h ^= std::bit_cast<std::uint64_t>(v == 0.0 ? 0.0 : v) + 0x9E3779B97F4A7C15ull + (h << 6) +
           (h >> 2);
      // splitmix64 finaliser
      h ^= h >> 30;
      h *= 0xBF58476D1CE4E5B9ull;
      h ^= h >> 27;
      h *= 0x94D049BB133111EBull;
      h ^= h >> 31;
    }
    return static_cast<std::size_t>(h);
  }
};

/// Collects the vertices and triangles of a mesh being read.
class MeshBuilder {
public:
  MeshBuilder(const std::string& label, const MeshReadOptions& options)
      : label_(label), options_(options) {}

  /// The vertex of a (checked, scaled) corner: the one with its coordinates if vertices are
  /// merged and it exists, else a new one.
  std::uint32_t vertex(const Vec3& p) {
    if (!options_.merge_vertices) return append(p);
    const auto next = static_cast<std::uint32_t>(mesh_.vertices.size());
    const auto [it, fresh] = index_.try_emplace(PointKey{{p.x(), p.y(), p.z()}}, next);
    if (fresh) append(p);
    return it->second;
  }

  /// Adds the triangle abc after checking it (where() names it in a message).
  template <class Where>
  void triangle(const Vec3& a, const Vec3& b, const Vec3& c, const Where& where) {
    check_triangle(label_, where, a, b, c, options_.min_area);
    const std::array<std::uint32_t, 3> t = {vertex(a), vertex(b), vertex(c)};
    add(t);
  }

  /// Adds the triangle t of the vertices X, which become the mesh's (set_vertices), after
  /// checking it.
  template <class Where>
  void indexed(const std::array<std::uint32_t, 3>& t, const std::vector<Vec3>& X,
               const Where& where) {
    check_triangle(label_, where, X[t[0]], X[t[1]], X[t[2]], options_.min_area);
    add(t);
  }

  /// The vertices as given (an OBJ file read without merging), after the triangles (indexed).
  void set_vertices(std::vector<Vec3> vertices) { mesh_.vertices = std::move(vertices); }

  /// The mesh; InputError if it has no triangles (`note` says why, e.g. "(the file is empty)").
  walls::TriangleMesh finish(const std::string& note) {
    if (mesh_.triangles.empty())
      throw InputError(label_ + ": number of triangles = 0 is invalid; valid range: [1, inf) " +
                       note);
    return std::move(mesh_);
  }

  std::size_t triangles() const { return mesh_.triangles.size(); }

private:
  std::uint32_t append(const Vec3& p) {
    constexpr auto most = std::numeric_limits<std::uint32_t>::max();
    if (mesh_.vertices.size() >= most)
      throw InputError(label_ + ": number of vertices = " + std::to_string(most) +
                       " or more is invalid; valid range: [0, " + std::to_string(most) +
                       ") (32-bit vertex indices)");
    mesh_.vertices.push_back(p);
    return static_cast<std::uint32_t>(mesh_.vertices.size() - 1);
  }
  void add(const std::array<std::uint32_t, 3>& t) {
    constexpr auto most = std::numeric_limits<std::uint32_t>::max();
    if (mesh_.triangles.size() >= most)
      throw InputError(label_ + ": number of triangles = " + std::to_string(most) +
                       " or more is invalid; valid range: [1, " + std::to_string(most) +
                       ") (32-bit wall indices)");
    mesh_.triangles.push_back(t);
  }

  const std::string& label_;
  const MeshReadOptions& options_;
  walls::TriangleMesh mesh_{};
  std::unordered_map<PointKey, std::uint32_t, PointHash> index_{};
};

/// Little-endian 32-bit unsigned integer and single-precision number at p.
inline std::uint32_t le32(const unsigned char* p) {
  return static_cast<std::uint32_t>(p[0]) | static_cast<std::uint32_t>(p[1]) << 8 |
         static_cast<std::uint32_t>(p[2]) << 16 | static_cast<std::uint32_t>(p[3]) << 24;
}
inline double le_float(const unsigned char* p) {
  return static_cast<double>(std::bit_cast<float>(le32(p)));
}

/// True if the bytes start with the word "solid" (any case), after an optional UTF-8 byte-order
/// mark and white space, followed by white space or nothing.
inline bool starts_with_solid(std::string_view s) {
  if (s.substr(0, 3) == "\xEF\xBB\xBF") s.remove_prefix(3);
  const auto b = s.find_first_not_of(space);
  if (b == std::string_view::npos) return false;
  s.remove_prefix(b);
  if (s.size() < 5 || !is_word(s.substr(0, 5), "solid")) return false;
  return s.size() == 5 || space.find(s[5]) != std::string_view::npos;
}

/// The binary facets of an STL file of `count` facets whose size has been checked.
inline walls::TriangleMesh read_stl_binary(std::istream& in, const std::string& label,
                                           std::uint32_t count, const MeshReadOptions& o) {
  MeshBuilder mesh(label, o);
  if (count == 0)
    throw InputError(label + ": number of facets = 0 is invalid; valid range: [1, inf) (the "
                             "header's facet count is 0: an empty binary STL)");
  constexpr std::uint32_t chunk = 4096;
  std::vector<unsigned char> buf(50 * static_cast<std::size_t>(std::min(count, chunk)));
  for (std::uint32_t first = 0; first < count;) {
    const std::uint32_t n = std::min(count - first, chunk);
    in.read(reinterpret_cast<char*>(buf.data()), static_cast<std::streamsize>(50 * n));
    if (in.gcount() != static_cast<std::streamsize>(50 * n)) {
      const auto got = static_cast<std::uint32_t>(in.gcount() / 50);
      throw InputError(label + ": facet " + std::to_string(first + got) +
                       " is invalid; valid range: a complete facet of 50 bytes (the file ended "
                       "while it was read: it changed since its size was checked)");
    }
    for (std::uint32_t k = 0; k < n; ++k) {
      const std::uint32_t f = first + k;
      const unsigned char* r = buf.data() + 50 * static_cast<std::size_t>(k) + 12; // the corners
      Vec3 c[3];
      for (int j = 0; j < 3; ++j) {
        const unsigned char* q = r + 12 * j;
        c[j] = scaled_point(
            label, [&] { return "facet " + std::to_string(f) + " vertex " + std::to_string(j); },
            le_float(q), le_float(q + 4), le_float(q + 8), o.scale);
      }
      mesh.triangle(c[0], c[1], c[2], [&] { return "facet " + std::to_string(f); });
    }
    first += n;
  }
  return mesh.finish("");
}

/// The tokens of a text file, with their line numbers.
class Lexer {
public:
  explicit Lexer(std::istream& in) : in_(in) {}

  /// The next token (empty at the end of the file). It stays valid until the next call.
  std::string_view next() {
    while (true) {
      const auto b = line_.find_first_not_of(space, pos_);
      if (b != std::string::npos) {
        const auto e = std::min(line_.find_first_of(space, b), line_.size());
        pos_ = e;
        return std::string_view(line_).substr(b, e - b);
      }
      if (!std::getline(in_, line_)) {
        line_.clear();
        pos_ = 0;
        end_ = true;
        return {};
      }
      ++number_;
      pos_ = (number_ == 1 && line_.starts_with("\xEF\xBB\xBF")) ? 3 : 0;
      binary_ = binary_ || has_binary_bytes(line_);
    }
  }
  /// Skips the rest of the current line.
  void skip_line() { pos_ = line_.size(); }
  /// The line of the last token (the last line at the end of the file).
  std::size_t line() const { return number_; }
  const std::string& text() const { return line_; }
  bool at_end() const { return end_; }
  bool failed() const { return in_.bad(); }
  /// True once a line read held bytes that a text file does not (has_binary_bytes).
  bool binary_seen() const { return binary_; }

private:
  std::istream& in_;
  std::string line_{};
  std::size_t pos_ = 0, number_ = 0;
  bool end_ = false, binary_ = false;
};

inline constexpr const char* stl_ascii_grammar =
    "valid range: an ASCII STL: 'solid <name>', facets of 'facet normal nx ny nz', 'outer loop', "
    "three 'vertex x y z', 'endloop', 'endfacet', then 'endsolid <name>'";

/// The ASCII facets of an STL file; `hint` is added to a syntax error once a line with bytes that
/// a text file does not hold has been read (a binary file whose header starts with "solid").
inline walls::TriangleMesh read_stl_ascii(std::istream& in, const std::string& label,
                                          const MeshReadOptions& o, const std::string& hint) {
  Lexer lx(in);
  MeshBuilder mesh(label, o);
  const auto syntax = [&](std::string_view token, const std::string& expected) {
    if (lx.failed())
      return InputError(label + ": reading failed after line " + std::to_string(lx.line()));
    if (lx.at_end())
      return InputError(label + ": the end of the file after line " + std::to_string(lx.line()) +
                        " is invalid (expected " + expected + "; the file is truncated); " +
                        stl_ascii_grammar + (lx.binary_seen() ? hint : ""));
    return InputError(label + ": line " + std::to_string(lx.line()) + " = " + shown(lx.text()) +
                      " is invalid (expected " + expected + ", found " + shown(token) + "); " +
                      stl_ascii_grammar + (lx.binary_seen() ? hint : ""));
  };
  const auto expect = [&](std::string_view word) {
    const auto t = lx.next();
    if (!is_word(t, word)) throw syntax(t, "'" + std::string(word) + "'");
  };
  const auto number = [&](const char* what) {
    const auto t = lx.next();
    double v = 0.0;
    const Parse p = parse_double(t, v);
    if (p == Parse::out_of_range)
      throw syntax(t, std::string("a number within the range of double (") + what + ")");
    if (p != Parse::ok) throw syntax(t, std::string("a number (") + what + ")");
    return v;
  };
  auto t = lx.next();
  if (!is_word(t, "solid")) throw syntax(t, "'solid'");
  lx.skip_line();
  std::size_t facet = 0;
  while (true) {
    t = lx.next();
    if (is_word(t, "endsolid")) {
      lx.skip_line();
      t = lx.next();
      if (t.empty() && lx.at_end() && !lx.failed()) break;
      if (!is_word(t, "solid")) throw syntax(t, "'solid' or the end of the file");
      lx.skip_line();
      continue;
    }
    if (!is_word(t, "facet")) throw syntax(t, "'facet' or 'endsolid'");
    const std::size_t line = lx.line();
    expect("normal");
    for (const char* what : {"normal x", "normal y", "normal z"})
      number(what); // any number: the normal is not used
    expect("outer");
    expect("loop");
    Vec3 c[3];
    for (auto& corner : c) {
      expect("vertex");
      const double x = number("vertex x"), y = number("vertex y"), z = number("vertex z");
      const std::size_t at = lx.line();
      corner = scaled_point(
          label, [&] { return "line " + std::to_string(at) + " vertex"; }, x, y, z, o.scale);
    }
    expect("endloop");
    expect("endfacet");
    mesh.triangle(c[0], c[1], c[2], [&] {
      return "facet " + std::to_string(facet) + " (line " + std::to_string(line) + ")";
    });
    ++facet;
  }
  return mesh.finish("(the file has no facets)");
}

/// The message of a binary STL whose size does not fit its header's count.
inline std::string stl_size_mismatch(std::uint32_t count, std::uintmax_t size) {
  const std::uintmax_t expected = 84 + 50 * static_cast<std::uintmax_t>(count);
  if (size < 84) size = 84; // the file shrank while it was read
  std::string text =
      "facet count in the header = " + std::to_string(count) + " is invalid; valid range: ";
  const std::uintmax_t whole = (size - 84) / 50, rest = (size - 84) % 50;
  if (rest == 0)
    text += std::to_string(whole) + " (the file has " + std::to_string(size) +
            " bytes = 84 + 50 x " + std::to_string(whole) + ")";
  else
    text += "none (the file has " + std::to_string(size) + " bytes = 84 + 50 x " +
            std::to_string(whole) + " + " + std::to_string(rest) + ", not 84 + 50 n for any n" +
            (whole < count ? ": it ends inside facet " + std::to_string(whole) + ", truncated"
                           : std::string()) +
            ")";
  return text + "; a binary STL of " + std::to_string(count) + " facets has 84 + 50 x " +
         std::to_string(count) + " = " + std::to_string(expected) + " bytes";
}

/// Statements of an OBJ file that are skipped.
inline bool obj_ignored(std::string_view key) {
  for (const std::string_view k :
       {"vt", "vn", "vp", "g", "o", "s", "mg", "usemtl", "mtllib", "usemap", "maplib", "lod",
        "bevel", "c_interp", "d_interp", "shadow_obj", "trace_obj", "p", "l"})
    if (key == k) return true;
  return false;
}

inline constexpr const char* obj_grammar =
    "valid range: 'v x y z [w]', 'f v1 v2 v3 ...' (corners v, v/vt, v/vt/vn or v//vn), a "
    "statement that is skipped (vt, vn, vp, g, o, s, mg, usemtl, mtllib, usemap, maplib, lod, "
    "bevel, c_interp, d_interp, shadow_obj, trace_obj, p, l), a # comment or a blank line";

/// The vertex index of an OBJ face corner `v`, `v/vt`, `v/vt/vn` or `v//vn` (the texture and
/// normal indices must be integers); "" if it parses, else why not.
inline std::string obj_corner(std::string_view token, long long& v) {
  std::string_view part[3];
  int parts = 0;
  while (true) {
    const auto slash = token.find('/');
    if (parts == 3) return "more than two '/'";
    part[parts++] = token.substr(0, slash);
    if (slash == std::string_view::npos) break;
    token.remove_prefix(slash + 1);
  }
  const char* names[3] = {"vertex", "texture", "normal"};
  for (int k = 0; k < parts; ++k) {
    if (k == 1 && parts == 3 && part[1].empty()) continue; // v//vn
    long long x = 0;
    const Parse p = parse_integer(part[k], x);
    if (p == Parse::out_of_range) return std::string(names[k]) + " index out of range";
    if (p != Parse::ok)
      return std::string(names[k]) + " index " + shown(part[k]) + " is not an integer";
    if (k == 0) v = x;
  }
  return "";
}

} // namespace detail::mesh_file

/// Reads an STL file (binary or ASCII, see the file comment) into a triangle mesh [m]. Throws
/// InputError naming the file and the line or facet for anything invalid.
inline walls::TriangleMesh read_stl(const std::string& path, const MeshReadOptions& options = {}) {
  namespace m = detail::mesh_file;
  const std::string label = "STL file '" + path + "'";
  m::check_options(label, options);
  const std::uintmax_t size = m::file_size(label, path);
  std::ifstream in;
  m::open(in, label, path);
  unsigned char head[84] = {};
  in.read(reinterpret_cast<char*>(head), 84);
  const auto got = static_cast<std::size_t>(in.gcount());
  const bool solid = m::starts_with_solid(std::string_view(reinterpret_cast<char*>(head), got));
  if (got == 84 && size >= 84) {
    const std::uint32_t count = m::le32(head + 80);
    if (size == 84 + 50 * static_cast<std::uintmax_t>(count))
      return m::read_stl_binary(in, label, count, options);
    if (!solid) throw InputError(label + ": " + m::stl_size_mismatch(count, size));
  }
  if (!solid)
    throw InputError(label + ": file size = " + std::to_string(size) +
                     " bytes is invalid; valid range: an ASCII STL (starting with 'solid') or a "
                     "binary STL of 84 + 50 n bytes (an 80-byte header, the facet count n, n "
                     "facets of 50 bytes)");
  std::string hint;
  if (got == 84) {
    const std::uint32_t count = m::le32(head + 80);
    hint = " (the file is read as ASCII because it starts with 'solid' and does not have the size "
           "of a binary STL: " +
           m::stl_size_mismatch(count, size) + ")";
  }
  in.clear();
  in.seekg(0);
  return m::read_stl_ascii(in, label, options, hint);
}

/// Reads a Wavefront OBJ file (see the file comment) into a triangle mesh [m]. Throws InputError
/// naming the file and the line for anything invalid.
inline walls::TriangleMesh read_obj(const std::string& path, const MeshReadOptions& options = {}) {
  namespace m = detail::mesh_file;
  const std::string label = "OBJ file '" + path + "'";
  m::check_options(label, options);
  m::file_size(label, path);
  std::ifstream in;
  m::open(in, label, path);

  struct Face {
    std::size_t line, begin, end; ///< corners[begin, end)
  };
  std::vector<Vec3> points;       // scaled [m]
  std::vector<long long> corners; // 0-based vertex indices (positive ones checked at the end)
  std::vector<Face> faces;
  std::vector<std::string_view> tok;
  std::string line;
  std::size_t number = 0;
  const auto bad_line = [&](const std::string& why) {
    return InputError(label + ": line " + std::to_string(number) + " = " + m::shown(line) +
                      " is invalid (" + why + "); " + m::obj_grammar);
  };
  while (std::getline(in, line)) {
    ++number;
    std::string_view rest(line);
    if (number == 1 && rest.starts_with("\xEF\xBB\xBF")) rest.remove_prefix(3);
    if (const auto hash = rest.find('#'); hash != std::string_view::npos)
      rest = rest.substr(0, hash);
    tok.clear();
    while (true) {
      const auto b = rest.find_first_not_of(m::space);
      if (b == std::string_view::npos) break;
      rest.remove_prefix(b);
      const auto e = std::min(rest.find_first_of(m::space), rest.size());
      tok.push_back(rest.substr(0, e));
      rest.remove_prefix(e);
    }
    if (tok.empty()) continue;
    const std::string_view key = tok[0];
    if (key == "v") {
      const std::size_t n = tok.size() - 1;
      if (n != 3 && n != 4 && n != 6)
        throw bad_line("'v' takes 3 numbers x y z, 4 with a weight w or 6 with a colour r g b; it "
                       "has " +
                       std::to_string(n));
      double x[6] = {};
      for (std::size_t k = 0; k < n; ++k) {
        const m::Parse p = m::parse_double(tok[k + 1], x[k]);
        if (p != m::Parse::ok) throw bad_line(m::not_a_number(tok[k + 1], p));
      }
      points.push_back(m::scaled_point(
          label, [&] { return "line " + std::to_string(number) + " vertex"; }, x[0], x[1], x[2],
          options.scale));
    } else if (key == "f") {
      if (tok.size() < 4)
        throw bad_line("a face needs at least 3 corners; it has " + std::to_string(tok.size() - 1));
      const std::size_t begin = corners.size();
      for (std::size_t k = 1; k < tok.size(); ++k) {
        long long v = 0;
        if (const std::string why = m::obj_corner(tok[k], v); !why.empty())
          throw bad_line("corner " + m::shown(tok[k]) + ": " + why);
        const auto before = static_cast<long long>(points.size());
        if (v == 0 || (v < 0 && v < -before))
          throw InputError(label + ": line " + std::to_string(number) +
                           " vertex index = " + std::to_string(v) +
                           " is invalid; valid range: [1, number of vertices], or [-" +
                           std::to_string(before) + ", -1] counting back from the last of the " +
                           std::to_string(before) + " vertices defined before the line");
        corners.push_back(v > 0 ? v - 1 : before + v);
      }
      faces.push_back({number, begin, corners.size()});
    } else if (!m::obj_ignored(key)) {
      throw bad_line("unknown statement " + m::shown(key));
    }
  }
  if (in.bad()) throw InputError(label + ": reading failed after line " + std::to_string(number));

  m::MeshBuilder mesh(label, options);
  const auto total = static_cast<long long>(points.size());
  if (points.size() >= std::numeric_limits<std::uint32_t>::max())
    throw InputError(label + ": number of vertices = " + std::to_string(points.size()) +
                     " is invalid; valid range: [0, 4294967295) (32-bit vertex indices)");
  for (const Face& f : faces) {
    for (std::size_t k = f.begin; k < f.end; ++k)
      if (corners[k] >= total)
        throw InputError(label + ": line " + std::to_string(f.line) + " vertex index = " +
                         std::to_string(corners[k] + 1) + " is invalid; valid range: [1, " +
                         std::to_string(total) + "] (the file's " + std::to_string(total) +
                         " vertices), or negative counting back");
    const std::size_t m_corners = f.end - f.begin;
    for (std::size_t k = 1; k + 1 < m_corners; ++k) {
      const auto where = [&] {
        std::string s = "face on line " + std::to_string(f.line);
        if (m_corners > 3)
          s += ", triangle " + std::to_string(k - 1) + " of its fan of " +
               std::to_string(m_corners - 2);
        return s;
      };
      const auto a = static_cast<std::size_t>(corners[f.begin]);
      const auto b = static_cast<std::size_t>(corners[f.begin + k]);
      const auto c = static_cast<std::size_t>(corners[f.begin + k + 1]);
      if (options.merge_vertices)
        mesh.triangle(points[a], points[b], points[c], where);
      else
        mesh.indexed({static_cast<std::uint32_t>(a), static_cast<std::uint32_t>(b),
                      static_cast<std::uint32_t>(c)},
                     points, where);
    }
  }
  if (!options.merge_vertices) mesh.set_vertices(std::move(points));
  return mesh.finish(number == 0 ? "(the file is empty)"
                                 : "(the file has " + std::to_string(total) +
                                       " vertices and no 'f' lines)");
}

/// Reads a mesh file by its extension: .stl (read_stl) or .obj (read_obj), in any case.
inline walls::TriangleMesh read_mesh(const std::string& path, const MeshReadOptions& options = {}) {
  std::string ext = std::filesystem::path(path).extension().string();
  for (auto& ch : ext)
    ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
  if (ext == ".stl") return read_stl(path, options);
  if (ext == ".obj") return read_obj(path, options);
  throw InputError("mesh file '" + path + "': extension = " + detail::mesh_file::shown(ext) +
                   " is invalid; valid range: .stl or .obj (in any case)");
}

namespace detail::mesh_file {

/// The unit normal (b - a) x (c - a) / |...| of a triangle; zero if it has none.
inline Vec3 facet_normal(const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 e1 = b - a, e2 = c - a;
  const double s = std::max(e1.cwiseAbs().maxCoeff(), e2.cwiseAbs().maxCoeff());
  if (!(s > 0.0) || !std::isfinite(s)) return Vec3::Zero();
  const Vec3 n = (e1 / s).cross(e2 / s);
  const double len = n.norm();
  return len > 0.0 && std::isfinite(len) ? Vec3(n / len) : Vec3::Zero();
}

/// The shortest decimal text of v that reads back to v.
inline void put_number(std::string& out, double v) {
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);
  out.append(buf, r.ptr);
}

inline void put_le32(char* p, std::uint32_t u) {
  for (int k = 0; k < 4; ++k)
    p[k] = static_cast<char>((u >> (8 * k)) & 0xFFu);
}

} // namespace detail::mesh_file

/// Writes a triangle mesh [m] as an STL file: ASCII (the default) or binary (single precision),
/// named `solid_name` (one line of text), with the normal of each triangle from its vertex order
/// (see the file comment). Throws InputError for a mesh that cannot be written as a valid file
/// and for an output folder that cannot be made or written (before anything is written), and
/// io::WriteError if writing fails (the previous file at `path`, if any, is left as it was).
inline void write_stl(const walls::TriangleMesh& mesh, const std::string& path, bool binary = false,
                      const std::string& solid_name = "grain") {
  namespace m = detail::mesh_file;
  const std::string who = "grain::io::write_stl";
  const std::string object = who + " '" + path + "'";
  const auto& X = mesh.vertices;
  const auto& T = mesh.triangles;
  grain::require(!T.empty(), object, "number of triangles", T.size(), "[1, inf)");
  if (binary)
    grain::require(T.size() <= std::numeric_limits<std::uint32_t>::max(), object,
                   "number of triangles", T.size(), "[1, 4294967295] (a binary STL's count)");
  grain::require(solid_name.find_first_of("\r\n") == std::string::npos, object, "solid_name",
                 m::shown(solid_name), "one line of text");
  std::vector<bool> used(X.size(), false);
  for (std::size_t f = 0; f < T.size(); ++f)
    for (int k = 0; k < 3; ++k) {
      grain::require(T[f][k] < X.size(), object,
                     "triangle " + std::to_string(f) + " vertex index " + std::to_string(k),
                     T[f][k], "[0, " + std::to_string(X.size()) + ") (the mesh's vertices)");
      used[T[f][k]] = true;
    }
  constexpr double float_max = std::numeric_limits<float>::max();
  for (std::size_t i = 0; i < X.size(); ++i) {
    if (!used[i]) continue;
    grain::require(X[i].allFinite(), object, "vertex " + std::to_string(i), m::point_text(X[i]),
                   "finite coordinates [m]");
    if (binary)
      grain::require(X[i].cwiseAbs().maxCoeff() <= float_max, object, "vertex " + std::to_string(i),
                     m::point_text(X[i]),
                     "coordinates within single precision, |x| <= 3.4e38 (a binary STL)");
  }
  io::detail::require_output_folder(who, path);
  io::detail::AtomicFile file(who, path, binary);
  std::ostream& out = file.stream();
  if (binary) {
    char header[84] = {};
    const std::string text = "binary STL, grain: " + solid_name;
    std::copy_n(text.begin(), std::min<std::size_t>(text.size(), 80), header);
    m::put_le32(header + 80, static_cast<std::uint32_t>(T.size()));
    out.write(header, 84);
    char rec[50] = {};
    for (const auto& t : T) {
      const Vec3 n = m::facet_normal(X[t[0]], X[t[1]], X[t[2]]);
      const Vec3* v[4] = {&n, &X[t[0]], &X[t[1]], &X[t[2]]};
      for (int j = 0; j < 4; ++j)
        for (int k = 0; k < 3; ++k)
          m::put_le32(rec + 12 * j + 4 * k,
                      std::bit_cast<std::uint32_t>(static_cast<float>((*v[j])[k])));
      out.write(rec, 50);
    }
  } else {
    std::string s;
    const auto point = [&](const Vec3& p) {
      for (int k = 0; k < 3; ++k) {
        s += ' ';
        m::put_number(s, p[k]);
      }
      s += '\n';
    };
    out << "solid " << solid_name << '\n';
    for (const auto& t : T) {
      s.clear();
      s += "  facet normal";
      point(m::facet_normal(X[t[0]], X[t[1]], X[t[2]]));
      s += "    outer loop\n";
      for (int k = 0; k < 3; ++k) {
        s += "      vertex";
        point(X[t[k]]);
      }
      s += "    endloop\n  endfacet\n";
      out << s;
    }
    out << "endsolid " << solid_name << '\n';
  }
  file.commit();
}

} // namespace grain::io
