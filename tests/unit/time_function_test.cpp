// Tables and time functions: closed-form values, end values, construction, input validation.
#include "../approx.hpp"
#include "../errors.hpp"
#include <chrono>
#include <cmath>
#include <cstddef>
#include <doctest/doctest.h>
#include <filesystem>
#include <fstream>
#include <grain/core/table.hpp>
#include <grain/core/time_function.hpp>
#include <limits>
#include <memory>
#include <numbers>
#include <random>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

using namespace grain;

namespace {
using grain::test::error_of;
using grain::test::has;

constexpr double inf = std::numeric_limits<double>::infinity();
constexpr double qnan = std::numeric_limits<double>::quiet_NaN();
constexpr double pi = std::numbers::pi;

/// A file in the temporary directory with a unique name, removed when it goes out of scope.
struct TempFile {
  std::filesystem::path path;
  explicit TempFile(const std::string& text) {
    static std::mt19937_64 rng(
        std::random_device{}() ^
        static_cast<std::uint64_t>(std::chrono::steady_clock::now().time_since_epoch().count()));
    static int counter = 0;
    path = std::filesystem::temp_directory_path() /
           ("grain_table_" + std::to_string(rng()) + "_" + std::to_string(++counter) + ".txt");
    std::ofstream(path, std::ios::binary) << text;
  }
  ~TempFile() {
    std::error_code ec;
    std::filesystem::remove(path, ec);
  }
  TempFile(const TempFile&) = delete;
  TempFile& operator=(const TempFile&) = delete;
  std::string name() const { return path.string(); }
};

/// The error of reading `text` as a table file; checks that it names the file.
std::string file_error(const std::string& text) {
  const TempFile f(text);
  const auto e = error_of([&] { (void)Table::from_file(f.path); });
  CHECK(has(e, "Table from file '" + f.name() + "'"));
  return e;
}
} // namespace

TEST_CASE("time function: constant") {
  const auto f = TimeFunction::constant(2.5);
  CHECK(f.kind() == TimeFunction::Kind::constant);
  for (double t : {-1e9, -1.0, 0.0, 0.3, 1e9}) {
    CHECK(f(t) == 2.5);
    CHECK(f.value(t) == 2.5);
    CHECK(f.active(t));
  }
  CHECK_FALSE(f.has_interval());
  const TimeFunction g = 9.81; // a plain number converts to a constant
  CHECK(g.kind() == TimeFunction::Kind::constant);
  CHECK(g(123.0) == 9.81);
  const TimeFunction zero;
  CHECK(zero(1.0) == 0.0);
  CHECK(zero.active(1.0));
}

TEST_CASE("time function: linear ramp with its time origin") {
  const double v0 = 1.5, slope = -0.4, t0 = 2.0;
  const auto f = TimeFunction::linear(v0, slope, t0);
  CHECK(f.kind() == TimeFunction::Kind::linear);
  CHECK(f(t0) == v0);
  CHECK(f(t0 + 2.5) == grain::test::approx(v0 + slope * 2.5).epsilon(1e-15));
  CHECK(f(0.0) == grain::test::approx(v0 - slope * t0).epsilon(1e-15)); // defined before t0 too
  CHECK(f(12.0) == grain::test::approx(1.5 - 0.4 * 10.0).epsilon(1e-15));
  const auto g = TimeFunction::linear(3.0, 2.0); // t0 = 0 by default
  CHECK(g(0.0) == 3.0);
  CHECK(g(0.25) == grain::test::approx(3.5).epsilon(1e-15));
  CHECK(g(-1.0) == grain::test::approx(1.0).epsilon(1e-15));
}

