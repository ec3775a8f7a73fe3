#pragma once
/// \file table.hpp
/// `Table`: a piecewise-linear function y(x) given by points with strictly increasing abscissae.
///
/// The abscissa is any quantity (time [s] for a time series, temperature [K] for a variable
/// property, ...); the table does not know its units. Between two points the value is
/// interpolated linearly; outside [x_front, x_back] the end values hold, so a table never
/// returns NaN for a non-NaN argument (also for x = +-inf). A NaN argument gives NaN.
///
/// Construction:
///
/// \code
/// grain::Table a({0.0, 1.0, 2.0}, {20.0, 80.0, 80.0});            // abscissae, ordinates
/// grain::Table b({{0.0, 20.0}, {1.0, 80.0}, {2.0, 80.0}});        // (x, y) pairs
/// grain::Table c = grain::Table::from_file("ramp.txt");           // "x y" lines, # comments
/// \endcode
///
/// Every table made from points is validated when it is made: at least two points, finite values,
/// abscissae strictly increasing. Errors are `InputError`s that name the table (its name, or
/// "Table from file '<path>'"), the offending entry (x[i] / y[i], or the line of the file), its
/// value and the valid range.
///
/// `Table()` is the empty table (no points): a placeholder, so that a parameter struct with a
/// table member can be default-constructed and its table given later
/// (`bodies::SpringParams p; p.spring = grain::Table(...);`). It is not a function: `empty()` is
/// true and it evaluates to NaN. Every object that takes a table (a spring, a torsion spring, an
/// unspring rule, a variable property, `TimeFunction::table`) rejects an empty one in its
/// validation with an `InputError` saying that the table must be given (`detail::require_given`).

#include <grain/core/error.hpp>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstddef>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>
#include <string_view>
#include <system_error>
#include <utility>
#include <vector>

namespace grain {

class Table {
public:
  /// The empty table (no points): a placeholder for a table to be given later. `empty()` is true,
  /// `size()` 0, and every evaluation gives NaN; the objects that take tables reject it.
  Table() = default;

  /// A table from its abscissae `x` and ordinates `y` (same length). `name` appears in error
  /// messages: "Table '<name>'" (just "Table" if empty).
  explicit Table(std::vector<double> x, std::vector<double> y, std::string name = {})
      : x_(std::move(x)), y_(std::move(y)), label_(label_of(name)) {
    validate(nullptr);
  }

  /// A table from a list of (x, y) pairs: `Table({{0, 1}, {2, 3}})`.
  template <std::size_t N>
  Table(const double (&points)[N][2], std::string name = {}) : label_(label_of(name)) {
    x_.reserve(N);
    y_.reserve(N);
    for (const auto& p : points) {
      x_.push_back(p[0]);
      y_.push_back(p[1]);
    }
    validate(nullptr);
  }

  /// A table from a list of (x, y) pairs held in a vector.
  explicit Table(const std::vector<std::pair<double, double>>& points, std::string name = {})
      : label_(label_of(name)) {
    x_.reserve(points.size());
    y_.reserve(points.size());
    for (const auto& [px, py] : points) {
      x_.push_back(px);
      y_.push_back(py);
    }
    validate(nullptr);
  }

