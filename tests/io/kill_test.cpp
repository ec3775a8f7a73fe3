// No lost data: the files of a writing run are readable whatever moment the run stops at.
//
// A run of 300 disks settling in a box writes, every few steps, legacy VTK frames of its
// particles, walls and contacts (ASCII and binary) with their .vtk.series files, a CSV history,
// an io::print log and a checkpoint. The run is a child process: this program starts it again
// and again (fork, then exec of itself in the child's role) in one folder, each time resuming
// from the checkpoint the previous one left, and kills it with SIGKILL after a random delay
// (seeded: the same delays every time). After each kill it checks every file left in the folder
// (also in a separate process, which loads the checkpoint into a fresh simulation):
//
// - each legacy VTK file is whole: its header, then sections whose counts match the data that
//   follows up to the end of the file, and every array of its kind present;
// - each .vtk.series file is whole and names only existing files, with increasing times;
// - the checkpoint loads with io::load_checkpoint;
// - each line of the CSV history has the header's number of cells, its steps increase, and the
//   file (and the print log) ends with a line break.
//
// Usage:
//   grain_io_kill kill [KILLS]   the kill test (default 40 kills)
//   grain_io_kill full_disk      a full disk, simulated with a file size limit (RLIMIT_FSIZE):
//                                the run stops with io::WriteError naming the file that did not
//                                fit, and what it left is readable (the checks above)
// Internal roles: `run DIR [LIMIT]` (the writing run), `check DIR` (the checks).
// Exit status 0 when every check passes, 1 otherwise.

#include <grain/grain.hpp>

#include <signal.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <random>
#include <set>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

namespace fs = std::filesystem;

namespace {

// ------------------------------------------------------------------ the writing run

using Contact =
    grain::Interaction<grain::normal::LinearSpringDashpot, grain::tangent::SpringDashpotSlider>;
using Sim = grain::Simulation<grain::Disk, grain::search::CellList, Contact>;

constexpr long kSteps = 2000; // steps of a whole run
constexpr long kEvery = 20;   // output interval [steps]

/// 300 disks on a 20 x 15 lattice in a box of 4 segments, falling under gravity.
Sim make_simulation() {
  Sim::Params params;
  params.time_step = 2e-6;
  params.gravity = grain::Vec2(0.0, -9.81);
  Sim sim(params, grain::Disk{0.001, false});
  const auto m = sim.add_material({.name = "glass",
                                   .density = 2500,
                                   .young = 1e7,
                                   .poisson = 0.3,
                                   .restitution = 0.5,
                                   .friction = 0.4});
  const double r = 0.5e-3, a = 2.1 * r;
  for (int j = 0; j < 15; ++j)
    for (int i = 0; i < 20; ++i)
      sim.add_particle(
          {.position = {(i + 0.6) * a, (j + 0.6) * a},
           .radius = r,
           .material = m,
           .velocity = {0.05 * std::sin(1.7 * (i + 20 * j)), 0.05 * std::cos(2.3 * (i + 20 * j))}});
  const double w = 20.5 * a, h = 30 * a;
  sim.add_wall(grain::walls::Segment{{0, 0}, {w, 0}}, {.name = "floor", .material = m});
  sim.add_wall(grain::walls::Segment{{0, 0}, {0, h}}, {.name = "left", .material = m});
  sim.add_wall(grain::walls::Segment{{w, 0}, {w, h}}, {.name = "right", .material = m});
  sim.add_wall(grain::walls::Segment{{0, h}, {w, h}}, {.name = "top", .material = m});
  return sim;
}

/// The child's role: runs to step kSteps in `dir`, from the checkpoint if there is one: a CSV
/// history row every step; VTK frames, a print line and a checkpoint every kEvery steps. With a
/// file size limit (bytes > 0) it expects a write to fail: exit 0 if it did with io::WriteError
/// naming a file of `dir` whose name ends with `failing` and the reason, 3 if the run ended, 4
/// for another error, 5 if the message or the file is not the one expected.
int run(const std::string& dir, long limit, const std::string& failing) {
  if (limit > 0) {
    signal(SIGXFSZ, SIG_IGN);
    rlimit r{};
    r.rlim_cur = r.rlim_max = static_cast<rlim_t>(limit);
    if (setrlimit(RLIMIT_FSIZE, &r) != 0) return 6;
  }
  const std::string ckpt = dir + "/run.ckpt";
  try {
    Sim sim = make_simulation();
    const bool resume = fs::exists(ckpt);
    if (resume) grain::io::load_checkpoint(sim, ckpt);
    auto history = grain::io::history(dir + "/history.csv", grain::io::lifecycle_columns(),
                                      grain::io::contact_force_columns());
    history.resume = resume;
    sim.steps(kSteps - sim.step_count(), grain::io::every_steps(1, history),
              grain::io::every_steps(
                  kEvery,
                  grain::io::vtk(dir + "/bed", {.plane_size = 0.01,
                                                .contacts = true,
                                                .format = grain::io::VtkFormat::ascii,
                                                .resume = resume}),
                  grain::io::vtk(dir + "/bin",
                                 {.contacts = true,
                                  .fields = grain::io::fields::velocity | grain::io::fields::id,
                                  .format = grain::io::VtkFormat::binary,
                                  .resume = resume}),
                  grain::io::print(dir + "/log.txt", grain::io::lifecycle_columns()),
                  grain::io::checkpoint(ckpt)));
  } catch (const grain::io::WriteError& e) {
    std::printf("%s\n", e.path().c_str());
    std::fprintf(stderr, "run: %s\n", e.what());
    if (limit <= 0) return 4;
    const std::string what = e.what();
    const bool named =
        what.find("'" + e.path() + "'") != std::string::npos && e.path().rfind(dir + "/", 0) == 0 &&
        e.error_number() == EFBIG && what.find(std::strerror(EFBIG)) != std::string::npos &&
        e.path().size() >= failing.size() &&
        e.path().compare(e.path().size() - failing.size(), failing.size(), failing) == 0;
    return named ? 0 : 5;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "run: unexpected error: %s\n", e.what());
    return 4;
  }
  return limit > 0 ? 3 : 0;
}