TEST_CASE("time function: oscillatory with phase and time origin") {
  const double base = 0.5, amp = 0.2, period = 0.1, phase = 0.3, t0 = 1.0;
  const auto f = TimeFunction::oscillatory(base, amp, period, phase, t0);
  CHECK(f.kind() == TimeFunction::Kind::oscillatory);
  for (double t : {0.0, 0.97, 1.0, 1.013, 1.05, 1.1, 2.345, 10.0}) {
    const double expected = base + amp * std::sin(2.0 * pi * (t - t0) / period + phase);
    CHECK(f(t) == grain::test::approx(expected).epsilon(1e-12));
  }
  // at t0 the value is base + amp sin(phase); periodic in the period
  CHECK(f(t0) == grain::test::approx(base + amp * std::sin(phase)).epsilon(1e-14));
  CHECK(f(t0 + 3 * period) == grain::test::approx(f(t0)).epsilon(1e-12));

  // phase 0, t0 0: quarter periods give base, base + amp, base, base - amp
  const auto g = TimeFunction::oscillatory(1.0, 2.0, 4.0);
  CHECK(g(0.0) == grain::test::approx(1.0).epsilon(1e-15));
  CHECK(g(1.0) == grain::test::approx(3.0).epsilon(1e-15));
  CHECK(g(2.0) == grain::test::approx(1.0).epsilon(1e-15));
  CHECK(g(3.0) == grain::test::approx(-1.0).epsilon(1e-15));
  // the phase shifts the wave: a phase of pi/2 starts at the crest, at t0
  const auto h = TimeFunction::oscillatory(0.0, 1.0, 4.0, pi / 2, 0.5);
  CHECK(h(0.5) == grain::test::approx(1.0).epsilon(1e-15));
  CHECK(h(1.5) == grain::test::approx(0.0).scale(1.0).epsilon(1e-14));
  CHECK(h(2.5) == grain::test::approx(-1.0).epsilon(1e-15));
  // a negative amplitude flips the sign
  const auto n = TimeFunction::oscillatory(0.0, -1.0, 4.0);
  CHECK(n(1.0) == grain::test::approx(-1.0).epsilon(1e-15));
}

TEST_CASE("time function: activity interval is closed, zero while inactive, no time shift") {
  const auto f = TimeFunction::linear(1.0, 2.0).active(0.5, 1.5);
  CHECK(f.has_interval());
  CHECK(f.t_begin() == 0.5);
  CHECK(f.t_end() == 1.5);
  CHECK(f.kind() == TimeFunction::Kind::linear);
  // boundaries belong to the interval
  CHECK(f.active(0.5));
  CHECK(f.active(1.5));
  CHECK(f(0.5) == grain::test::approx(2.0).epsilon(1e-15)); // 1 + 2 * 0.5: t0 stays 0
  CHECK(f(1.5) == grain::test::approx(4.0).epsilon(1e-15));
  CHECK(f(1.0) == grain::test::approx(3.0).epsilon(1e-15));
  // just outside: inactive, value 0; value() ignores the interval
  const double before = std::nextafter(0.5, 0.0), after = std::nextafter(1.5, 2.0);
  CHECK_FALSE(f.active(before));
  CHECK_FALSE(f.active(after));
  CHECK(f(before) == 0.0);
  CHECK(f(after) == 0.0);
  CHECK(f(-10.0) == 0.0);
  CHECK(f(10.0) == 0.0);
  CHECK(f.value(10.0) == grain::test::approx(21.0).epsilon(1e-15));
  CHECK_FALSE(f.active(qnan));
  CHECK(f(qnan) == 0.0);

  // the activity of an oscillation and of a table, infinite ends, a single instant
  const auto o = TimeFunction::oscillatory(1.0, 1.0, 1.0).active(2.0, inf);
  CHECK_FALSE(o.active(1.999));
  CHECK(o(1.999) == 0.0);
  CHECK(o(2.25) == grain::test::approx(2.0).epsilon(1e-12));
  CHECK(o.active(1e300));
  const auto tab = TimeFunction::table(Table({{0.0, 1.0}, {1.0, 3.0}})).active(-inf, 0.5);
  CHECK(tab(-5.0) == 1.0);
  CHECK(tab(0.5) == grain::test::approx(2.0).epsilon(1e-15));
  CHECK(tab(0.75) == 0.0);
  const auto instant = TimeFunction::constant(7.0).active(1.0, 1.0);
  CHECK(instant(1.0) == 7.0);
  CHECK(instant(std::nextafter(1.0, 2.0)) == 0.0);
  // a later interval replaces the earlier one; the original is unchanged
  const auto g = f.active(0.0, 0.25);
  CHECK(g(1.0) == 0.0);
  CHECK(f(1.0) == grain::test::approx(3.0).epsilon(1e-15));
  CHECK(has(g.describe(), "active in [0, 0.25]"));
}