  /// Reads a table from a text file of "x y" lines. A `#` starts a comment that runs to the end
  /// of the line; blank lines and comment lines are skipped; numbers are separated by spaces or
  /// tabs (a comma is not a separator: "1,5" is an error, not two numbers). Windows line ends
  /// are accepted. Errors name the file and the line: a missing or unreadable file, a line that
  /// is not two numbers, a non-finite value, an abscissa that does not increase strictly, fewer
  /// than two points.
  static Table from_file(const std::filesystem::path& path) {
    const std::string label = "Table from file '" + path.string() + "'";
    std::error_code ec;
    if (!std::filesystem::exists(path, ec)) throw InputError(label + ": the file does not exist");
    if (std::filesystem::is_directory(path, ec))
      throw InputError(label + ": the path is a directory, not a file");
    std::ifstream in(path);
    if (!in) throw InputError(label + ": the file cannot be opened for reading");

    std::vector<double> x, y;
    std::vector<std::size_t> lines;
    std::string line;
    std::size_t number = 0;
    while (std::getline(in, line)) {
      ++number;
      std::string_view rest(line);
      if (const auto hash = rest.find('#'); hash != std::string_view::npos)
        rest = rest.substr(0, hash);
      double v[2];
      int count = 0;
      while (true) {
        const auto begin = rest.find_first_not_of(" \t\r\v\f");
        if (begin == std::string_view::npos) break;
        rest = rest.substr(begin);
        const auto end = std::min(rest.find_first_of(" \t\r\v\f"), rest.size());
        const std::string_view token = rest.substr(0, end);
        rest = rest.substr(end);
        if (count == 2) throw bad_line(label, number, line, "more than two numbers");
        if (!parse_number(token, v[count]))
          throw bad_line(label, number, line, "'" + std::string(token) + "' is not a number");
        ++count;
      }
      if (count == 0) continue;
      if (count == 1) throw bad_line(label, number, line, "only one number");
      x.push_back(v[0]);
      y.push_back(v[1]);
      lines.push_back(number);
    }
    if (in.bad()) throw InputError(label + ": reading failed after line " + std::to_string(number));
    Table t;
    t.x_ = std::move(x);
    t.y_ = std::move(y);
    t.label_ = label;
    t.validate(&lines);
    return t;
  }

  /// y(x): linear interpolation inside [x_front, x_back], the end value outside. O(log n). NaN for
  /// the empty table.
  double operator()(double x) const noexcept {
    if (x_.empty()) return std::numeric_limits<double>::quiet_NaN();
    if (x <= x_.front()) return y_.front();
    if (x >= x_.back()) return y_.back();
    return interpolate(segment(x), x);
  }

  /// The same value, with a caller-held cursor for repeated evaluation at slowly increasing x
  /// (a time loop): if x lies in the segment `hint` or the next one, no search is done. `hint`
  /// is updated to the segment of x; any value is a valid starting hint (start with 0). Each
  /// caller (each thread) keeps its own hint; the table itself is never modified.
  double operator()(double x, std::size_t& hint) const noexcept {
    if (x_.empty()) return std::numeric_limits<double>::quiet_NaN();
    if (x <= x_.front()) {
      hint = 0;
      return y_.front();
    }
    if (x >= x_.back()) {
      hint = x_.size() - 2;
      return y_.back();
    }
    const std::size_t i = hint;
    if (i + 1 < x_.size() && x_[i] <= x) {
      if (x < x_[i + 1]) return interpolate(i, x);
      if (i + 2 < x_.size() && x < x_[i + 2]) {
        hint = i + 1;
        return interpolate(i + 1, x);
      }
    }
    hint = segment(x);
    return interpolate(hint, x);
  }

  /// The segment i (0 <= i <= size() - 2) with x[i] <= x < x[i+1], clamped to the first and last
  /// segment outside the range (0 for the empty table, which has no segment).
  std::size_t segment(double x) const noexcept {
    if (x_.size() < 2) return 0;
    const auto it = std::upper_bound(x_.begin() + 1, x_.end() - 1, x);
    return static_cast<std::size_t>(it - x_.begin()) - 1;
  }

  std::size_t size() const noexcept { return x_.size(); }
  /// True for the empty table of the default constructor (a table made from points never is).
  bool empty() const noexcept { return x_.empty(); }
  const std::vector<double>& x() const noexcept { return x_; }
  const std::vector<double>& y() const noexcept { return y_; }
  /// The first and last abscissa (NaN for the empty table).
  double x_front() const noexcept {
    return x_.empty() ? std::numeric_limits<double>::quiet_NaN() : x_.front();
  }
  double x_back() const noexcept {
    return x_.empty() ? std::numeric_limits<double>::quiet_NaN() : x_.back();
  }
  /// How the table is named in messages: "Table 'name'", "Table" or "Table from file 'path'".
  const std::string& label() const noexcept { return label_; }

private:
  static std::string label_of(const std::string& name) {
    return name.empty() ? std::string("Table") : "Table '" + name + "'";
  }

