#pragma once
// Triangle meshes of the obstacle tests.
#include <grain/core/vector.hpp>
#include <grain/walls/mesh_features.hpp>

#include <Eigen/Dense>

namespace grain::test {

/// The unit square [0, 1]^2 at z = 0 in two triangles (diagonal (0, 0)-(1, 1)).
inline walls::TriangleMesh square2() {
  return {{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 1, 0), Vec3(0, 1, 0)}, {{0, 1, 2}, {0, 2, 3}}};
}

/// The unit square in eight triangles that all meet at the centre (vertex 4): a 3 x 3 grid of
/// vertices, each quarter split by the diagonal through the centre. Vertices 1, 3, 5, 7 are the
/// midpoints of the sides, where two boundary edges go on in a straight line.
inline walls::TriangleMesh square8() {
  walls::TriangleMesh m;
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 3; ++i)
      m.vertices.push_back(Vec3(0.5 * i, 0.5 * j, 0));
  m.triangles = {{0, 1, 4}, {0, 4, 3}, {1, 2, 4}, {2, 5, 4},
                 {3, 4, 6}, {4, 7, 6}, {4, 5, 8}, {4, 8, 7}};
  return m;
}

/// The box [lo, hi], each side split into two triangles; vertex k has the coordinates of hi where
/// its bits 1, 2, 4 (x, y, z) are set and those of lo elsewhere.
inline walls::TriangleMesh box(const Vec3& lo, const Vec3& hi) {
  walls::TriangleMesh m;
  for (int k = 0; k < 8; ++k)
    m.vertices.push_back(
        Vec3(k & 1 ? hi.x() : lo.x(), k & 2 ? hi.y() : lo.y(), k & 4 ? hi.z() : lo.z()));
  m.triangles = {{0, 2, 3}, {0, 3, 1}, {4, 5, 7}, {4, 7, 6}, {0, 1, 5}, {0, 5, 4},
                 {2, 6, 7}, {2, 7, 3}, {0, 4, 6}, {0, 6, 2}, {1, 3, 7}, {1, 7, 5}};
  return m;
}

/// The mesh turned by R and shifted by s.
inline walls::TriangleMesh moved(walls::TriangleMesh m, const Eigen::Matrix3d& R, const Vec3& s) {
  for (auto& x : m.vertices)
    x = R * x + s;
  return m;
}

} // namespace grain::test