TEST_CASE("time function: a callable is the user's function, with the activity interval") {
  int calls = 0;
  const auto f = TimeFunction::callable([&calls](double t) {
    ++calls;
    return 2.0 * t * t;
  });
  CHECK(f.kind() == TimeFunction::Kind::callable);
  CHECK(f(1.5) == 4.5);
  CHECK(f.value(-1.0) == 2.0);
  CHECK(calls == 2);
  const auto g = f.active(0.0, 1.0);
  CHECK(g(2.0) == 0.0); // inactive: not called
  CHECK(calls == 2);
  CHECK(has(g.describe(), {"a function of time", "active in [0, 1]"}));
  // an exception of the user's function reaches the caller
  const auto bad = TimeFunction::callable([](double) -> double { throw std::runtime_error("no"); });
  CHECK_THROWS_AS((void)bad(0.0), std::runtime_error);
  // a vector callable is called once per time for all its components
  int vcalls = 0;
  const auto v = VectorTimeFunction<3>::callable([&vcalls](double t) {
    ++vcalls;
    return Vec3(t, 2.0 * t, 3.0 * t);
  });
  CHECK(v(2.0) == Vec3(2.0, 4.0, 6.0));
  CHECK(v.value(2.0) == Vec3(2.0, 4.0, 6.0));
  CHECK(vcalls == 1);
  CHECK(v.component(1)(3.0) == 6.0);
  CHECK(vcalls == 2);
  CHECK(has(error_of([] { (void)VectorTimeFunction<3>::callable({}); }), {"callable", "empty"}));
}

TEST_CASE("table: interpolation at and between points, end values held outside") {
  const Table t({0.0, 1.0, 3.0, 4.0}, {10.0, 20.0, 0.0, 5.0}, "profile");
  CHECK(t.size() == 4);
  CHECK(t.x_front() == 0.0);
  CHECK(t.x_back() == 4.0);
  CHECK(t.label() == "Table 'profile'");
  // exact at the points
  CHECK(t(0.0) == 10.0);
  CHECK(t(1.0) == 20.0);
  CHECK(t(3.0) == 0.0);
  CHECK(t(4.0) == 5.0);
  // linear in between
  CHECK(t(0.25) == grain::test::approx(12.5).epsilon(1e-15));
  CHECK(t(2.0) == grain::test::approx(10.0).epsilon(1e-15));
  CHECK(t(2.5) == grain::test::approx(5.0).epsilon(1e-15));
  CHECK(t(3.5) == grain::test::approx(2.5).epsilon(1e-15));
  // end values outside, never NaN, even far away and at infinity
  for (double x : {-1e-12, -1.0, -1e300, -inf})
    CHECK(t(x) == 10.0);
  for (double x : {4.0 + 1e-12, 5.0, 1e300, inf})
    CHECK(t(x) == 5.0);
  // segment lookup
  CHECK(t.segment(-1.0) == 0);
  CHECK(t.segment(0.0) == 0);
  CHECK(t.segment(1.0) == 1);
  CHECK(t.segment(2.9) == 1);
  CHECK(t.segment(3.0) == 2);
  CHECK(t.segment(10.0) == 2);
  // a NaN argument is the only way to get NaN
  CHECK(std::isnan(t(qnan)));

  // a two-point table; no value is NaN over a sweep far past both ends
  const Table two({{-1.0, 2.0}, {1.0, 4.0}});
  CHECK(two(0.0) == grain::test::approx(3.0).epsilon(1e-15));
  for (int k = -100; k <= 100; ++k) {
    const double v = two(k * 0.1);
    CHECK_FALSE(std::isnan(v));
    CHECK(v >= 2.0);
    CHECK(v <= 4.0);
  }
}

TEST_CASE("table: the cursor gives the same values as the search, in any order") {
  std::vector<double> x, y;
  for (int i = 0; i < 50; ++i) {
    x.push_back(i * 0.1 + 0.001 * i * i);
    y.push_back(std::sin(0.3 * i));
  }
  const Table t(x, y);
  std::size_t hint = 0;
  for (int k = -20; k < 800; ++k) { // increasing, with steps that skip segments now and then
    const double xx = k * 0.0075;
    CHECK(t(xx, hint) == t(xx));
    if (xx > t.x_front() && xx < t.x_back()) CHECK(hint == t.segment(xx));
  }
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-1.0, 8.0);
  for (int k = 0; k < 500; ++k) { // random order
    const double xx = u(rng);
    CHECK(t(xx, hint) == t(xx));
  }
  hint = 12345; // any starting hint is valid
  CHECK(t(1.23, hint) == t(1.23));
  CHECK(hint == t.segment(1.23));
  hint = 48; // the last segment
  CHECK(t(0.05, hint) == t(0.05));
  CHECK(hint == 0);

  // through a time function
  const auto f = TimeFunction::table(t);
  hint = 0;
  for (int k = 0; k < 100; ++k)
    CHECK(f(k * 0.05, hint) == f(k * 0.05));
}

