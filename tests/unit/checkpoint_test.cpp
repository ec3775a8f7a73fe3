// Checkpoint and restart: a resumed run continues bit-identically to an uninterrupted one, and
// files that do not fit the simulation are rejected with messages that say why.

#include <doctest/doctest.h>
#include <grain/grain.hpp>
#include <grain/models/conduction/batchelor_obrien.hpp>

#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>
#include <type_traits>
#include <vector>

using namespace grain;

namespace {

using Contact =
    Interaction<normal::Hertz<>, tangent::Mindlin, rolling::None, conduction::BatchelorOBrien>;
using Sim = Simulation<Sphere, search::CellList, Contact>;
using SimEuler = Simulation<Sphere, search::CellList, Contact, integrate::SymplecticEuler>;

std::string temp_path(const std::string& name) {
  const auto dir = std::filesystem::temp_directory_path() / "grain_checkpoint_test";
  std::filesystem::create_directories(dir);
  return (dir / name).string();
}

/// A thermo-mechanical pile with everything that carries state across steps: tangential
/// (Mindlin) histories, a hot wall, a prescribed force and a fixed temperature on groups, a
/// temperature-dependent conductivity (per-contact constants), a sink and a particle that is
/// created late.
template <class S>
S make(double young = 1e7) {
  typename S::Params prm;
  prm.time_step = 2e-6;
  prm.gravity = Vec3(0, 0, -9.81);
  prm.max_start_overlap = 0.25; // the pile starts with particles up to 0.17 R into each other
  S sim(prm);
  Material m;
  m.density = 2500;
  m.young = young;
  m.friction = 0.4;
  m.conductivity = 1;
  m.heat_capacity = 800;
  const auto k = sim.add_material(m);
  sim.add_wall(walls::Plane{{0, 0, 0}, {0, 0, 1}}, {.material = k, .temperature = 350.0});
  std::vector<std::int64_t> first;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j)
      for (int l = 0; l < 3; ++l) {
        const auto id =
            sim.add_particle({.position = {0.021 * i + 0.002 * l, 0.021 * j, 0.011 + 0.021 * l},
                              .radius = 0.01,
                              .material = k,
                              .velocity = {0.05 * j, -0.02 * i, 0},
                              .temperature = 300.0 + 5 * l});
        if (l == 2) first.push_back(id);
      }
  sim.add_particle({.position = {0.03, 0.03, 0.2},
                    .radius = 0.008,
                    .material = k,
                    .temperature = 400.0,
                    .creation_time = 0.03});
  sim.add_group("top", first);
  sim.prescribe_force("top",
                      VectorTimeFunction<3>(TimeFunction::oscillatory(0, 1e-3, 0.01), 0.0, 0.0));
  sim.add_group("held", {first.front()});
  sim.fix_temperature("held", 380.0);
  sim.add_variable_property(
      {"all", Property::conductivity, Variable::temperature, Table({{300.0, 1.0}, {400.0, 2.0}})});
  sim.add_sink(regions::Box<3>{{0.06, -1, -1}, {1, 1, 1}});
  return sim;
}

template <class S>
void require_identical(const S& a, const S& b) {
  REQUIRE(a.size() == b.size());
  REQUIRE(a.step_count() == b.step_count());
  CHECK(a.time() == b.time());
  CHECK(a.removed_ids() == b.removed_ids());
  const auto& p = a.particles();
  const auto& q = b.particles();
  std::size_t differ = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    differ += p.id[i] != q.id[i] || p.position[i] != q.position[i] ||
              p.velocity[i] != q.velocity[i] || p.omega[i] != q.omega[i] ||
              p.force[i] != q.force[i] || p.temperature[i] != q.temperature[i] ||
              !p.orientation[i].coeffs().isApprox(q.orientation[i].coeffs(), 0.0);
  }
  CHECK(differ == 0);
}

} // namespace

