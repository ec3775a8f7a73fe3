#pragma once
/// \file contact_records.hpp
/// Per-contact records (the first seed's ContactStartTime, ContactStartStep and ContactDuration,
/// with the contact area): `io::ContactRecorder`, an observer of a run that follows every
/// contact from the step it is first found touching to the step it is no longer found.
///
/// | field | meaning | unit |
/// |---|---|---|
/// | `id_i`, `id_j` | the particle ids (a pair: `id_i < id_j`); `id_j` = -1 for a wall | - |
/// | `wall` | the wall index; -1 for a pair | - |
/// | `start_time`, `start_step` | the first step end (or the start of the run) at which it touched | s, - |
/// | `end_time`, `end_step` | the first step end at which it no longer touched (NaN, -1 while it lasts) | s, - |
/// | `duration()` | end_time - start_time (while it lasts: up to the last step seen) = the steps in contact x dt | s |
/// | `impact_velocity` | normal approach speed when it was first found | m/s |
/// | `max_overlap`, `max_normal_force` | over the contact | m, N |
/// | `area`, `max_area` | contact area at the last step seen and its maximum: pi a^2 (3D), 2 a L (2D disks of length L), a the contact radius the area model gives | m^2 |
///
/// ```cpp
/// grain::io::ContactRecorder records("contacts.csv"); // written at the end of each run
/// sim.run(0.5, records);
/// for (const auto& c : records.finished()) std::printf("%g s\n", c.duration());
/// ```
///
/// A contact is matched from step to step by its partners' ids (and wall index), so records
/// survive re-sorting and neighbour-list rebuilds; the contacts are read after each step with
/// `Simulation::for_each_contact`, which evaluates them again (about the cost of the contact
/// pass per step). The duration is exact to one step: a contact that lasts from t_a to t_b is
/// seen at the step ends within it, so |duration - (t_b - t_a)| < dt.

#include <grain/io/atomic_file.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <numbers>
#include <ostream>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

namespace grain::io {

/// One contact's record (see the file comment).
struct ContactRecord {
  std::int64_t id_i = -1;
  std::int64_t id_j = -1;
  std::int64_t wall = -1;
  double start_time = 0.0;
  long start_step = 0;
  double end_time = std::numeric_limits<double>::quiet_NaN();
  long end_step = -1;
  double last_time = 0.0; ///< the last step end at which it touched [s]
  double impact_velocity = 0.0;
  double max_overlap = 0.0;
  double max_normal_force = 0.0;
  double area = 0.0;
  double max_area = 0.0;

  bool ongoing() const { return std::isnan(end_time); }
  double duration() const { return (ongoing() ? last_time : end_time) - start_time; }
};

/// An observer that records every contact of a run (see the file comment). Give it to
/// `Simulation::run` or `steps`; it keeps its records across runs.
class ContactRecorder {
public:
  /// `csv_path`: if not empty, the records (finished, then ongoing) are written there at the end
  /// of each run.
  explicit ContactRecorder(std::string csv_path = "") : path_(std::move(csv_path)) {}

  /// Records the contacts touching at the start of a run (a first run: start_time = its time).
  template <class Sim>
  void start(const Sim& sim) {
    if (!started_) visit(sim);
    started_ = true;
  }
  /// After each step.
  template <class Sim>
  void operator()(const Sim& sim) {
    visit(sim);
  }
  /// At the end of a run: writes the CSV file if one was given.
  template <class Sim>
  void finish(const Sim&) {
    if (!path_.empty()) write_csv(path_);
  }

  /// The contacts that ended, in the order they ended (then by ids).
  const std::vector<ContactRecord>& finished() const { return finished_; }
  /// The contacts touching at the last step seen, ordered by (id_i, id_j, wall).
  const std::vector<ContactRecord>& ongoing() const { return ongoing_; }