TEST_CASE("table: inline columns, pairs and a file give the same table") {
  const Table cols({0.0, 0.5, 2.0}, {1.0, 3.0, -1.0}, "inline");
  const Table pairs({{0.0, 1.0}, {0.5, 3.0}, {2.0, -1.0}}, "pairs");
  const std::vector<std::pair<double, double>> pv{{0.0, 1.0}, {0.5, 3.0}, {2.0, -1.0}};
  const Table from_vector(pv);
  const TempFile file("# time [s]   value\n"
                      "# second comment line\n"
                      "0 1\n"
                      "\n"
                      "   \t  \n"
                      "\t5e-1\t+3.0   # inline comment\r\n"
                      "# comment between points\n"
                      "2.0 -1 \n");
  const Table from_file = Table::from_file(file.path);
  for (const Table* t : {&pairs, &from_vector, &from_file}) {
    CHECK(t->x() == cols.x());
    CHECK(t->y() == cols.y());
  }
  CHECK(pairs.label() == "Table 'pairs'");
  CHECK(from_vector.label() == "Table");
  CHECK(from_file.label() == "Table from file '" + file.name() + "'");
  for (double x : {-1.0, 0.0, 0.2, 0.5, 1.0, 2.0, 3.0})
    CHECK(from_file(x) == cols(x));
  CHECK(from_file(0.25) == grain::test::approx(2.0).epsilon(1e-15));
  CHECK(from_file(1.25) == grain::test::approx(1.0).epsilon(1e-15));

  // a time function shares its table; copies are cheap and evaluate the same
  const auto f = TimeFunction::table(from_file);
  CHECK(f.kind() == TimeFunction::Kind::table);
  const TimeFunction copy = f;
  REQUIRE(f.table_ptr() != nullptr);
  CHECK(copy.table_ptr() == f.table_ptr());
  CHECK(copy(0.25) == f(0.25));
  CHECK(f(-100.0) == 1.0);
  CHECK(f(100.0) == -1.0);
  CHECK(TimeFunction::constant(1.0).table_ptr() == nullptr);
  const auto shared = std::make_shared<const Table>(cols);
  CHECK(TimeFunction::table(shared).table_ptr() == shared.get());
  CHECK(TimeFunction::table({{0.0, 0.0}, {1.0, 2.0}})(0.5) == grain::test::approx(1.0));
  CHECK(has(f.describe(), "3 points"));
}

TEST_CASE("table: bad inline tables name the table, the entry, the value and the range") {
  auto e = error_of([] { Table({1.0}, {2.0}, "ramp"); });
  CHECK(has(e, "Table 'ramp'"));
  CHECK(has(e, "number of points = 1"));
  CHECK(has(e, "[2, inf)"));
  e = error_of([] { Table(std::vector<double>{}, std::vector<double>{}); });
  CHECK(has(e, "Table: number of points = 0"));
  e = error_of([] { Table({{0.0, 1.0}}); });
  CHECK(has(e, "number of points = 1"));
  e = error_of([] { Table({0.0, 1.0, 2.0}, {1.0, 2.0}, "ramp"); });
  CHECK(has(e, "number of ordinates y = 2"));
  CHECK(has(e, "valid range: 3"));

  e = error_of([] { Table({0.0, 1.0, 1.0, 2.0}, {0.0, 0.0, 0.0, 0.0}, "ramp"); });
  CHECK(has(e, "Table 'ramp': x[2] = 1 is invalid"));
  CHECK(has(e, "(1, inf)"));
  CHECK(has(e, "duplicate"));
  e = error_of([] { Table({{0.0, 0.0}, {2.0, 0.0}, {1.5, 0.0}}, "ramp"); });
  CHECK(has(e, "x[2] = 1.5 is invalid"));
  CHECK(has(e, "(2, inf)"));
  CHECK(has(e, "unsorted"));
  e = error_of([] { Table({0.0, qnan}, {0.0, 0.0}, "ramp"); });
  CHECK(has(e, "x[1] = nan"));
  CHECK(has(e, "a finite number"));
  e = error_of([] { Table({0.0, 1.0}, {inf, 0.0}, "ramp"); });
  CHECK(has(e, "y[0] = inf"));
  CHECK(has(e, "a finite number"));
  e = error_of([] { Table({0.0, 1.0}, {-1.5e308, 1.5e308}, "huge"); });
  CHECK(has(e, "y[1] - y[0] = inf"));
}

