// What a first grain program needs: parameter structs with tables that default-construct (and
// reject a table that was never given).
#include "../approx.hpp"
#include "../errors.hpp"
#include <grain/bodies/rigid_body.hpp>
#include <grain/bodies/spring.hpp>
#include <grain/bodies/system.hpp>
#include <grain/bodies/torsion_spring.hpp>
#include <grain/bodies/unspring.hpp>
#include <grain/grain.hpp>

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <numbers>
#include <type_traits>
#include <vector>

namespace gb = grain::bodies;
using grain::Table;
using grain::Vec3;
using grain::test::approx;
using grain::test::error_of;
using grain::test::has;

namespace {

/// The message every owner gives for the empty table: "<object>: <name> = Table (no points) is
/// invalid; valid range: a Table of at least 2 points (...)".
std::string not_given(const std::string& object, const std::string& name) {
  return object + ": " + name +
         " = Table (no points) is invalid; valid range: a Table of at least 2 points";
}

} // namespace

// ------------------------------------------------------------------ tables not yet given

// every parameter struct with a Table member (grep "Table" in include/grain)
static_assert(std::is_default_constructible_v<Table>);
static_assert(std::is_default_constructible_v<gb::SpringParams>);
static_assert(std::is_default_constructible_v<gb::TorsionLaw>);
static_assert(std::is_default_constructible_v<gb::TorsionSpringParams>);
static_assert(std::is_default_constructible_v<gb::UnspringRule>);
static_assert(std::is_default_constructible_v<grain::VariableProperty>);

TEST_CASE("first program: a default-constructed spring takes its table later and works") {
  gb::SpringParams sp; // compiles: the table is empty until given
  sp.spring = Table({-1.0, 1.0}, {-100.0, 100.0});
  sp.geometry = gb::SpringGeometry::constant_direction;
  sp.direction = Vec3::UnitX();
  gb::SpringState st = gb::init_spring(sp, gb::SpringKinematics{});
  gb::SpringKinematics k;
  k.p2 = Vec3(0.01, 0.0, 0.0);
  const gb::SpringResult r = gb::evaluate(sp, st, k, 0.0, 1e-3, 1.0);
  CHECK(r.elastic == approx(1.0).epsilon(1e-14)); // 100 N/m x 0.01 m
}

TEST_CASE("first program: the empty table is NaN and a given table is unchanged") {
  const Table empty;
  CHECK(empty.empty());
  CHECK(empty.size() == 0);
  CHECK(std::isnan(empty(0.0)));
  std::size_t hint = 0;
  CHECK(std::isnan(empty(0.0, hint)));
  CHECK(std::isnan(empty.x_front()));
  CHECK(std::isnan(empty.x_back()));

  // a table assigned over the placeholder interpolates and holds its end values as before
  Table t;
  t = Table({0.0, 1.0, 2.0}, {20.0, 80.0, 80.0}, "ramp");
  CHECK_FALSE(t.empty());
  CHECK(t(0.5) == approx(50.0).epsilon(1e-15));
  CHECK(t(-1.0) == 20.0);
  CHECK(t(3.0) == 80.0);
  CHECK(t.label() == "Table 'ramp'");
  // a table made from points is still validated when it is made
  CHECK(has(error_of([] { Table(std::vector<double>{0.0}, std::vector<double>{1.0}); }),
            "Table: number of points = 1 is invalid; valid range: [2, inf)"));
}

TEST_CASE("first program: every object that takes a table rejects one that was never given") {
  gb::SpringParams sp;
  CHECK(has(error_of([&] { gb::validate(sp); }),
            not_given("SPRING", "spring") + " (the force-stroke table f(s) must be given)"));
  CHECK(has(error_of([&] { gb::init_spring(sp, gb::SpringKinematics{}); }),
            not_given("SPRING", "spring")));
  gb::BodySystem sys;
  sys.add_body(gb::RigidBody{});
  CHECK(has(error_of([&] { sys.add_spring(sp, 0, Vec3::Zero(), gb::world, Vec3::UnitX()); }),
            not_given("SPRING 0", "spring")));

  sp.spring = Table({-1.0, 1.0}, {-1.0, 1.0});
  sp.dashpot = Table{};
  CHECK(has(error_of([&] { gb::validate(sp); }), not_given("SPRING", "dashpot")));
  sp.dashpot.reset();
  sp.unload = Table{};
  CHECK(has(error_of([&] { gb::validate(sp); }), not_given("SPRING", "unload")));

  gb::TorsionSpringParams tp;
  tp.pitch.spring = Table{};
  CHECK(has(error_of([&] { gb::validate(tp); }), not_given("TORSION_SPRING", "pitch.spring")));
  tp.pitch.spring.reset();
  tp.yaw.dashpot = Table{};
  CHECK(has(error_of([&] { gb::validate(tp); }), not_given("TORSION_SPRING", "yaw.dashpot")));

  gb::UnspringRule rule{.tsprings = {0}, .msprings = {0}, .max = 1.0, .unload = {{0, Table{}}}};
  CHECK(has(error_of([&] { gb::Unspring u(std::move(rule), 1); }),
            not_given("UNSPRING", "unload[0]")));

  CHECK(has(error_of([] { grain::TimeFunction::table(Table{}); }),
            not_given("TimeFunction::table", "table")));

  grain::VariableProperty vp;
  vp.table = std::make_shared<const Table>();
  CHECK(has(error_of([&] { vp.validate(); }), "table = Table (no points) is invalid"));
}