  /// Writes every record as CSV: a header, then one row per contact (finished, then ongoing);
  /// end_time is empty and end_step -1 for an ongoing contact. Throws WriteError if the file
  /// cannot be written.
  void write_csv(const std::string& path) const {
    detail::AtomicFile f("grain::io::ContactRecorder", path);
    std::ostream& o = f.stream();
    o << "id_i,id_j,wall,start_time,start_step,end_time,end_step,duration,impact_velocity,"
         "max_overlap,max_normal_force,area,max_area\n";
    auto row = [&](const ContactRecord& c) {
      char end[32] = "", line[512];
      if (!c.ongoing()) std::snprintf(end, sizeof end, "%.17g", c.end_time);
      std::snprintf(line, sizeof line,
                    "%lld,%lld,%lld,%.17g,%ld,%s,%ld,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g\n",
                    static_cast<long long>(c.id_i), static_cast<long long>(c.id_j),
                    static_cast<long long>(c.wall), c.start_time, c.start_step, end, c.end_step,
                    c.duration(), c.impact_velocity, c.max_overlap, c.max_normal_force, c.area,
                    c.max_area);
      o << line;
    };
    for (const auto& c : finished_)
      row(c);
    for (const auto& c : ongoing_)
      row(c);
    f.commit();
  }

private:
  using Key = std::tuple<std::int64_t, std::int64_t, std::int64_t>;
  static Key key(const ContactRecord& c) { return {c.id_i, c.id_j, c.wall}; }

  template <class Sim>
  void visit(const Sim& sim) {
    constexpr int D = Sim::dimension;
    using C = typename Sim::contact_type;
    const auto& p = sim.particles();
    const double t = sim.time();
    const long step = static_cast<long>(sim.step_count());
    double length = 0.0;
    if constexpr (D == 2) length = sim.shape().thickness;
    now_.clear();
    sim.for_each_contact(
        [&](std::size_t i, std::size_t j, bool wall, const auto& g, const auto& r) {
          if (!(g.overlap > 0.0)) return; // an adhesive pair bonded across a gap is not a contact
          ContactRecord c;
          c.id_i = p.id[i];
          c.id_j = wall ? -1 : p.id[j];
          c.wall = wall ? static_cast<std::int64_t>(j) : -1;
          if (!wall && c.id_j < c.id_i) std::swap(c.id_i, c.id_j);
          const auto mj = wall ? sim.walls()[j].options.material : p.material[j];
          const double a = C::area_model::radius(g, sim.contact_pair(i, j, wall), r.normal,
                                                 sim.contact_params(p.material[i], mj).area);
          c.area = D == 3 ? std::numbers::pi * a * a : 2.0 * a * length;
          c.max_area = c.area;
          c.max_overlap = g.overlap;
          c.max_normal_force = r.normal.force;
          c.impact_velocity = g.normal_velocity;
          c.start_time = c.last_time = t;
          c.start_step = step;
          now_.push_back(c);
        });
    std::sort(now_.begin(), now_.end(),
              [](const ContactRecord& a, const ContactRecord& b) { return key(a) < key(b); });
    // merge with the contacts of the last step: those still touching keep their start and
    // extremes, those gone are finished, the new ones start now
    next_.clear();
    std::size_t k = 0;
    for (const auto& c : now_) {
      while (k < ongoing_.size() && key(ongoing_[k]) < key(c))
        end(ongoing_[k++], t, step);
      if (k < ongoing_.size() && key(ongoing_[k]) == key(c)) {
        ContactRecord o = ongoing_[k++];
        o.last_time = t;
        o.area = c.area;
        o.max_area = std::max(o.max_area, c.area);
        o.max_overlap = std::max(o.max_overlap, c.max_overlap);
        o.max_normal_force = std::max(o.max_normal_force, c.max_normal_force);
        next_.push_back(o);
      } else {
        next_.push_back(c);
      }
    }
    while (k < ongoing_.size())
      end(ongoing_[k++], t, step);
    ongoing_.swap(next_);
  }

  void end(ContactRecord c, double t, long step) {
    c.end_time = t;
    c.end_step = step;
    finished_.push_back(c);
  }

  std::string path_;
  bool started_ = false;
  std::vector<ContactRecord> finished_, ongoing_, now_, next_;
};

} // namespace grain::io