TEST_CASE("checkpoint: a resumed run continues bit-identically") {
  const std::string path = temp_path("pile.ckpt");
  Sim whole = make<Sim>();
  whole.run(0.05);
  REQUIRE(whole.removed_ids().size() > 0); // the sink acted
  REQUIRE(whole.inactive_count() == 0);    // the late particle came

  Sim first = make<Sim>();
  first.run(0.02); // before the late particle is created
  io::save_checkpoint(first, path);
  Sim resumed = make<Sim>();
  io::load_checkpoint(resumed, path);
  CHECK(resumed.inactive_count() == 1);
  resumed.run(0.03);
  require_identical(whole, resumed);

  // the tangential histories were restored, not restarted: a run resumed without them differs
  Sim fresh = make<Sim>();
  fresh.run(0.02);
  auto& fp = fresh.particles();
  Sim restarted = make<Sim>();
  for (std::size_t i = 0; i < restarted.size(); ++i) {
    if (!fresh.is_active(restarted.particles().id[i])) continue; // the sink took it
    const auto k = fresh.index_of(restarted.particles().id[i]);
    restarted.particles().position[i] = fp.position[k];
    restarted.particles().velocity[i] = fp.velocity[k];
    restarted.particles().omega[i] = fp.omega[k];
    restarted.particles().temperature[i] = fp.temperature[k];
  }
  restarted.run(0.03);
  bool all_same = true;
  for (std::size_t i = 0; i < whole.size(); ++i)
    all_same =
        all_same && whole.particles().position[i] ==
                        restarted.particles().position[restarted.index_of(whole.particles().id[i])];
  CHECK_FALSE(all_same);
}

TEST_CASE("checkpoint: the periodic observer writes a file a run can resume from") {
  const std::string path = temp_path("periodic.ckpt");
  std::filesystem::remove(path);
  Sim a = make<Sim>();
  a.run(0.01, io::every(0.005, io::checkpoint(path)));
  REQUIRE(std::filesystem::exists(path));
  CHECK_FALSE(std::filesystem::exists(path + ".tmp"));
  Sim b = make<Sim>();
  io::load_checkpoint(b, path);
  CHECK(b.time() == a.time());
  a.run(0.005);
  b.run(0.005);
  require_identical(a, b);
}