TEST_CASE("table: bad files name the file and the line") {
  // a missing file and a directory
  std::filesystem::path missing;
  {
    const TempFile gone("");
    missing = gone.path; // a unique name, removed at the end of this scope
  }
  REQUIRE_FALSE(std::filesystem::exists(missing));
  auto e = error_of([&] { (void)Table::from_file(missing); });
  CHECK(has(e, "Table from file '" + missing.string() + "'"));
  CHECK(has(e, "does not exist"));
  e = error_of([] { (void)Table::from_file(std::filesystem::temp_directory_path()); });
  CHECK(has(e, "directory"));

  // malformed lines
  e = file_error("# header\n0 1\n1\n");
  CHECK(has(e, "line 3 = '1' is invalid"));
  CHECK(has(e, "only one number"));
  CHECK(has(e, "two numbers \"x y\""));
  e = file_error("0 1\n1 2 3\n");
  CHECK(has(e, "line 2 = '1 2 3'"));
  CHECK(has(e, "more than two numbers"));
  e = file_error("0 1\n\n1 abc # comment\n");
  CHECK(has(e, "line 3 = '1 abc # comment'"));
  CHECK(has(e, "'abc' is not a number"));
  e = file_error("0,0 1\n");
  CHECK(has(e, "line 1"));
  CHECK(has(e, "'0,0' is not a number"));
  e = file_error("0 1\n1 2x\n");
  CHECK(has(e, "line 2"));
  CHECK(has(e, "'2x' is not a number"));
  e = file_error("0 1\n+-1 2\n");
  CHECK(has(e, "'+-1' is not a number"));
  e = file_error("0 1\n1 1e999\n");
  CHECK(has(e, "line 2"));

  // non-finite, unsorted and duplicate abscissae
  e = file_error("0 1\n1 nan\n");
  CHECK(has(e, "y on line 2 = nan is invalid"));
  CHECK(has(e, "a finite number"));
  e = file_error("# t v\n0 1\n2 2\n\n# back in time\n1.5 3\n");
  CHECK(has(e, "x on line 6 = 1.5 is invalid"));
  CHECK(has(e, "valid range: (2, inf)"));
  CHECK(has(e, "x on line 3 = 2"));
  CHECK(has(e, "unsorted"));
  e = file_error("0 1\n1 2\n1 3\n");
  CHECK(has(e, "x on line 3 = 1 is invalid"));
  CHECK(has(e, "duplicate"));

  // fewer than two points
  e = file_error("# only a comment\n\n");
  CHECK(has(e, "number of points = 0"));
  CHECK(has(e, "no data lines"));
  e = file_error("");
  CHECK(has(e, "number of points = 0"));
  e = file_error("# one point\n\n5 1\n");
  CHECK(has(e, "number of points = 1"));
  CHECK(has(e, "line 3"));
}