// ------------------------------------------------------------------ the checks

std::string read_all(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

/// Reads a legacy VTK polydata file as io::vtk writes it. Throws a message on anything missing.
class VtkReader {
public:
  explicit VtkReader(std::string text) : s_(std::move(text)) {}

  /// The names of the arrays of the POINT_DATA or CELL_DATA section (empty if there is none).
  std::vector<std::string> read() {
    expect_line("# vtk DataFile Version 3.0");
    const std::string title = line();
    if (title.rfind("grain ", 0) != 0) fail("title '" + title + "'");
    const std::string format = line();
    if (format != "ASCII" && format != "BINARY") fail("format '" + format + "'");
    binary_ = format == "BINARY";
    expect_line("DATASET POLYDATA");
    std::vector<std::string> arrays;
    std::size_t points = 0, count = 0; // the number of tuples of the data section
    while (at_ < s_.size()) {
      std::istringstream w(line());
      std::string key;
      w >> key;
      if (key == "POINTS") {
        std::string type;
        w >> points >> type;
        numbers(3 * points, 8, type == "double");
      } else if (key == "VERTICES" || key == "LINES" || key == "POLYGONS") {
        std::size_t cells = 0, size = 0;
        w >> cells >> size;
        if (!w) fail(key + " counts");
        numbers(size, 4, false);
      } else if (key == "POINT_DATA" || key == "CELL_DATA") {
        w >> count;
        if (!w || (key == "POINT_DATA" && count != points)) fail(key + " count");
      } else if (key == "SCALARS" || key == "VECTORS") {
        std::string name, type;
        std::size_t comps = 3;
        w >> name >> type;
        if (key == "SCALARS") {
          w >> comps;
          expect_line("LOOKUP_TABLE default");
        }
        if (!w || count == 0) fail("array " + name);
        numbers(count * comps, type == "double" || type == "vtktypeint64" ? 8 : 4,
                type == "double");
        arrays.push_back(name);
      } else {
        fail("keyword '" + key + "'");
      }
    }
    return arrays;
  }

private:
  [[noreturn]] void fail(const std::string& what) const {
    throw std::runtime_error(what + " is missing or wrong (at byte " + std::to_string(at_) +
                             " of " + std::to_string(s_.size()) + ")");
  }
  std::string line() {
    const std::size_t end = s_.find('\n', at_);
    if (end == std::string::npos) fail("a line break");
    std::string l = s_.substr(at_, end - at_);
    at_ = end + 1;
    return l;
  }
  void expect_line(const std::string& l) {
    if (line() != l) fail("line '" + l + "'");
  }
  /// n numbers: binary, n values of `bytes` bytes and a line break; ASCII, n numbers on whole
  /// lines (doubles parsed as such, integers as integers).
  void numbers(std::size_t n, std::size_t bytes, bool real) {
    if (binary_) {
      if (at_ + n * bytes + 1 > s_.size() || s_[at_ + n * bytes] != '\n') fail("binary block");
      at_ += n * bytes + 1;
      return;
    }
    std::size_t got = 0;
    while (got < n) {
      std::istringstream w(line());
      w.imbue(std::locale::classic());
      std::string token;
      while (w >> token) {
        char* end = nullptr;
        if (real)
          (void)std::strtod(token.c_str(), &end);
        else
          (void)std::strtoll(token.c_str(), &end, 10);
        if (end != token.c_str() + token.size()) fail("number '" + token + "'");
        ++got;
      }
    }
    if (got != n) fail(std::to_string(n) + " numbers");
  }

  std::string s_;
  std::size_t at_ = 0;
  bool binary_ = false;
};

/// The arrays each kind of file must have.
const std::map<std::string, std::vector<std::string>> kArrays = {
    {"bed_particles",
     {"id", "radius", "velocity", "omega", "force", "torque", "mass", "orientation", "material"}},
    {"bin_particles", {"id", "velocity"}},
    {"bed_walls", {"wall", "present"}},
    {"bin_walls", {"wall", "present"}},
    {"bed_contacts",
     {"wall", "id_i", "id_j", "normal_force", "normal_viscous", "tangential_force", "normal",
      "force_local", "overlap", "contact_radius"}},
};
/// The arrays of a file of kind `kind` ("bin_contacts" as "bed_contacts"); none if unknown.
const std::vector<std::string>* arrays_of(const std::string& kind) {
  const auto it = kArrays.find(kind == "bin_contacts" ? "bed_contacts" : kind);
  return it == kArrays.end() ? nullptr : &it->second;
}

/// The files named by a series file as io::vtk writes it, with their times; throws if the file
/// is not whole.
std::vector<std::pair<std::string, double>> series_entries(const std::string& text) {
  const std::string head = "{\n  \"file-series-version\" : \"1.0\",\n  \"files\" : [\n";
  const std::string tail = "  ]\n}\n";
  if (text.rfind(head, 0) != 0) throw std::runtime_error("series head is missing");
  if (text.size() < head.size() + tail.size() ||
      text.compare(text.size() - tail.size(), tail.size(), tail) != 0)
    throw std::runtime_error("series end is missing");
  std::vector<std::pair<std::string, double>> entries;
  std::istringstream lines(text.substr(head.size(), text.size() - head.size() - tail.size()));
  for (std::string l; std::getline(lines, l);) {
    const std::string a = "    { \"name\" : \"", b = "\", \"time\" : ";
    const std::size_t nb = l.find(b);
    if (l.rfind(a, 0) != 0 || nb == std::string::npos)
      throw std::runtime_error("series entry '" + l + "'");
    char* end = nullptr;
    const double t = std::strtod(l.c_str() + nb + b.size(), &end);
    if (std::string(end) != " }," && std::string(end) != " }")
      throw std::runtime_error("series entry '" + l + "'");
    entries.emplace_back(l.substr(a.size(), nb - a.size()), t);
  }
  return entries;
}

/// Splits a CSV line (no quoted cells with commas in this test's files).
std::vector<std::string> cells(const std::string& l) {
  std::vector<std::string> out;
  std::size_t a = 0;
  for (std::size_t b; (b = l.find(',', a)) != std::string::npos; a = b + 1)
    out.push_back(l.substr(a, b - a));
  out.push_back(l.substr(a));
  return out;
}

/// Every check of the folder; returns the number of failures (each printed).
int check(const std::string& dir) {
  int failures = 0;
  auto problem = [&](const fs::path& file, const std::string& what) {
    std::fprintf(stderr, "check: %s: %s\n", file.filename().c_str(), what.c_str());
    ++failures;
  };
  std::size_t vtk_files = 0;
  for (const auto& e : fs::directory_iterator(dir)) {
    const fs::path p = e.path();
    const std::string name = p.filename().string();
    if (p.extension() == ".vtk") {
      ++vtk_files;
      const std::string kind = name.substr(0, name.rfind('_'));
      try {
        const auto arrays = VtkReader(read_all(p)).read();
        const auto* want = arrays_of(kind);
        const bool contacts = kind.find("contacts") != std::string::npos;
        if (!want)
          problem(p, "an unknown kind of file");
        else if (arrays != *want && !(contacts && arrays.empty())) // no contact, no cell data
          problem(p, "arrays missing");
      } catch (const std::exception& x) {
        problem(p, x.what());
      }
    } else if (name.size() > 11 && name.compare(name.size() - 11, 11, ".vtk.series") == 0) {
      try {
        double last = -1.0;
        for (const auto& [file, time] : series_entries(read_all(p))) {
          if (!fs::exists(fs::path(dir) / file)) problem(p, "names a missing file " + file);
          if (!(time > last)) problem(p, "times do not increase at " + file);
          last = time;
        }
      } catch (const std::exception& x) {
        problem(p, x.what());
      }
    } else if (name == "history.csv") {
      const std::string text = read_all(p);
      if (!text.empty() && text.back() != '\n') problem(p, "ends inside a line");
      std::istringstream lines(text);
      std::string header;
      std::getline(lines, header);
      const std::size_t width = cells(header).size();
      long last = -1;
      for (std::string l; std::getline(lines, l);) {
        const auto c = cells(l);
        if (c.size() != width) {
          problem(p, "a line of " + std::to_string(c.size()) + " cells for " +
                         std::to_string(width) + ": '" + l + "'");
          break;
        }
        const long step = std::strtol(c[1].c_str(), nullptr, 10);
        if (step <= last)
          problem(p, "step " + std::to_string(step) + " after " + std::to_string(last));
        last = step;
      }
    } else if (name == "log.txt") {
      const std::string text = read_all(p);
      if (!text.empty() && text.back() != '\n') problem(p, "ends inside a line");
    } else if (name == "run.ckpt") {
      try {
        Sim fresh = make_simulation();
        grain::io::load_checkpoint(fresh, p.string());
        if (fresh.step_count() % kEvery != 0 && fresh.step_count() != kSteps)
          problem(p, "step " + std::to_string(fresh.step_count()));
      } catch (const std::exception& x) {
        problem(p, x.what());
      }
    } else if (p.extension() != ".tmp" && name != ".grain_write_test") {
      // a killed write leaves its temporary file, a killed start the probe of the folder check
      problem(p, "an unexpected file");
    }
  }
  std::printf("checked %zu VTK files\n", vtk_files);
  return failures;
}

// ------------------------------------------------------------------ the parent

std::string self_path;

/// Starts this program in a role; returns its pid.
pid_t start(const std::vector<std::string>& args) {
  std::fflush(nullptr);
  const pid_t pid = fork();
  if (pid == 0) {
    std::vector<char*> argv{const_cast<char*>(self_path.c_str())};
    for (const auto& a : args)
      argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    execv(self_path.c_str(), argv.data());
    std::_Exit(127);
  }
  return pid;
}

/// How a child ended: its exit status, or 128 + the signal that ended it.
int wait_for(pid_t pid) {
  int status = 0;
  while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

int check_in_child(const std::string& dir) { return wait_for(start({"check", dir})); }

fs::path fresh_folder(const std::string& name) {
  const fs::path dir =
      fs::temp_directory_path() / ("grain_io_kill_" + std::to_string(getpid())) / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

int kill_test(int kills) {
  // the time of a whole run, to spread the kills over it
  const fs::path whole = fresh_folder("whole");
  const auto t0 = std::chrono::steady_clock::now();
  if (wait_for(start({"run", whole.string()})) != 0 || check_in_child(whole.string()) != 0) {
    std::fprintf(stderr, "kill: the uninterrupted run or its files failed\n");
    return 1;
  }
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::printf("kill: an uninterrupted run takes %.2f s\n", seconds);
  std::mt19937 rng(20261128);
  std::uniform_real_distribution<double> delay(0.0, 0.6 * seconds);
  fs::path dir = fresh_folder("killed_0");
  int failed = 0, finished = 0, rounds = 0;
  for (int k = 0; k < kills; ++k) {
    const double d = delay(rng);
    const pid_t pid = start({"run", dir.string()});
    std::this_thread::sleep_for(std::chrono::duration<double>(d));
    kill(pid, SIGKILL);
    const int status = wait_for(pid);
    const int bad = check_in_child(dir.string());
    std::printf("kill %2d after %.3f s: %s; check %s\n", k, d,
                status == 128 + SIGKILL ? "killed" : "the run had ended",
                bad == 0 ? "passed" : "FAILED");
    if (bad != 0) ++failed;
    if (status != 128 + SIGKILL) { // the run reached its end: a new one in a new folder
      if (status != 0) ++failed;
      ++finished;
      dir = fresh_folder("killed_" + std::to_string(++rounds));
    }
  }
  std::printf("kill: %d kills, %d runs reached their end, %d checks failed\n", kills, finished,
              failed);
  if (failed == 0) fs::remove_all(whole.parent_path());
  return failed == 0 ? 0 : 1;
}

int full_disk_test() {
  // limits under which the files of the first outputs fit and then one write does not: the
  // largest ASCII particle frame is about 71 kB, the checkpoint 60 kB, the whole history 290 kB
  struct Case {
    long limit;
    const char* failing; // the end of the name of the file expected to fail
  };
  int failed = 0;
  for (const Case c : {Case{30000, ".vtk"}, Case{62000, ".vtk"}, Case{100000, "history.csv"}}) {
    const long limit = c.limit;
    const fs::path dir = fresh_folder("full_" + std::to_string(limit));
    const int status = wait_for(start({"run", dir.string(), std::to_string(limit), c.failing}));
    const int bad = check_in_child(dir.string());
    std::printf("full disk at %ld bytes a file: run %s; check %s\n", limit,
                status == 0   ? "stopped by io::WriteError naming the file"
                : status == 3 ? "FAILED: ended without an error"
                              : "FAILED: other error",
                bad == 0 ? "passed" : "FAILED");
    failed += (status != 0) + (bad != 0);
  }
  if (failed == 0)
    fs::remove_all(fs::temp_directory_path() / ("grain_io_kill_" + std::to_string(getpid())));
  return failed == 0 ? 0 : 1;
}

} // namespace

int main(int argc, char** argv) {
  std::error_code ec;
  self_path = fs::read_symlink("/proc/self/exe", ec).string();
  if (ec) self_path = argv[0];
  const std::string role = argc > 1 ? argv[1] : "";
  if (role == "run" && argc >= 3)
    return run(argv[2], argc > 3 ? std::atol(argv[3]) : 0, argc > 4 ? argv[4] : "");
  if (role == "check" && argc == 3) return check(argv[2]) == 0 ? 0 : 1;
  if (role == "kill") return kill_test(argc > 2 ? std::atoi(argv[2]) : 40);
  if (role == "full_disk") return full_disk_test();
  std::fprintf(stderr, "usage: grain_io_kill kill [KILLS] | full_disk\n");
  return 2;
}