TEST_CASE("checkpoint: files that do not fit are rejected with the reason") {
  const std::string path = temp_path("reject.ckpt");
  Sim a = make<Sim>();
  a.run(0.001);
  io::save_checkpoint(a, path);

  SUBCASE("another format version") {
    const std::string bad = temp_path("version.ckpt");
    std::filesystem::copy_file(path, bad, std::filesystem::copy_options::overwrite_existing);
    std::fstream f(bad, std::ios::in | std::ios::out | std::ios::binary);
    const std::uint32_t v = 99;
    f.seekp(8);
    f.write(reinterpret_cast<const char*>(&v), sizeof v);
    f.close();
    Sim b = make<Sim>();
    CHECK_THROWS_WITH_AS(io::load_checkpoint(b, bad),
                         doctest::Contains("format version = 99 is invalid; valid: 5"), InputError);
  }
  SUBCASE("another simulation type") {
    SimEuler b = make<SimEuler>();
    CHECK_THROWS_WITH_AS(io::load_checkpoint(b, path),
                         doctest::Contains("simulation type = 'sphere 3D"), InputError);
  }
  SUBCASE("other materials") {
    Sim b = make<Sim>(2e7);
    CHECK_THROWS_WITH_AS(io::load_checkpoint(b, path), doctest::Contains("materials"), InputError);
  }
  SUBCASE("another number of walls") {
    Sim b = make<Sim>();
    b.add_wall(walls::Plane{{0, 0, 1}, {0, 0, -1}});
    CHECK_THROWS_WITH_AS(io::load_checkpoint(b, path), doctest::Contains("walls = 1 is invalid"),
                         InputError);
  }
  SUBCASE("a truncated file") {
    const std::string bad = temp_path("truncated.ckpt");
    std::filesystem::copy_file(path, bad, std::filesystem::copy_options::overwrite_existing);
    std::filesystem::resize_file(bad, std::filesystem::file_size(bad) / 2);
    Sim b = make<Sim>();
    CHECK_THROWS_WITH_AS(io::load_checkpoint(b, bad), doctest::Contains("truncated or corrupt"),
                         InputError);
    // the failed load leaves b as it was set up: it runs exactly as a never-loaded set-up does
    CHECK_FALSE(b.initialized());
    Sim fresh = make<Sim>();
    fresh.run(0.001);
    b.run(0.001);
    require_identical(fresh, b);
    // and after a run, a failed load leaves the state of that run: the loads on the walls of
    // its last step and a removal requested since
    static_assert(std::is_copy_assignable_v<Sim>);
    for (int k = 0; k < 200 && b.wall_force(0).norm() == 0.0; ++k) { // until the floor is hit
      fresh.run(1e-4);
      b.run(1e-4);
    }
    const Vec3 floor_load = b.wall_force(0);
    REQUIRE(floor_load.norm() > 0.0);
    const std::int64_t victim = b.particles().id[0];
    b.remove_particle(victim);
    fresh.remove_particle(victim);
    CHECK_THROWS_AS(io::load_checkpoint(b, bad), InputError);
    CHECK(b.initialized());
    CHECK(b.wall_force(0) == floor_load);
    fresh.run(0.001);
    b.run(0.001);
    require_identical(fresh, b);
    CHECK_FALSE(b.is_active(victim));
  }
  SUBCASE("another search type") {
    using SimVerlet = Simulation<Sphere, search::VerletList, Contact>;
    SimVerlet b = make<SimVerlet>();
    CHECK_THROWS_WITH_AS(io::load_checkpoint(b, path), doctest::Contains("search Verlet list"),
                         InputError);
  }
  SUBCASE("a missing file and a file of another kind") {
    Sim b = make<Sim>();
    CHECK_THROWS_WITH_AS(io::load_checkpoint(b, temp_path("none.ckpt")),
                         doctest::Contains("missing or unreadable"), InputError);
    const std::string text = temp_path("text.ckpt");
    std::ofstream(text) << "time,step\n0,0\n";
    CHECK_THROWS_WITH_AS(io::load_checkpoint(b, text), doctest::Contains("file type is invalid"),
                         InputError);
  }
  SUBCASE("a simulation that never started cannot be saved") {
    Sim b = make<Sim>();
    CHECK_THROWS_WITH_AS(io::save_checkpoint(b, temp_path("early.ckpt")),
                         doctest::Contains("not initialised"), InputError);
  }
}

TEST_CASE("checkpoint: corrupt contents are rejected before the simulation takes them") {
  const std::string path = temp_path("contents.ckpt");
  Sim a = make<Sim>();
  a.run(0.001);
  io::save_checkpoint(a, path);
  // the length of the first per-particle array (ids) follows the header
  const std::size_t ids = 8 + 4 + 8 + std::string(GRAIN_VERSION_STRING).size() + 8 +
                          io::detail::signature<Sim>().size() + 8 +
                          8 * io::detail::material_numbers(a.materials()).size() + 8 + 8;
  const auto patched = [&](std::size_t at, const auto& value) {
    const std::string bad = temp_path("patched.ckpt");
    std::filesystem::copy_file(path, bad, std::filesystem::copy_options::overwrite_existing);
    std::fstream f(bad, std::ios::in | std::ios::out | std::ios::binary);
    f.seekp(static_cast<std::streamoff>(at));
    f.write(reinterpret_cast<const char*>(&value), sizeof value);
    return bad;
  };
  std::uint64_t n = 0;
  {
    std::ifstream f(path, std::ios::binary);
    f.seekg(static_cast<std::streamoff>(ids));
    f.read(reinterpret_cast<char*>(&n), sizeof n);
  }
  REQUIRE(n == a.size());
  Sim b = make<Sim>();
  SUBCASE("per-particle arrays of another length than the number of particles") {
    const std::string why = "a per-particle array of " + std::to_string(n - 1) + " entries for " +
                            std::to_string(n) + " particles";
    CHECK_THROWS_WITH_AS(io::load_checkpoint(b, patched(ids, std::uint64_t{n - 1})),
                         doctest::Contains(why.c_str()), InputError);
  }
  SUBCASE("a length larger than the file can hold") {
    CHECK_THROWS_WITH_AS(io::load_checkpoint(b, patched(ids, std::uint64_t{1} << 61)),
                         doctest::Contains("a length of 2305843009213693952"), InputError);
  }
  SUBCASE("a truth value that is neither 0 nor 1") {
    // the last item before the end mark is the flag `initialized`
    const auto flag = std::filesystem::file_size(path) - 8 - 1;
    CHECK_THROWS_WITH_AS(io::load_checkpoint(b, patched(flag, std::uint8_t{2})),
                         doctest::Contains("a truth value of 2"), InputError);
  }
  CHECK_FALSE(b.initialized()); // each failed load leaves b as it was
}