  double interpolate(std::size_t i, double x) const noexcept {
    const double t = (x - x_[i]) / (x_[i + 1] - x_[i]);
    return y_[i] + t * (y_[i + 1] - y_[i]);
  }

  static bool parse_number(std::string_view token, double& value) {
    if (!token.empty() && token.front() == '+') {
      token.remove_prefix(1);
      if (!token.empty() && (token.front() == '+' || token.front() == '-')) return false;
    }
    if (token.empty()) return false;
    const auto [end, ec] = std::from_chars(token.data(), token.data() + token.size(), value);
    return ec == std::errc() && end == token.data() + token.size();
  }

  static InputError bad_line(const std::string& label, std::size_t number, const std::string& line,
                             const std::string& why) {
    std::string text = line;
    if (!text.empty() && text.back() == '\r') text.pop_back();
    return InputError(label + ": line " + std::to_string(number) + " = '" + text +
                      "' is invalid (" + why + "); valid range: two numbers \"x y\", optionally " +
                      "followed by a # comment");
  }

  /// Checks the points; `lines` (null for inline tables) gives the file line of each point.
  void validate(const std::vector<std::size_t>* lines) const {
    const auto where = [&](char axis, std::size_t i) {
      if (!lines) return std::string(1, axis) + "[" + std::to_string(i) + "]";
      return std::string(1, axis) + " on line " + std::to_string((*lines)[i]);
    };
    const auto fail = [&](const std::string& what, double value, const std::string& range) {
      throw InputError(label_ + ": " + what + " = " + detail::to_text(value) +
                       " is invalid; valid range: " + range);
    };
    if (y_.size() != x_.size())
      throw InputError(label_ + ": number of ordinates y = " + std::to_string(y_.size()) +
                       " is invalid; valid range: " + std::to_string(x_.size()) +
                       " (one per abscissa x)");
    if (x_.size() < 2) {
      std::string note;
      if (lines && lines->empty()) note = " (the file has no data lines)";
      if (lines && lines->size() == 1)
        note = " (the only data line is line " + std::to_string((*lines)[0]) + ")";
      throw InputError(label_ + ": number of points = " + std::to_string(x_.size()) +
                       " is invalid; valid range: [2, inf)" + note);
    }
    for (std::size_t i = 0; i < x_.size(); ++i) {
      if (!std::isfinite(x_[i])) fail(where('x', i), x_[i], "a finite number");
      if (!std::isfinite(y_[i])) fail(where('y', i), y_[i], "a finite number");
      if (i == 0) continue;
      if (!(x_[i] > x_[i - 1]))
        fail(where('x', i), x_[i],
             "(" + detail::to_text(x_[i - 1]) + ", inf), above " + where('x', i - 1) + " = " +
                 detail::to_text(x_[i - 1]) + " (abscissae must increase strictly; " +
                 (x_[i] == x_[i - 1] ? "duplicate" : "unsorted") + ")");
      if (!std::isfinite(x_[i] - x_[i - 1]))
        fail(where('x', i) + " - " + where('x', i - 1), x_[i] - x_[i - 1],
             "a finite difference (neighbouring points too far apart)");
      if (!std::isfinite(y_[i] - y_[i - 1]))
        fail(where('y', i) + " - " + where('y', i - 1), y_[i] - y_[i - 1],
             "a finite difference (neighbouring points too far apart)");
    }
  }

  std::vector<double> x_, y_;
  std::string label_ = "Table";
};

namespace detail {

/// Throws `InputError("<object>: <name> = Table (no points) is invalid; valid range: a Table of
/// at least 2 points (<what> must be given)")` for the empty table of the default constructor.
inline void require_given(const Table& t, const std::string& object, const std::string& name,
                          const std::string& what) {
  if (t.empty())
    throw InputError(
        object + ": " + name +
        " = Table (no points) is invalid; valid range: a Table of at least 2 points (" + what +
        " must be given)");
}

} // namespace detail

} // namespace grain
