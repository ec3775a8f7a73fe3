// Writes the legacy VTK files of a small body system (bodies, one of them converted from a sphere,
// a mesh body of two hexahedra with two face colours, springs of every geometry, ball joints)
// with two grain::bodies::body_vtk writers (ASCII and binary) in one io::every_steps, together
// with expected.json: the system's state at every output, taken from its accessors, and for the
// mesh body the world positions of all its mesh nodes (from the mesh as given and the body's
// pose, not from the surface), its pose and the colours of its listed faces.
// read_bodies_vtk.py reads the files back with VTK and compares them with expected.json.
//
// Usage: grain_write_bodies_vtk <output directory>

#include <grain/bodies/mesh.hpp>
#include <grain/bodies/output.hpp>
#include <grain/bodies/system.hpp>
#include <grain/io/console.hpp>

#include <cstdio>
#include <exception>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

namespace {

namespace gb = grain::bodies;
using grain::Table;
using grain::Vec3;

constexpr long kSteps = 7;
constexpr long kStepsPerOutput = 2;

std::string num(double x) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.17g", x);
  return buf;
}
std::string vec(const Vec3& v) {
  return "[" + num(v.x()) + ", " + num(v.y()) + ", " + num(v.z()) + "]";
}

gb::RigidBody body(double m, const Vec3& x, const Vec3& v, const Vec3& w) {
  gb::RigidBody b;
  b.mass = m;
  b.inertia = gb::inertia_tensor(0.1 * m, 0.12 * m, 0.15 * m, 0.01 * m, 0.0, 0.005 * m);
  b.position = x;
  b.velocity = v;
  b.omega = w;
  return b;
}

/// Two unit cubes side by side along x (nodes 0-7 and 1, 8, 9, 2, 5, 10, 11, 6), sharing the
/// face x = 1, turned about (1, 2, 3) by 0.6 rad and moved by (0.5, -1, 2).
gb::Mesh two_cubes() {
  const Eigen::Matrix3d r = Eigen::AngleAxisd(0.6, Vec3(1, 2, 3).normalized()).toRotationMatrix();
  gb::Mesh m;
  for (const Vec3& x :
       {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 1, 0), Vec3(0, 1, 0), Vec3(0, 0, 1), Vec3(1, 0, 1),
        Vec3(1, 1, 1), Vec3(0, 1, 1), Vec3(2, 0, 0), Vec3(2, 1, 0), Vec3(2, 0, 1), Vec3(2, 1, 1)})
    m.nodes.push_back(r * (0.4 * x) + Vec3(0.5, -1.0, 2.0));
  m.elements = {{{0, 1, 2, 3, 4, 5, 6, 7}, 800.0}, {{1, 8, 9, 2, 5, 10, 11, 6}, 800.0}};
  return m;
}
/// Global colour 3; the end faces x = 0 and x = 2 in colour 5 (listed in other node orders).
const std::vector<long> kColours{3, 4, 7, 0, 4, 3, 5, 4, 10, 11, 9, 8, 5};