namespace {
/// An archive that reads nothing: it hands each item of a state to `edit`, which puts into it
/// a value a corrupt file could hold.
template <class F>
struct EditArchive {
  static constexpr bool reading = true;
  F edit;
  template <class... T>
  void operator()(T&... items) {
    (edit(items), ...);
  }
};
template <class F>
EditArchive<F> edit_archive(F f) {
  return {std::move(f)};
}
} // namespace

TEST_CASE("checkpoint: a state read that a step cannot run is refused, not run") {
  Sim a = make<Sim>();
  a.run(0.001);
  REQUIRE(a.histories().size() > 0);
  SUBCASE("a contact history whose sliding flag is neither 0 nor 1") {
    // any bytes fill a history; the truth value of the stick-slip models is checked
    auto ar = edit_archive([](auto& x) {
      if constexpr (std::is_same_v<std::decay_t<decltype(x)>, std::vector<Sim::History>>)
        if (!x.empty()) std::memset(&x.front().tangent.sliding, 2, 1);
    });
    CHECK_THROWS_WITH_AS(a.serialize(ar), doctest::Contains("the state read has a contact history"),
                         InputError);
  }
  SUBCASE("step counters that would overflow the time") {
    auto ar = edit_archive([](auto& x) {
      if constexpr (std::is_same_v<std::decay_t<decltype(x)>, long>)
        x = std::numeric_limits<long>::min();
    });
    CHECK_THROWS_WITH_AS(a.serialize(ar), doctest::Contains("the step counters"), InputError);
  }
  SUBCASE("a negative radius") {
    auto radius = edit_archive([](auto& x) {
      if constexpr (std::is_same_v<std::decay_t<decltype(x)>, std::vector<double>>)
        if (!x.empty() && x.front() == 0.01) x.front() = -0.01; // the first radius
    });
    CHECK_THROWS_WITH_AS(a.serialize(radius), doctest::Contains("the radius -0.01 m of particle 0"),
                         InputError);
  }
  SUBCASE("a repeated particle id") {
    bool first = true;
    auto ids = edit_archive([&](auto& x) {
      if constexpr (std::is_same_v<std::decay_t<decltype(x)>, std::vector<std::int64_t>>)
        if (first && x.size() > 1) {
          x[1] = x[0];
          first = false;
        }
    });
    CHECK_THROWS_WITH_AS(a.serialize(ids), doctest::Contains("a repeated particle id"), InputError);
  }
}

TEST_CASE("the search survives particles at the ends of the doubles") {
  // an extent beyond the largest double must neither hang the grid nor overflow a cell index
  Simulation<Sphere, search::CellList, presets::LinearCoulomb> sim({.time_step = 1e-6});
  Material m;
  m.density = 2500;
  m.young = 1e7;
  const auto k = sim.add_material(m);
  sim.add_particle({.position = {-1e308, 0, 0}, .radius = 0.01, .material = k});
  sim.add_particle({.position = {1e308, 0, 0}, .radius = 0.01, .material = k});
  sim.add_particle({.position = {0, 0, 0}, .radius = 0.01, .material = k});
  sim.add_particle({.position = {0.0199, 0, 0}, .radius = 0.01, .material = k});
  sim.steps(3);
  CHECK(sim.neighbor_list().partners.size() >= 1);           // the touching pair is listed
  CHECK(sim.particles().velocity[sim.index_of(3)][0] > 0.0); // and pushed apart
}
