// Mesh files: io::read_stl (ASCII and binary), io::read_obj, io::read_mesh and io::write_stl.
//
// - A closed cube written by write_stl and read back (ASCII, binary) is one connected mesh of 8
//   vertices and 12 triangles (every edge shared by two faces), area 6 L^2, volume L^3 by the
//   divergence theorem (the orientation kept), the corners as written (ASCII exactly; binary in
//   single precision, exact for these coordinates).
// - Files written here byte by byte, independently of write_stl: ASCII with upper-case keywords,
//   Windows line ends, two solids and tokens across lines; a binary file whose header starts
//   with "solid"; an OBJ file with quads, a pentagon, negative indices, the v/vt/vn, v/vt and
//   v//vn forms and the statements that are skipped. The triangles are the expected ones.
// - scale and min_area; merged and unmerged vertices.
// - Every bad input gives an InputError naming the file and the line (text) or the facet
//   (binary) and the bad value; write_stl refuses meshes it cannot write and reports a failed
//   write as io::WriteError.
// - A sphere dropped on a square read from an STL file as an obstacle rests where it rests on a
//   plane: at the height R - delta of the Hertz static overlap.

#include "../errors.hpp"
#include "../support/materials.hpp"
#include "../support/meshes.hpp"
#include <doctest/doctest.h>
#include <grain/grain.hpp>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <limits>
#include <numbers>
#include <string>
#include <vector>

using namespace grain;
using grain::test::error_of;
using grain::test::has;

