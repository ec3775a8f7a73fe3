// Fuzz target of grain::io::read_stl and read_obj: the input is written as an .stl and as an .obj
// file and read, with and without merging of vertices. Each read either throws grain::InputError
// or gives a mesh that obstacles accept: at least one triangle, finite vertices, indices in
// range, three different vertices per triangle, walls::MeshFeatures built without an error (for
// the merged mesh).
// Reads with and without merging agree on every triangle's corners, and a mesh written by
// write_stl as ASCII reads back identical.

#include "fuzz_support.hpp"

#include <grain/io/mesh_file.hpp>
#include <grain/walls/mesh_features.hpp>

#include <cstddef>
#include <cstdint>
#include <string>

namespace {

using grain::walls::TriangleMesh;

/// Aborts unless m is a valid mesh (see the file comment); `features`: also builds its features.
void check(const TriangleMesh& m, bool features) {
  if (m.triangles.empty()) grain_fuzz::fail("mesh without triangles");
  for (const auto& x : m.vertices)
    if (!x.allFinite()) grain_fuzz::fail("vertex not finite");
  for (const auto& t : m.triangles) {
    for (const auto v : t)
      if (v >= m.vertices.size()) grain_fuzz::fail("vertex index out of range");
    if (t[0] == t[1] || t[1] == t[2] || t[2] == t[0]) grain_fuzz::fail("repeated vertex index");
  }
  if (!features) return;
  try {
    grain::walls::MeshFeatures::build(m, grain::Vec3::Zero(), "fuzz");
  } catch (const grain::InputError&) {
    grain_fuzz::fail("a mesh read is refused by MeshFeatures");
  }
}

/// True if a and b have the same triangles with the same corners.
bool same_corners(const TriangleMesh& a, const TriangleMesh& b) {
  if (a.triangles.size() != b.triangles.size()) return false;
  for (std::size_t k = 0; k < a.triangles.size(); ++k)
    for (int j = 0; j < 3; ++j)
      if (a.vertices[a.triangles[k][j]] != b.vertices[b.triangles[k][j]]) return false;
  return true;
}

/// Reads the file with `read` merged and unmerged and checks both.
template <class Read>
void run(const std::string& path, Read read) {
  TriangleMesh merged, loose;
  bool ok_merged = false, ok_loose = false;
  try {
    merged = read(path, grain::io::MeshReadOptions{});
    ok_merged = true;
  } catch (const grain::InputError&) {
  }
  try {
    loose = read(path, grain::io::MeshReadOptions{.merge_vertices = false});
    ok_loose = true;
  } catch (const grain::InputError&) {
  }
  if (ok_merged != ok_loose) grain_fuzz::fail("merging decides whether a file is read");
  if (!ok_merged) return;
  check(merged, true);
  check(loose, false); // its triangles are the same, each on its own
  if (!same_corners(merged, loose)) grain_fuzz::fail("merged and unmerged triangles differ");
  // ASCII round trip: the shortest decimal text reads back to the same doubles
  const std::string out = (grain_fuzz::scratch() / "written.stl").string();
  grain::io::write_stl(merged, out);
  const TriangleMesh again = grain::io::read_stl(out);
  if (again.vertices != merged.vertices || again.triangles != merged.triangles)
    grain_fuzz::fail("ASCII STL round trip differs");
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  run(grain_fuzz::write_input("mesh.stl", data, size),
      [](const std::string& p, const grain::io::MeshReadOptions& o) {
        return grain::io::read_stl(p, o);
      });
  run(grain_fuzz::write_input("mesh.obj", data, size),
      [](const std::string& p, const grain::io::MeshReadOptions& o) {
        return grain::io::read_obj(p, o);
      });
  return 0;
}