/// Records the system's state at every call as a JSON frame.
struct Recorder {
  std::vector<std::string>* frames;
  const gb::Mesh* mesh;
  Vec3 centre;              // the mesh's centre of mass as given
  std::vector<Vec3>* start; // the positions at the first call (the writers' displacements)
  void operator()(const gb::BodySystem& s) const {
    const auto& b = s.bodies();
    if (start->empty()) *start = b.position;
    std::string f = "{\"time\": " + num(s.time()) + ", \"meshes\": [";
    for (std::size_t k = 0; k < s.mesh_count(); ++k) {
      const std::size_t i = s.mesh_body_index(k);
      f += std::string(k ? ", " : "") + "{\"body\": " + std::to_string(i) +
           ", \"position\": " + vec(b.position[i]) + ", \"velocity\": " + vec(b.velocity[i]) +
           ", \"omega\": " + vec(b.omega[i]) + ", \"nodes\": [";
      for (std::size_t n = 0; n < mesh->nodes.size(); ++n)
        f += std::string(n ? ", " : "") + vec(gb::to_world(b, i, mesh->nodes[n] - centre));
      f += "]}";
    }
    f += "], \"bodies\": [";
    for (std::size_t i = 0; i < b.size(); ++i) {
      const Eigen::Quaterniond q(b.orientation[i] * b.axes[i].conjugate());
      f += std::string(i ? ", " : "") + "{\"position\": " + vec(b.position[i]) +
           ", \"velocity\": " + vec(b.velocity[i]) + ", \"omega\": " + vec(b.omega[i]) +
           ", \"force\": " + vec(b.force[i]) + ", \"torque\": " + vec(b.torque[i]) +
           ", \"mass\": " + num(b.mass[i]) + ", \"orientation\": [" + num(q.w()) + ", " +
           num(q.x()) + ", " + num(q.y()) + ", " + num(q.z()) +
           "], \"radius\": " + num(b.radius[i]) +
           ", \"displacement\": " + vec(b.position[i] - (*start)[i]) + "}";
    }
    f += "], \"springs\": [";
    for (std::size_t i = 0; i < s.spring_count(); ++i) {
      const auto [p1, p2] = gb::spring_line(s, i);
      const auto& r = s.spring_result(i);
      f += std::string(i ? ", " : "") + "{\"p1\": " + vec(p1) + ", \"p2\": " + vec(p2) +
           ", \"force\": " + vec(r.force) + ", \"total_force\": " + num(r.total) +
           ", \"elastic_force\": " + num(r.elastic) + ", \"friction_force\": " + num(r.friction) +
           ", \"stroke\": " + num(r.stroke) + ", \"length\": " + num(r.length) +
           ", \"state\": " + std::to_string(s.spring_state(i).code) + "}";
    }
    f += "], \"torsion_springs\": [";
    for (std::size_t i = 0; i < s.torsion_spring_count(); ++i) {
      const auto& r = s.torsion_result(i);
      f += std::string(i ? ", " : "") + "{\"point\": " + vec(s.torsion_point(i)) +
           ", \"torque\": " + vec(r.torque) + ", \"xdir\": " + vec(r.x) +
           ", \"ydir\": " + vec(r.y) + ", \"zdir\": " + vec(r.z) +
           ", \"roll\": " + num(r.angles[0]) + ", \"pitch\": " + num(r.angles[1]) +
           ", \"yaw\": " + num(r.angles[2]) + ", \"spring_torque\": " + vec(r.spring_torque) +
           ", \"total_torque\": " + vec(r.total_torque) + "}";
    }
    f += "], \"joints\": [";
    for (std::size_t i = 0; i < s.joint_count(); ++i) {
      const auto& r = s.joint_result(i);
      f += std::string(i ? ", " : "") + "{\"point\": " + vec(s.joint_points(i).first) +
           ", \"reaction\": " + vec(r.reaction) + ", \"gap\": " + num(r.gap) + "}";
    }
    frames->push_back(f + "]}");
  }
};

} // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: grain_write_bodies_vtk <output directory>\n");
    return 2;
  }
  try {
    const std::filesystem::path dir(argv[1]);
    std::filesystem::create_directories(dir);
    gb::BodySystem s(Vec3(0.0, 0.0, -9.81));
    s.add_body(body(1.0, Vec3(0.0, 0.0, -0.5), Vec3(0.1, 0.0, 0.0), Vec3(0.0, 0.2, 0.0)));
    s.add_body(body(2.0, Vec3(0.0, 0.0, -1.5), Vec3(0.0, 0.3, 0.0), Vec3(0.5, 0.0, 0.1)));
    s.add_body(body(0.5, Vec3(1.0, 0.5, -1.0), Vec3(0.0, 0.0, 0.2), Vec3(0.0, 0.0, 1.0)));
    // a sphere converted to a body keeps its radius for display; a meshed body its surface
    s.add_body(gb::sphere_body(0.05, 7800.0, Vec3(-1.0, 0.0, 0.5), Vec3(0.0, 0.1, 0.0)));
    const gb::Mesh mesh = two_cubes();
    s.add_mesh_body(mesh, gb::face_colors_from_list(kColours), Vec3(0.2, -0.1, 0.3),
                    Vec3(1.0, -2.0, 0.5), "two cubes");
    s.add_ball_joint(0, Vec3::Zero());
    s.add_ball_joint(0, Vec3(0.0, 0.0, -1.0), 1);
    const Table k({-1.0, 1.0}, {-200.0, 200.0});
    s.add_spring({.spring = k, .damping_ratio = 0.1}, 2, Vec3(1.0, 0.5, -1.0), 1,
                 Vec3(0.0, 0.0, -1.4));
    s.add_spring({.spring = k,
                  .geometry = gb::SpringGeometry::constant_direction,
                  .direction = Vec3::UnitZ()},
                 2, Vec3(1.0, 0.5, -0.9), gb::world, Vec3(1.0, 0.5, 0.0));
    s.add_spring({.spring = Table({-1.0, 0.0, 1.0}, {-1000.0, 0.0, 0.0}),
                  .geometry = gb::SpringGeometry::point_to_plane,
                  .friction = 0.3},
                 1, Vec3(0.0, 0.0, -1.9), gb::world, Vec3(0.0, 0.0, -1.9), Vec3(0.1, 0.0, 1.0));
    s.add_spring({.spring = k,
                  .geometry = gb::SpringGeometry::planar,
                  .direction = Vec3::UnitX(),
                  .inactive = true},
                 2, Vec3(1.0, 0.5, -1.0), 0, Vec3(0.0, 0.2, -0.5));
    gb::TorsionSpringParams tp;
    tp.roll.spring = Table({-1.0, 1.0}, {-5.0, 5.0});
    tp.yaw.spring = Table({-1.0, 1.0}, {-3.0, 3.0});
    tp.yaw.damping_ratio = 0.2;
    s.add_torsion_spring(tp, 2, 1, Vec3::UnitZ(), Vec3::UnitX());
    std::vector<std::string> frames;
    std::vector<Vec3> start;
    s.steps(kSteps, 1e-3,
            grain::io::every_steps(
                kStepsPerOutput, gb::body_vtk((dir / "sys").string()),
                gb::body_vtk((dir / "sys_binary").string(), grain::io::VtkFormat::binary),
                Recorder{&frames, &mesh, gb::mass_properties(mesh).centre, &start}));
    std::ofstream out(dir / "expected.json");
    out << "{\"series\": {\"sys\": \"ascii\", \"sys_binary\": \"binary\"},\n";
    // the mesh's faces as node sets with their colours: 10 boundary faces, the listed ones 5
    out << " \"mesh_faces\": 10, \"global_colour\": 3, \"listed_faces\": [[[0, 3, 4, 7], 5], "
           "[[8, 9, 10, 11], 5]],\n \"frames\": [\n";
    for (std::size_t k = 0; k < frames.size(); ++k)
      out << "  " << frames[k] << (k + 1 < frames.size() ? ",\n" : "\n");
    out << "]}\n";
    if (!out) throw std::runtime_error("cannot write expected.json");
  } catch (const std::exception& e) {
    std::fprintf(stderr, "grain_write_bodies_vtk: %s\n", e.what());
    return 1;
  }
  return 0;
}