namespace {

namespace fs = std::filesystem;

/// The folder of this test's files.
const fs::path& folder() {
  static const fs::path dir = [] {
    auto d = fs::temp_directory_path() / "grain_mesh_file_test";
    fs::create_directories(d);
    return d;
  }();
  return dir;
}

/// Writes `bytes` to the file `name` of the folder; returns its path.
std::string put(const std::string& name, const std::string& bytes) {
  const std::string path = (folder() / name).string();
  std::ofstream o(path, std::ios::binary | std::ios::trunc);
  o.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  o.close();
  REQUIRE(o.good());
  return path;
}

std::string get(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

/// A little-endian 32-bit integer, and a single-precision number, as 4 bytes.
std::string le32(std::uint32_t u) {
  std::string s(4, '\0');
  for (int k = 0; k < 4; ++k)
    s[k] = static_cast<char>((u >> (8 * k)) & 0xFFu);
  return s;
}
std::string le_float(float f) { return le32(std::bit_cast<std::uint32_t>(f)); }

/// A binary STL: the header (padded to 80 bytes with spaces), `count` in the count field and the
/// facets given as 12 numbers each (normal, corners), every attribute count 0.
std::string binary_stl(const std::string& header, std::uint32_t count,
                       const std::vector<std::array<float, 12>>& facets) {
  std::string s = header;
  s.resize(80, ' ');
  s += le32(count);
  for (const auto& f : facets) {
    for (float x : f)
      s += le_float(x);
    s += std::string(2, '\0');
  }
  return s;
}

double surface_area(const walls::TriangleMesh& m) {
  double a = 0.0;
  for (const auto& t : m.triangles)
    a += 0.5 *
         (m.vertices[t[1]] - m.vertices[t[0]]).cross(m.vertices[t[2]] - m.vertices[t[0]]).norm();
  return a;
}

/// The enclosed volume by the divergence theorem: sum of a . (b x c) / 6 over the triangles abc
/// (positive for a closed surface whose triangles turn counter-clockwise seen from outside).
double volume(const walls::TriangleMesh& m) {
  double v = 0.0;
  for (const auto& t : m.triangles)
    v += m.vertices[t[0]].dot(m.vertices[t[1]].cross(m.vertices[t[2]])) / 6.0;
  return v;
}

/// Corner j of triangle k of m.
Vec3 corner(const walls::TriangleMesh& m, std::size_t k, int j) {
  return m.vertices[m.triangles[k][j]];
}

/// True if a and b have the same triangles with the same corners (vertex numbering aside).
bool same_triangles(const walls::TriangleMesh& a, const walls::TriangleMesh& b) {
  if (a.triangles.size() != b.triangles.size()) return false;
  for (std::size_t k = 0; k < a.triangles.size(); ++k)
    for (int j = 0; j < 3; ++j)
      if (corner(a, k, j) != corner(b, k, j)) return false;
  return true;
}

/// True if every edge of the mesh has exactly two faces (a closed, connected surface).
bool closed(const walls::TriangleMesh& m) {
  const auto f = walls::MeshFeatures::build(m, Vec3::Zero(), "mesh");
  for (std::uint32_t e = 0; e < f->edge_count(); ++e)
    if (f->edge_faces(e).size() != 2) return false;
  return f->edge_count() == 3 * m.triangles.size() / 2;
}

/// Facets of the unit square [0, 1]^2 at z = 0 (diagonal (0, 0)-(1, 1)) in ASCII STL.
const char* const square_ascii = "solid square\n"
                                 "facet normal 0 0 1\n"
                                 " outer loop\n"
                                 "  vertex 0 0 0\n"
                                 "  vertex 1 0 0\n"
                                 "  vertex 1 1 0\n"
                                 " endloop\n"
                                 "endfacet\n"
                                 "facet normal 0 0 1\n"
                                 " outer loop\n"
                                 "  vertex 0 0 0\n"
                                 "  vertex 1 1 0\n"
                                 "  vertex 0 1 0\n"
                                 " endloop\n"
                                 "endfacet\n"
                                 "endsolid square\n";

} // namespace

TEST_CASE("mesh files: a cube written as ASCII STL reads back as one closed mesh") {
  const double L = 0.3;
  const Vec3 lo(0.1, -0.2, 0.05);
  const auto cube = grain::test::box(lo, lo + Vec3::Constant(L));
  const std::string path = (folder() / "cube_ascii.stl").string();
  io::write_stl(cube, path);
  CHECK(get(path).starts_with("solid grain\n  facet normal 0 0 -1\n    outer loop\n"));
  const auto m = io::read_stl(path);
  CHECK(m.vertices.size() == 8);
  REQUIRE(m.triangles.size() == 12);
  CHECK(same_triangles(m, cube)); // the shortest decimal text reads back to the same doubles
  CHECK(closed(m));
  CHECK(surface_area(m) == doctest::Approx(6 * L * L).epsilon(1e-13));
  CHECK(volume(m) == doctest::Approx(L * L * L).epsilon(1e-12));
  // without merging: three vertices per facet, the same triangles
  const auto loose = io::read_stl(path, {.merge_vertices = false});
  CHECK(loose.vertices.size() == 36);
  CHECK(same_triangles(loose, cube));
  CHECK(loose.triangles[11] == std::array<std::uint32_t, 3>{33, 34, 35});
  // read_mesh by the extension, in any case
  const std::string upper = (folder() / "CUBE.STL").string();
  fs::copy_file(path, upper, fs::copy_options::overwrite_existing);
  CHECK(same_triangles(io::read_mesh(upper), cube));
}

TEST_CASE("mesh files: a cube written as binary STL reads back as one closed mesh") {
  // coordinates exact in single precision
  const double L = 0.25;
  const Vec3 lo(0.5, -0.25, 0.125);
  const auto cube = grain::test::box(lo, lo + Vec3::Constant(L));
  const std::string path = (folder() / "cube_binary.stl").string();
  io::write_stl(cube, path, true, "cube");
  const std::string bytes = get(path);
  REQUIRE(bytes.size() == 84 + 50 * 12);
  CHECK(!bytes.starts_with("solid"));
  CHECK(bytes.substr(80, 4) == le32(12));
  CHECK(bytes.substr(84, 12) == le_float(0) + le_float(0) + le_float(-1)); // normal of triangle 0
  const auto m = io::read_stl(path);
  CHECK(m.vertices.size() == 8);
  REQUIRE(m.triangles.size() == 12);
  CHECK(same_triangles(m, cube));
  CHECK(closed(m));
  CHECK(surface_area(m) == doctest::Approx(6 * L * L).epsilon(1e-13));
  CHECK(volume(m) == doctest::Approx(L * L * L).epsilon(1e-12));
  CHECK(io::read_stl(path, {.merge_vertices = false}).vertices.size() == 36);
}

TEST_CASE("mesh files: ASCII STL with upper case, Windows line ends and two solids") {
  const std::string path = put("two_solids.stl", "solid first part\r\n"
                                                 "  FACET NORMAL 0 0 1\r\n"
                                                 "    OUTER LOOP\r\n"
                                                 "      VERTEX 0 0 0\r\n"
                                                 "      VERTEX 1.0e+000 0 0\r\n"
                                                 "      VERTEX +1 1E0 -0\r\n"
                                                 "    ENDLOOP\r\n"
                                                 "  ENDFACET\r\n"
                                                 "ENDSOLID first part\r\n"
                                                 "solid\n"
                                                 "facet normal nan nan nan outer loop vertex 0 0 "
                                                 "0\tvertex 1 1 0 vertex\n0 1 0 endloop endfacet\n"
                                                 "endsolid");
  const auto m = io::read_stl(path);
  REQUIRE(m.vertices.size() == 4);
  CHECK(m.vertices[2] == Vec3(1, 1, 0)); // -0 and 0 are one point
  CHECK(m.triangles == std::vector<std::array<std::uint32_t, 3>>{{0, 1, 2}, {0, 2, 3}});
  CHECK(surface_area(m) == 1.0);
}

TEST_CASE("mesh files: a binary STL whose header starts with \"solid\" is read as binary") {
  const std::string bytes =
      binary_stl("solid square, from a program that starts every header so", 2,
                 {{9, 9, 9, 0, 0, 0, 1, 0, 0, 1, 1, 0}, {0, 0, 0, 0, 0, 0, 1, 1, 0, 0, 1, 0.5f}});
  REQUIRE(bytes.size() == 184);
  const auto m = io::read_stl(put("solid_binary.stl", bytes));
  REQUIRE(m.vertices.size() == 4);
  CHECK(m.vertices[3] == Vec3(0, 1, 0.5));
  CHECK(m.triangles == std::vector<std::array<std::uint32_t, 3>>{{0, 1, 2}, {0, 2, 3}});
}

TEST_CASE("mesh files: OBJ with quads, a pentagon, negative indices and every corner form") {
  const std::string text = "# a strip of two squares, a triangle and a pentagon above\n"
                           "mtllib strip.mtl\n"
                           "o strip\n"
                           "v 0 0 0\n"
                           "v 1 0 0\n"
                           "v 1 1 0\n"
                           "v 0 1 0 1.0\n"
                           "vt 0 0\n"
                           "vt 1 0\n"
                           "vn 0 0 1\n"
                           "g left\n"
                           "usemtl steel\n"
                           "s off\n"
                           "f 1/1/1 2/2/1 3/1/1 4/2/1\n"
                           "\n"
                           "v 2 0 0 0.5 0.5 0.5\n"
                           "v 2 1 0\n"
                           "f -5//1 -2//1 -1//1 -4//1 # the second square, counted back\n"
                           "v 3 0.5 0\n"
                           "l 6 7\n"
                           "f 5/1 7/2 6/1\r\n"
                           "v 0 0 1\n"
                           "v 1 0 1\n"
                           "v 1.5 0.5 1\n"
                           "v 1 1 1\n"
                           "v 0 1 1\n"
                           "f 8 9 10 11 -1\n";
  const std::string path = put("strip.obj", text);
  const std::vector<std::array<std::uint32_t, 3>> expected = {
      {0, 1, 2}, {0, 2, 3}, {1, 4, 5}, {1, 5, 2}, {4, 6, 5}, {7, 8, 9}, {7, 9, 10}, {7, 10, 11}};
  for (const bool merge : {true, false}) {
    CAPTURE(merge);
    const auto m = io::read_obj(path, {.merge_vertices = merge});
    CHECK(m.vertices.size() == 12);
    CHECK(m.triangles == expected);
    CHECK(m.vertices[6] == Vec3(3, 0.5, 0));
    CHECK(m.vertices[9] == Vec3(1.5, 0.5, 1));
    CHECK(surface_area(m) == doctest::Approx(1 + 1 + 0.5 + 1.25).epsilon(1e-15));
  }
  CHECK(io::read_mesh(path).triangles == expected);
}

TEST_CASE("mesh files: OBJ vertices with equal coordinates are merged") {
  // two triangles of a square, each with its own copy of the diagonal, and an unused vertex
  const std::string path = put("copies.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\n"
                                             "v 0 0 0\nv 1 1 0\nv 0 1 0\nv 5 5 5\n"
                                             "f 1 2 3\nf 4 5 6\n");
  const auto merged = io::read_obj(path);
  CHECK(merged.vertices.size() == 4);
  CHECK(merged.triangles == std::vector<std::array<std::uint32_t, 3>>{{0, 1, 2}, {0, 2, 3}});
  const auto loose = io::read_obj(path, {.merge_vertices = false});
  CHECK(loose.vertices.size() == 7);
  CHECK(loose.triangles == std::vector<std::array<std::uint32_t, 3>>{{0, 1, 2}, {3, 4, 5}});
}

TEST_CASE("mesh files: scale and min_area") {
  // a cube of 100 mm in a file in mm
  const auto cube_mm = grain::test::box(Vec3::Zero(), Vec3::Constant(100.0));
  const std::string path = (folder() / "cube_mm.stl").string();
  io::write_stl(cube_mm, path);
  const auto m = io::read_stl(path, {.scale = 1e-3});
  REQUIRE(m.triangles.size() == 12);
  for (std::size_t i = 0; i < m.vertices.size(); ++i)
    CHECK((m.vertices[i].array() == 0.0 || m.vertices[i].array() == 0.1).all());
  CHECK(surface_area(m) == doctest::Approx(0.06).epsilon(1e-14));
  CHECK(volume(m) == doctest::Approx(1e-3).epsilon(1e-14));
  // triangles of 5e-3 m^2: at or below min_area they are degenerate
  CHECK(io::read_stl(path, {.scale = 1e-3, .min_area = 4.9e-3}).triangles.size() == 12);
  const std::string e = error_of([&] { io::read_stl(path, {.scale = 1e-3, .min_area = 5.1e-3}); });
  CHECK(has(e, {path.c_str(), "facet 0 (line 2) area = 0.005 is invalid", "min_area = 0.0051"}));
  // coordinates that are finite in the file but not after scaling
  const std::string big = put("big.stl", "solid s\nfacet normal 0 0 1\nouter loop\n"
                                         "vertex 0 0 0\nvertex 1e308 0 0\n");
  CHECK(has(error_of([&] { io::read_stl(big, {.scale = 10}); }),
            {big.c_str(), "line 5 vertex times scale = (inf, 0, 0) is invalid",
             "the file's (1e+308, 0, 0) times scale = 10"}));
}

TEST_CASE("mesh files: every bad file is an InputError naming the file, the place and the value") {
  struct Case {
    std::string name, bytes;
    std::vector<std::string> parts; ///< in the message besides the path
  };
  const auto cube = grain::test::box(Vec3::Zero(), Vec3::Constant(1.0));
  const std::string cube_path = (folder() / "bad_cube.stl").string();
  io::write_stl(cube, cube_path, true);
  const std::string cube_bytes = get(cube_path);
  std::vector<std::array<float, 12>> four(4, {0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0});
  auto nan_facet = four;
  nan_facet[3][6] = std::numeric_limits<float>::quiet_NaN(); // facet 3, vertex 1, x
  auto repeated = four;
  repeated[1][9] = 1; // facet 1: vertex 2 = vertex 1
  repeated[1][10] = 0;
  const std::string vertex_lines = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
  const Case cases[] = {
      {"empty.stl", "", {"file size = 0 bytes is invalid"}},
      {"short.stl", "hello", {"file size = 5 bytes is invalid", "'solid'"}},
      {"truncated.stl",
       cube_bytes.substr(0, cube_bytes.size() - 10),
       {"facet count in the header = 12 is invalid", "674 bytes", "ends inside facet 11",
        "684 bytes"}},
      {"count.stl",
       binary_stl("cube", 100, std::vector<std::array<float, 12>>(12, four[0])),
       {"facet count in the header = 100 is invalid; valid range: 12", "684 bytes = 84 + 50 x 12",
        "5084 bytes"}},
      {"huge_count.stl",
       binary_stl("cube", 4000000000u, four),
       {"facet count in the header = 4000000000 is invalid", "the file has 284 bytes",
        "200000000084 bytes"}},
      {"zero_count.stl", binary_stl("empty", 0, {}), {"number of facets = 0 is invalid"}},
      {"nan_binary.stl",
       binary_stl("cube", 4, nan_facet),
       {"facet 3 vertex 1 = (nan, 0, 0) is invalid", "finite coordinates"}},
      {"repeated_binary.stl",
       binary_stl("cube", 4, repeated),
       {"facet 1 corners = (0, 0, 0), (1, 0, 0), (1, 0, 0) is invalid", "three different points"}},
      {"nan_ascii.stl",
       "solid s\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex nan 0 0\n",
       {"line 5 vertex = (nan, 0, 0) is invalid"}},
      {"collinear.stl",
       "solid s\n\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 1 1\nvertex 2 2 "
       "2\nendloop\nendfacet\nendsolid s\n",
       {"facet 0 (line 3) area = 0 is invalid", "(2, 2, 2)"}},
      {"typo.stl",
       "solid s\nfacet normal 0 0 1\nouter lop\n",
       {"line 3 = 'outer lop' is invalid (expected 'loop', found 'lop')"}},
      {"word.stl",
       "solid s\nfacet normal 0 0 1\nouter loop\nvertex 0 zero 0\n",
       {"line 4 = 'vertex 0 zero 0' is invalid (expected a number (vertex y), found 'zero')"}},
      {"no_end.stl",
       std::string(square_ascii).substr(0, std::string(square_ascii).rfind("end")),
       {"the end of the file after line 15 is invalid (expected 'facet' or 'endsolid'"}},
      {"after_end.stl",
       square_ascii + std::string("extra\n"),
       {"line 17 = 'extra' is invalid (expected 'solid' or the end of the file"}},
      {"solid_binary_bad.stl",
       binary_stl("solid but binary\n\x01\x02", 3, four),
       {"line 2 = '\\x01\\x02", "read as ASCII because it starts with 'solid'",
        "facet count in the header = 3"}},
      {"empty.obj", "", {"number of triangles = 0 is invalid", "the file is empty"}},
      {"no_faces.obj", vertex_lines, {"the file has 3 vertices and no 'f' lines"}},
      {"range.obj", vertex_lines + "f 1 2 4\n", {"line 4 vertex index = 4 is invalid", "[1, 3]"}},
      {"later_range.obj",
       vertex_lines + "f 1 2 3\nv 1 1 0\nf 1 6 3\nv 2 2 0\n",
       {"line 6 vertex index = 6 is invalid", "[1, 5]"}},
      {"back.obj",
       vertex_lines + "f -1 -2 -4\n",
       {"line 4 vertex index = -4 is invalid", "[-3, -1]"}},
      {"zero.obj", vertex_lines + "f 0 1 2\n", {"line 4 vertex index = 0 is invalid"}},
      {"two.obj", vertex_lines + "f 1 2\n", {"line 4 = 'f 1 2' is invalid", "at least 3 corners"}},
      {"garbage.obj",
       vertex_lines + "hello world\n",
       {"line 4 = 'hello world' is invalid (unknown statement 'hello')"}},
      {"number.obj", "v 0 0 0\nv 1 x 0\n", {"line 2 = 'v 1 x 0' is invalid ('x' is not a number)"}},
      {"huge.obj", "v 0 0 1e999\n", {"line 1", "'1e999' is outside the range of double"}},
      {"short_v.obj", "v 0 0\n", {"line 1 = 'v 0 0' is invalid", "it has 2"}},
      {"corner.obj",
       vertex_lines + "f 1/a 2 3\n",
       {"line 4", "texture index 'a' is not an integer"}},
      {"slashes.obj", vertex_lines + "f 1/1/1/1 2 3\n", {"line 4", "more than two '/'"}},
      {"nan.obj", "v 0 0 0\nv nan 1 0\n", {"line 2 vertex = (nan, 1, 0) is invalid"}},
      {"flat.obj",
       vertex_lines + "v 2 0 0\nf 1 2 3\nf 1 2 4\n",
       {"face on line 6 area = 0 is invalid"}},
      {"fan.obj",
       vertex_lines + "v 1 1 0\nv 0.5 0.5 0\nf 1 2 4 5 3\n",
       {"face on line 6, triangle 1 of its fan of 3 area = 0 is invalid", "(0.5, 0.5, 0)"}},
  };
  for (const auto& c : cases) {
    CAPTURE(c.name);
    const std::string path = put(c.name, c.bytes);
    const std::string e = error_of([&] { io::read_mesh(path); });
    INFO("message: ", e);
    CHECK(has(e, path));
    for (const auto& part : c.parts)
      CHECK(has(e, part));
  }
}

TEST_CASE("mesh files: a missing file, a folder, bad options and an unknown extension") {
  const std::string missing = (folder() / "missing.stl").string();
  CHECK(has(error_of([&] { io::read_stl(missing); }), {missing.c_str(), "does not exist"}));
  const std::string missing_obj = (folder() / "missing.obj").string();
  CHECK(has(error_of([&] { io::read_obj(missing_obj); }), {missing_obj.c_str(), "does not exist"}));
  const std::string dir = (folder() / "a_folder.stl").string();
  fs::create_directories(dir);
  CHECK(has(error_of([&] { io::read_stl(dir); }), {dir.c_str(), "is a folder"}));
  const std::string path = put("square.stl", square_ascii);
  CHECK(io::read_stl(path).triangles.size() == 2);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (const double scale : {0.0, -1e-3, nan, HUGE_VAL})
    CHECK(has(error_of([&] { io::read_stl(path, {.scale = scale}); }),
              {path.c_str(), "scale = ", "valid range: (0, inf)"}));
  for (const double min_area : {-1.0, nan, HUGE_VAL})
    CHECK(has(error_of([&] { io::read_obj(path, {.min_area = min_area}); }),
              {path.c_str(), "min_area = ", "valid range: [0, inf) m^2"}));
  const std::string ply = put("square.ply", square_ascii);
  CHECK(has(error_of([&] { io::read_mesh(ply); }),
            {ply.c_str(), "extension = '.ply' is invalid; valid range: .stl or .obj"}));
}

TEST_CASE("mesh files: write_stl refuses meshes it cannot write and reports failed writes") {
  const std::string path = (folder() / "refused.stl").string();
  fs::remove(path);
  auto m = grain::test::square2();
  m.triangles[1][2] = 4;
  CHECK(has(error_of([&] { io::write_stl(m, path); }),
            {"write_stl", path.c_str(), "triangle 1 vertex index 2 = 4 is invalid", "[0, 4)"}));
  m = grain::test::square2();
  m.vertices[3].y() = std::numeric_limits<double>::quiet_NaN();
  CHECK(has(error_of([&] { io::write_stl(m, path); }), {"vertex 3 = (0, nan, 0) is invalid"}));
  m = grain::test::square2();
  for (auto& x : m.vertices)
    x *= 1e39;
  CHECK(has(error_of([&] { io::write_stl(m, path, true); }),
            {"vertex 1 = (1e+39, 0, 0) is invalid", "single precision"}));
  io::write_stl(m, path); // ASCII holds it
  CHECK(io::read_stl(path).vertices[2] == Vec3(1e39, 1e39, 0));
  fs::remove(path);
  CHECK(has(error_of([&] { io::write_stl(walls::TriangleMesh{}, path); }),
            {"number of triangles = 0 is invalid"}));
  CHECK(has(error_of([&] { io::write_stl(grain::test::square2(), path, false, "two\nlines"); }),
            {"solid_name = 'two\\x0Alines' is invalid"}));
  CHECK(!fs::exists(path));
  if (fs::exists("/dev/full"))
    for (const bool binary : {false, true})
      CHECK(has(error_of<io::WriteError>(
                    [&] { io::write_stl(grain::test::square8(), "/dev/full", binary); }),
                {"grain::io::write_stl: cannot write '/dev/full'"}));
}

TEST_CASE("mesh files: a sphere on a square read from an STL file rests as on a plane") {
  using Contact = Interaction<normal::Hertz<>, tangent::None>;
  using Sim = Simulation<Sphere, search::CellList, Contact>;
  const std::string path = put("floor.stl", square_ascii);
  const auto floor = io::read_stl(path);
  REQUIRE(floor.vertices.size() == 4);
  const double R = 0.05;
  const Material mat = grain::test::material(0.3);
  // over the shared diagonal: one contact, of one triangle
  auto rest = [&](bool obstacle) {
    Sim::Params prm;
    prm.time_step = 1e-5;
    prm.gravity = Vec3(0, 0, -9.81);
    Sim sim(prm);
    const auto k = sim.add_material(mat);
    if (obstacle)
      add_obstacle(sim, floor, {.name = "floor", .material = k});
    else
      sim.add_wall(walls::Plane{Vec3::Zero(), Vec3::UnitZ()}, {.material = k});
    sim.add_particle({.position = Vec3(0.4, 0.4, R + 2e-3), .radius = R, .material = k});
    std::size_t most = 0;
    for (int s = 0; s < 50000; ++s) {
      sim.step();
      most = std::max(most, sim.contact_counts().second);
    }
    CHECK(most == 1);
    CHECK(sim.particles().velocity[0].norm() < 1e-6);
    return sim.particles().position[0];
  };
  const Vec3 on_mesh = rest(true), on_plane = rest(false);
  // Hertz at rest: m g = 4/3 E* sqrt(R) delta^(3/2)
  const double mass = mat.density * 4.0 / 3.0 * std::numbers::pi * R * R * R;
  const double young = PairProperties::mix(mat, mat).young_eff;
  const double delta = std::pow(mass * 9.81 / (4.0 / 3.0 * young * std::sqrt(R)), 2.0 / 3.0);
  MESSAGE("overlap " << R - on_mesh.z() << " m on the mesh, " << R - on_plane.z()
                     << " m on a plane; Hertz static overlap " << delta << " m");
  CHECK(on_mesh.x() == 0.4);
  CHECK(on_mesh.y() == 0.4);
  CHECK(on_mesh.z() == doctest::Approx(on_plane.z()).epsilon(1e-12));
  CHECK(std::abs(on_mesh.z() - (R - delta)) < 1e-3 * delta);
}
