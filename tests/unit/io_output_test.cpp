// Output helpers over long runs, failing files and restarts: io::every keeps to its time grid,
// writers report a write that did not reach the file (a failed checkpoint keeps the previous
// one), and writers resumed after a checkpoint leave the files of an uninterrupted run.
#include "../errors.hpp"
#include "../support/csv_files.hpp"
#include <doctest/doctest.h>
#include <grain/grain.hpp>

#include <sys/resource.h>

#include <algorithm>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

using namespace grain;

namespace {

using Sim3 = Simulation<Sphere, search::AllPairs, Interaction<normal::Hertz<>>>;

using grain::test::error_of;
using grain::test::Folder;
using grain::test::has;
using grain::test::scratch;

std::string file_text(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

/// A device whose writes always fail with "No space left on device" (Linux).
const char* const full_device = "/dev/full";
bool have_full_device() { return std::filesystem::exists(full_device); }

/// While it lives, files written by this process may not grow beyond `bytes` (RLIMIT_FSIZE) and
/// SIGXFSZ is ignored, so that a write past the limit fails with EFBIG as on a full disk. Both
/// are restored when it goes, also when a check fails or an exception leaves the scope.
class FileSizeLimit {
public:
  explicit FileSizeLimit(rlim_t bytes) {
    previous_ = std::signal(SIGXFSZ, SIG_IGN);
    if (getrlimit(RLIMIT_FSIZE, &saved_) != 0) return;
    rlimit r = saved_;
    r.rlim_cur = saved_.rlim_max == RLIM_INFINITY ? bytes : std::min(bytes, saved_.rlim_max);
    active_ = setrlimit(RLIMIT_FSIZE, &r) == 0;
  }
  ~FileSizeLimit() {
    if (active_) setrlimit(RLIMIT_FSIZE, &saved_);
    std::signal(SIGXFSZ, previous_);
  }
  FileSizeLimit(const FileSizeLimit&) = delete;
  FileSizeLimit& operator=(const FileSizeLimit&) = delete;
  bool active() const { return active_; }

private:
  rlimit saved_{};
  void (*previous_)(int) = SIG_DFL;
  bool active_ = false;
};

/// Five spheres dropped onto a floor: contacts, a wall, a state that changes every step.
Sim3 pile() {
  Sim3::Params p;
  p.time_step = 1e-5;
  p.gravity = {0, 0, -9.81};
  Sim3 sim(p);
  const auto m = sim.add_material({.name = "glass", .density = 2500, .young = 1e7});
  sim.add_wall(walls::Plane{{0, 0, 0}, {0, 0, 1}}, {.material = m});
  for (int k = 0; k < 5; ++k)
    sim.add_particle({.position = {0.0015 * k, 0.0, 0.0012 + 0.0021 * k},
                      .radius = 1e-3,
                      .material = m,
                      .velocity = {0.0, 0.01 * k, 0.0}});
  return sim;
}

} // namespace

TEST_CASE("io::every keeps to the grid start + k interval over a long run") {
  // 25 s at dt = 1e-3 with an output every 0.01 s: each output at the step of its due time
  Sim3::Params p;
  p.time_step = 1e-3;
  Sim3 sim(p);
  const auto m = sim.add_material({.name = "glass", .density = 2500, .young = 1e7});
  sim.add_particle({.position = {0, 0, 0}, .radius = 0.05, .material = m, .velocity = {0.1, 0, 0}});
  const double interval = 0.01, duration = 25.0;
  std::vector<double> times;
  sim.run(duration, io::every(interval, [&](const Sim3& s) { times.push_back(s.time()); }));
  const auto expected = static_cast<std::size_t>(std::llround(duration / interval)) + 1;
  CHECK(times.size() == expected);
  std::size_t off_grid = 0, first_off = expected;
  for (std::size_t k = 0; k < times.size(); ++k) {
    // the k-th output is due at k interval; a step late would be 1e-3 s off
    if (std::abs(times[k] - static_cast<double>(k) * interval) > 1e-9) {
      ++off_grid;
      first_off = std::min(first_off, k);
    }
  }
  INFO("first output off the grid: number " << first_off);
  CHECK(off_grid == 0);
}

TEST_CASE("io::every with an interval that is a function of time") {
  // interval(t) = 0.1 + 0.1 t, evaluated at each step (dt = 1e-3): an output at the first step
  // whose time reaches the last due time plus interval(t), which then advances by it; and one at
  // the end. The due times: 0, 0.1, then t_(k+1) = t_k + 0.1 + 0.1 t with t the step of output
  Sim3::Params p;
  p.time_step = 1e-3;
  Sim3 sim(p);
  const auto m = sim.add_material({.name = "glass", .density = 2500, .young = 1e7});
  sim.add_particle({.position = {0, 0, 0}, .radius = 0.05, .material = m});
  std::vector<double> times;
  const auto interval = TimeFunction::table({{0.0, 0.1}, {1.0, 0.2}});
  sim.run(1.0, io::every(interval, [&](const Sim3& s) { times.push_back(s.time()); }));
  // by hand: step k at t = k ms; output when t >= due + 0.1 + 0.1 t, i.e. t >= (due + 0.1) / 0.9
  std::vector<double> expected{0.0};
  double due = 0.0;
  for (int k = 1; k <= 1000; ++k) {
    const double t = k * 1e-3;
    if (t + 1e-6 >= due + 0.1 + 0.1 * t) {
      due += 0.1 + 0.1 * t;
      expected.push_back(t);
    }
  }
  if (expected.back() != 1.0) expected.push_back(1.0);
  REQUIRE(times.size() == expected.size());
  for (std::size_t k = 0; k < times.size(); ++k)
    CHECK(std::abs(times[k] - expected[k]) < 1e-9);
  CHECK(expected.size() == 8); // 0, 0.112, 0.235, 0.372, 0.525, 0.694, 0.882, 1
  // a constant interval gives the outputs of the fixed-interval every
  times.clear();
  sim.run(0.5, io::every(TimeFunction::callable([](double) { return 0.25; }),
                         [&](const Sim3& s) { times.push_back(s.time()); }));
  CHECK(times.size() == 3); // 1.0, 1.25, 1.5
  // an interval that is not positive names the time
  CHECK(has(error_of([&] {
              sim.run(0.1, io::every(TimeFunction::callable(
                                         [](double t) { return t > 1.55 ? 0.0 : 0.01; }),
                                     [](const Sim3&) {}));
            }),
            {"grain::io::every", "interval = 0", "at t = 1.55"}));
}

// ------------------------------------------------------------------ failed writes
TEST_CASE("a CSV history, an io::print file and a VTK series that cannot be written throw") {
  if (!have_full_device()) {
    MESSAGE("no " << full_device << " on this system: the test is skipped");
    return;
  }
  Sim3 sim = pile();
  // opening the device succeeds; the header is lost at its flush
  const std::string csv = error_of<std::runtime_error>(
      [&] { sim.run(1e-4, io::every(1e-5, io::history(full_device, io::lifecycle_columns()))); });
  CHECK(has(csv, "grain::io::csv"));
  CHECK(has(csv, full_device));
  const std::string print = error_of<std::runtime_error>(
      [&] { sim.run(1e-4, io::every(1e-5, io::print(std::string(full_device)))); });
  CHECK(has(print, "grain::io::print"));
  CHECK(has(print, full_device));
  // the frames are written; the series file that lists them is not
  const auto dir = scratch("grain_io_output_test/series", Folder::empty);
  std::filesystem::create_symlink(full_device, dir / "bed_particles.vtk.series");
  const std::string series = error_of<std::runtime_error>(
      [&] { sim.run(1e-4, io::every(1e-5, io::vtk((dir / "bed").string()))); });
  CHECK(has(series, "grain::io::vtk"));
  CHECK(has(series, "bed_particles.vtk.series"));
  CHECK(std::filesystem::exists(dir / "bed_particles_000000.vtk"));
  std::filesystem::remove_all(dir);
}

TEST_CASE("a CSV row that does not reach the file throws") {
  Sim3 sim = pile();
  const auto dir = scratch("grain_io_output_test/rows", Folder::empty);
  const auto path = dir / "h.csv";
  auto out = io::every_steps(1, io::history(path.string(), io::lifecycle_columns()));
  sim.steps(4, out); // header and five rows
  const auto size = std::filesystem::file_size(path);
  const auto row = size / 6; // about one line
  std::string error;
  {
    FileSizeLimit limit(size + 2 * row); // room for two more rows, not for 50
    REQUIRE(limit.active());
    error = error_of<std::runtime_error>([&] { sim.steps(50, out); });
  }
  CHECK(has(error, "grain::io::csv: cannot write '" + path.string() + "'"));
  CHECK(std::filesystem::file_size(path) <= size + 2 * row);
  std::filesystem::remove_all(dir);
}

TEST_CASE("checkpoint: a save that fails keeps the previous checkpoint and says why") {
  const auto dir = scratch("grain_io_output_test/checkpoint", Folder::empty);
  const std::string path = (dir / "run.ckpt").string();
  Sim3 sim = pile();
  sim.run(2e-3);
  io::save_checkpoint(sim, path);
  const Sim3 saved = sim;
  sim.run(2e-3);
  // the size of the next checkpoint, to fail on its very last bytes: those its close writes
  io::save_checkpoint(sim, (dir / "size.ckpt").string());
  const auto size = std::filesystem::file_size(dir / "size.ckpt");
  std::string error;
  {
    FileSizeLimit limit(size - 1);
    REQUIRE(limit.active());
    error = error_of<std::runtime_error>([&] { io::save_checkpoint(sim, path); });
  }
  CHECK(has(error, "grain::io::save_checkpoint: cannot write '" + path + ".tmp'"));
  CHECK(has(error, "'" + path + "' is left as it was"));
  CHECK_FALSE(std::filesystem::exists(path + ".tmp"));
  // the earlier checkpoint is whole: a set-up loaded from it has the state it was saved with
  Sim3 loaded = pile();
  io::load_checkpoint(loaded, path);
  CHECK(loaded.step_count() == saved.step_count());
  CHECK(loaded.time() == saved.time());
  REQUIRE(loaded.size() == saved.size());
  for (std::size_t i = 0; i < saved.size(); ++i) {
    CHECK(loaded.particles().position[i] == saved.particles().position[i]);
    CHECK(loaded.particles().velocity[i] == saved.particles().velocity[i]);
  }
  std::filesystem::remove_all(dir);
}

// ------------------------------------------------------------------ restart
TEST_CASE("writers resumed after a checkpoint leave the files of an uninterrupted run") {
  const double interval = 2e-3, end = 2e-2;
  const auto whole = scratch("grain_io_output_test/whole", Folder::empty),
             parts = scratch("grain_io_output_test/parts", Folder::empty);
  const io::VtkOptions vtk{.plane_size = 0.02, .contacts = true};
  auto files_in = [](const std::filesystem::path& dir) {
    std::set<std::string> names;
    for (const auto& e : std::filesystem::directory_iterator(dir))
      if (e.path().extension() != ".ckpt") names.insert(e.path().filename().string());
    return names;
  };

  Sim3 a = pile();
  a.run(end, io::every(interval, io::history((whole / "h.csv").string()),
                       io::vtk((whole / "bed").string(), vtk)));

  // a run that saves a checkpoint at 0.01 s, writes on past it and stops (mid-row)
  const std::string ckpt = (parts / "run.ckpt").string();
  {
    Sim3 b = pile();
    auto out = io::every(interval, io::history((parts / "h.csv").string()),
                         io::vtk((parts / "bed").string(), vtk));
    b.run(0.01, out, io::every(0.01, io::checkpoint(ckpt)));
    b.run(0.005, out);
    std::ofstream((parts / "h.csv").string(), std::ios::app) << "0.0151,15";
  }
  // restarted from the checkpoint to the same end
  Sim3 c = pile();
  io::load_checkpoint(c, ckpt);
  REQUIRE(c.time() == doctest::Approx(0.01).epsilon(1e-12));
  auto history = io::history((parts / "h.csv").string());
  history.resume = true;
  auto resumed = vtk;
  resumed.resume = true;
  c.run(end - c.time(), io::every(interval, history, io::vtk((parts / "bed").string(), resumed)));

  CHECK(c.step_count() == a.step_count());
  CHECK(file_text(parts / "h.csv") == file_text(whole / "h.csv"));
  REQUIRE(files_in(parts) == files_in(whole)); // the frames after the checkpoint are replaced
  for (const auto& name : files_in(whole)) {
    INFO(name);
    CHECK(file_text(parts / name) == file_text(whole / name));
  }
  std::filesystem::remove_all(whole);
  std::filesystem::remove_all(parts);
}

TEST_CASE("a resumed CSV writer keeps the file only if its columns are the same") {
  const auto dir = scratch("grain_io_output_test/columns", Folder::empty);
  const auto path = dir / "h.csv";
  Sim3 sim = pile();
  sim.run(1e-4, io::every(2e-5, io::history(path.string())));
  const auto rows = file_text(path);
  // resumed at a later step with other columns: an error, the file untouched
  auto other = io::history(path.string(), io::lifecycle_columns());
  other.resume = true;
  CHECK_THROWS_WITH_AS(sim.run(1e-4, io::every(2e-5, other)),
                       doctest::Contains("header = 'time [s],step,particles"), InputError);
  CHECK(file_text(path) == rows);
  // resumed at step 0 (no row before it): the file is written anew with the new columns
  Sim3 fresh = pile();
  fresh.run(1e-4, io::every(2e-5, other));
  CHECK(file_text(path).starts_with("time [s],step,particles,contacts_pp,contacts_pw,"
                                    "kinetic_energy [J],potential_energy [J],elastic_energy "
                                    "[J],active,inactive,removed\n"));
  std::filesystem::remove_all(dir);
}

TEST_CASE("a resumed VTK writer numbers on only after a frame number it can continue") {
  const auto dir = scratch("grain_io_output_test/series", Folder::empty);
  const std::string prefix = (dir / "bed").string();
  Sim3 sim = pile();
  sim.initialize();
  auto next_after = [&](const std::string& name) {
    std::ofstream(prefix + "_particles.vtk.series")
        << "{ \"files\" : [ { \"name\" : \"" << name << "\", \"time\" : -1 } ] }\n";
    auto writer = io::vtk(prefix, {.resume = true});
    writer.start(sim);
    return writer.count;
  };
  CHECK(next_after("bed_particles_000041.vtk") == 42);
  // the largest int has no next number, a negative one is not a frame, another stem not ours:
  // the frames are counted instead
  CHECK(next_after("bed_particles_2147483647.vtk") == 1);
  CHECK(next_after("bed_particles_-5.vtk") == 1);
  CHECK(next_after("other_particles_000041.vtk") == 1);
  std::filesystem::remove_all(dir);
}