TEST_CASE("time function: invalid parameters name the function, the value and the range") {
  auto e = error_of([] { (void)TimeFunction::oscillatory(0.0, 1.0, 0.0); });
  CHECK(has(e, "TimeFunction::oscillatory: period = 0 is invalid; valid range: (0, inf)"));
  e = error_of([] { (void)TimeFunction::oscillatory(0.0, 1.0, -2.0); });
  CHECK(has(e, "period = -2"));
  e = error_of([] { (void)TimeFunction::oscillatory(0.0, 1.0, inf); });
  CHECK(has(e, "period = inf"));
  e = error_of([] { (void)TimeFunction::oscillatory(0.0, qnan, 1.0); });
  CHECK(has(e, "TimeFunction::oscillatory: amplitude = nan"));
  e = error_of([] { (void)TimeFunction::oscillatory(0.0, 1.0, 1.0, inf); });
  CHECK(has(e, "phase = inf"));
  e = error_of([] { (void)TimeFunction::constant(qnan); });
  CHECK(has(e, "TimeFunction::constant: value = nan"));
  e = error_of([] {
    TimeFunction f = inf;
    (void)f;
  });
  CHECK(has(e, "TimeFunction::constant: value = inf"));
  e = error_of([] { (void)TimeFunction::linear(0.0, inf); });
  CHECK(has(e, "TimeFunction::linear: slope = inf is invalid; valid range: a finite number"));
  e = error_of([] { (void)TimeFunction::linear(0.0, 1.0, qnan); });
  CHECK(has(e, "t0 = nan"));
  e = error_of([] { (void)TimeFunction::table(std::shared_ptr<const Table>()); });
  CHECK(has(e, "TimeFunction::table: table = null"));

  e = error_of([] { (void)TimeFunction::constant(1.0).active(2.0, 1.0); });
  CHECK(has(e, "TimeFunction (constant)::active: t_end = 1 is invalid"));
  CHECK(has(e, "[2, inf]"));
  e = error_of([] { (void)TimeFunction::linear(1.0, 1.0).active(qnan, 1.0); });
  CHECK(has(e, "TimeFunction (linear)::active: t_begin = nan"));
  e = error_of([] { (void)TimeFunction::linear(1.0, 1.0).active(inf, inf); });
  CHECK(has(e, "t_begin = inf"));
  e = error_of([] { (void)TimeFunction::constant(1.0).active(0.0, qnan); });
  CHECK(has(e, "t_end = nan"));
  CHECK(error_of([] { (void)TimeFunction::constant(1.0).active(-inf, inf); }).empty());
}

TEST_CASE("vector time function: components, direction times magnitude, activity") {
  const VectorTimeFunction<3> g = Vec3(0.0, 0.0, -9.81);
  CHECK(g(0.0) == Vec3(0.0, 0.0, -9.81));
  CHECK(g(100.0) == Vec3(0.0, 0.0, -9.81));
  CHECK(g.active(5.0));
  CHECK_FALSE(g.is_along());

  const VectorTimeFunction<3> v(TimeFunction::linear(0.0, 1.0), 2.0,
                                TimeFunction::oscillatory(0.0, 1.0, 4.0).active(0.0, 2.0));
  const Vec3 a = v(1.0);
  CHECK(a.x() == grain::test::approx(1.0));
  CHECK(a.y() == 2.0);
  CHECK(a.z() == grain::test::approx(1.0));
  CHECK(v(3.0).z() == 0.0); // z inactive after t = 2
  CHECK(v.value(3.0).z() == grain::test::approx(-1.0));
  CHECK(v.active(3.0)); // the other components are

  const auto w = VectorTimeFunction<2>::along(Vec2(3.0, 4.0), TimeFunction::linear(0.0, 10.0))
                     .active(1.0, 2.0);
  CHECK(w.is_along());
  CHECK(w.direction().x() == grain::test::approx(0.6));
  CHECK(w.direction().y() == grain::test::approx(0.8));
  CHECK(w(1.5).x() == grain::test::approx(9.0));
  CHECK(w(1.5).y() == grain::test::approx(12.0));
  CHECK_FALSE(w.active(0.5));
  CHECK(w(0.5) == Vec2::Zero());
  CHECK(w.value(0.5).y() == grain::test::approx(4.0));

  const VectorTimeFunction<2> zero;
  CHECK(zero(1.0) == Vec2::Zero());
  const VectorTimeFunction<2> p(std::array<TimeFunction, 2>{1.0, TimeFunction::constant(2.0)});
  CHECK(p(0.0) == Vec2(1.0, 2.0));
  const auto off = p.active(1.0, 2.0);
  CHECK_FALSE(off.active(0.0));
  CHECK(off(0.0) == Vec2::Zero());
  CHECK(off.component(1).t_begin() == 1.0);

  auto e = error_of([] { (void)VectorTimeFunction<3>::along(Vec3::Zero(), 1.0); });
  CHECK(has(e, "VectorTimeFunction::along: |direction| = 0"));
  e = error_of([] { (void)VectorTimeFunction<2>::along(Vec2(qnan, 1.0), 1.0); });
  CHECK(has(e, "VectorTimeFunction::along"));
}
