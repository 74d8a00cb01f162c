#include "roller/mesh/strip_mesher.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <iomanip>
#include <sstream>
#include <string>
#include <vector>

#include "roller/core/error.hpp"

namespace roller {
namespace {

// Explicit grid lines may come from decimal scene input; their ends are accepted within this
// relative tolerance of 0 and the extent and then snapped exactly.
constexpr Real kEndTolerance = 1e-9;

// A structured strip with millions of nodes is beyond what the direct solvers of the
// increment problem handle; a larger request is almost surely a mistyped refine or nx.
constexpr Real kMaxNodes = 1e7;

std::string to_text(Real value) {
  std::ostringstream out;
  out << std::setprecision(12) << value;
  return out.str();
}

// ---------------------------------------------------------------------------------------------
// Grid lines
// ---------------------------------------------------------------------------------------------

std::vector<Real> uniform_lines(Real extent, int n) {
  std::vector<Real> lines(static_cast<std::size_t>(n) + 1);
  for (int i = 0; i <= n; ++i) lines[static_cast<std::size_t>(i)] = extent * i / n;
  lines.back() = extent;
  return lines;
}

// Growth factor between neighbouring intervals so that n intervals span `ratio`.
Real growth_factor(int n, Real ratio) { return n < 2 ? 1.0 : std::pow(ratio, 1.0 / (n - 1)); }

Real progression_sum(Real first, int n, Real q) {
  Real sum = 0.0;
  Real interval = first;
  for (int k = 0; k < n; ++k) {
    sum += interval;
    interval *= q;
  }
  return sum;
}

// Intervals first, first*q, ..., rescaled so that they sum to `length` exactly (up to
// round-off), listed from the fine end outwards.
std::vector<Real> progression(Real length, int n, Real first, Real q) {
  std::vector<Real> intervals(static_cast<std::size_t>(n));
  Real interval = first;
  for (auto& h : intervals) {
    h = interval;
    interval *= q;
  }
  const Real scale = length / progression_sum(first, n, q);
  for (auto& h : intervals) h *= scale;
  return intervals;
}

// First (finest) interval of n intervals over `length` whose largest/smallest is `ratio`.
Real first_interval(Real length, int n, Real ratio) {
  return length / progression_sum(1.0, n, growth_factor(n, ratio));
}

std::vector<Real> full_ratio_progression(Real length, int n, Real ratio) {
  const Real q = growth_factor(n, ratio);
  return progression(length, n, first_interval(length, n, ratio), q);
}

// n intervals over `length` that start at `first` and grow by the factor q in [1, q_max]
// that makes them fit; the caller guarantees n*first <= length <= sum at q_max.
std::vector<Real> progression_from_first(Real length, int n, Real first, Real q_max) {
  Real lo = 1.0;
  Real hi = q_max;
  for (int iteration = 0; iteration < 200 && hi - lo > 1e-15 * hi; ++iteration) {
    const Real mid = 0.5 * (lo + hi);
    (progression_sum(first, n, mid) < length ? lo : hi) = mid;
  }
  return progression(length, n, first, 0.5 * (lo + hi));
}

// Lines from `start` stepping by `intervals` in direction `sign` (+1 right, -1 left).
std::vector<Real> walk(Real start, const std::vector<Real>& intervals, Real sign) {
  std::vector<Real> lines{start};
  for (const Real h : intervals) lines.push_back(lines.back() + sign * h);
  return lines;
}

std::vector<Real> one_sided_lines(Real extent, int n, Real ratio, bool fine_at_start) {
  const std::vector<Real> intervals = full_ratio_progression(extent, n, ratio);
  std::vector<Real> lines = fine_at_start ? walk(0.0, intervals, 1.0) : walk(extent, intervals, -1.0);
  if (!fine_at_start) std::reverse(lines.begin(), lines.end());
  lines.front() = 0.0;
  lines.back() = extent;
  return lines;
}

// How n intervals are shared between the sides [0, focus] and [focus, extent].
struct FocusSplit {
  int n_left = 1;
  Real first_left = 0.0;   // finest interval of the left side if it spanned `ratio` alone
  Real first_right = 0.0;  // same for the right side
  Real mismatch = 0.0;     // |log(first_left / first_right)|
  // Both sides can start with the same interval at the focus and the whole axis still spans
  // exactly `ratio`.
  bool common_spacing = false;
};

FocusSplit evaluate_split(Real left, Real right, int n, int n_left, Real ratio) {
  FocusSplit split;
  split.n_left = n_left;
  split.first_left = first_interval(left, n_left, ratio);
  split.first_right = first_interval(right, n - n_left, ratio);
  split.mismatch = std::abs(std::log(split.first_left / split.first_right));
  // The side that needs the coarser start sets the common focus spacing and spans the ratio,
  // which takes at least two intervals unless both sides happen to agree; the other side
  // then grows less, which needs room for its intervals at that spacing (growth >= 1).
  const bool left_sets = split.first_left >= split.first_right;
  const Real first = std::max(split.first_left, split.first_right);
  const int setter_n = left_sets ? n_left : n - n_left;
  const int other_n = left_sets ? n - n_left : n_left;
  const Real other_length = left_sets ? right : left;
  const bool sides_agree = split.mismatch <= kEndTolerance;
  const bool spans_ratio = setter_n >= 2 || (sides_agree && other_n >= 2);
  const bool other_fits = other_n * first <= other_length * (1.0 + kEndTolerance);
  split.common_spacing = spans_ratio && other_fits;
  return split;
}

// The split whose sides' own finest intervals agree best, preferring those that allow a
// common spacing at the focus.
FocusSplit best_split(Real left, Real right, int n, Real ratio) {
  FocusSplit best = evaluate_split(left, right, n, 1, ratio);
  for (int n_left = 2; n_left < n; ++n_left) {
    const FocusSplit split = evaluate_split(left, right, n, n_left, ratio);
    const bool better =
        split.common_spacing == best.common_spacing ? split.mismatch < best.mismatch : split.common_spacing;
    if (better) best = split;
  }
  return best;
}

// Intervals of both sides listed outwards from the focus. The side that needs the coarser
// start spans the full ratio; the other starts with the same interval and grows less.
void common_spacing_intervals(Real left, Real right, int n, Real ratio, const FocusSplit& split,
                              std::vector<Real>* left_intervals, std::vector<Real>* right_intervals) {
  const int n_right = n - split.n_left;
  const Real first = std::max(split.first_left, split.first_right);
  if (split.first_left >= split.first_right) {
    *left_intervals = full_ratio_progression(left, split.n_left, ratio);
    *right_intervals = progression_from_first(right, n_right, first, growth_factor(n_right, ratio));
  } else {
    *right_intervals = full_ratio_progression(right, n_right, ratio);
    *left_intervals = progression_from_first(left, split.n_left, first, growth_factor(split.n_left, ratio));
  }
}

std::vector<Real> lines_around(Real focus, Real extent, const std::vector<Real>& left_intervals,
                               const std::vector<Real>& right_intervals) {
  std::vector<Real> lines = walk(focus, left_intervals, -1.0);
  std::reverse(lines.begin(), lines.end());
  const std::vector<Real> right_lines = walk(focus, right_intervals, 1.0);
  lines.insert(lines.end(), right_lines.begin() + 1, right_lines.end());
  lines.front() = 0.0;
  lines.back() = extent;
  return lines;
}

std::vector<Real> two_sided_lines(Real extent, int n, Real ratio, Real focus) {
  const Real left = focus;
  const Real right = extent - focus;
  const FocusSplit split = best_split(left, right, n, ratio);
  if (split.common_spacing) {
    std::vector<Real> left_intervals;
    std::vector<Real> right_intervals;
    common_spacing_intervals(left, right, n, ratio, split, &left_intervals, &right_intervals);
    return lines_around(focus, extent, left_intervals, right_intervals);
  }
  // The focus lies about one finest interval from an end: a line there would leave a sliver,
  // so grade from that end (the ratio stays exact, the finest spacing is next to the focus).
  const bool near_left = left <= right;
  if ((near_left ? split.n_left : n - split.n_left) == 1) return one_sided_lines(extent, n, ratio, near_left);
  // Integer counts forbid a common focus spacing (small ratio, lopsided counts): each side
  // spans the ratio on its own, and the focus spacings differ by exp(mismatch).
  return lines_around(focus, extent, full_ratio_progression(left, split.n_left, ratio),
                      full_ratio_progression(right, n - split.n_left, ratio));
}

std::vector<Real> geometric_lines(Real extent, int n, const Grading& grading) {
  if (n == 1 || grading.ratio == 1.0) return uniform_lines(extent, n);
  if (grading.focus <= 0.0) return one_sided_lines(extent, n, grading.ratio, true);
  if (grading.focus >= extent) return one_sided_lines(extent, n, grading.ratio, false);
  return two_sided_lines(extent, n, grading.ratio, grading.focus);
}

void require_input(bool condition, const std::string& message) {
  if (!condition) throw InputError(message);
}

bool strictly_increasing(const std::vector<Real>& lines) {
  return std::adjacent_find(lines.begin(), lines.end(), std::greater_equal<Real>()) == lines.end();
}

std::vector<Real> refine_lines(const std::vector<Real>& lines, int refine) {
  std::vector<Real> refined{lines.front()};
  for (std::size_t i = 0; i + 1 < lines.size(); ++i) {
    const Real width = lines[i + 1] - lines[i];
    for (int k = 1; k < refine; ++k) refined.push_back(lines[i] + width * k / refine);
    refined.push_back(lines[i + 1]);
  }
  return refined;
}

std::vector<Real> base_lines(const std::vector<Real>& explicit_lines, Real extent, int n, const Grading& grading) {
  if (explicit_lines.empty()) return grid_lines(extent, n, grading);
  std::vector<Real> lines = explicit_lines;
  lines.front() = 0.0;
  lines.back() = extent;
  return lines;
}

// ---------------------------------------------------------------------------------------------
// Validation (messages name the scene key, its value and the rule)
// ---------------------------------------------------------------------------------------------

std::string check_positive(const std::string& key, Real value) {
  if (std::isfinite(value) && value > 0.0) return {};
  return key + " = " + to_text(value) + ": must be a finite number > 0";
}

std::string check_grading(const std::string& key, const Grading& grading, Real extent) {
  if (grading.kind != Grading::Kind::Uniform && grading.kind != Grading::Kind::Geometric)
    return key + ".kind = " + std::to_string(static_cast<int>(grading.kind)) + ": must be uniform or geometric";
  if (grading.kind == Grading::Kind::Uniform) return {};
  if (!std::isfinite(grading.ratio) || grading.ratio < 1.0)
    return key + ".ratio = " + to_text(grading.ratio) + ": must be >= 1 (largest / smallest interval)";
  if (!std::isfinite(grading.focus) || grading.focus < 0.0 || grading.focus > extent)
    return key + ".focus = " + to_text(grading.focus) + ": must lie in [0, " + to_text(extent) +
           "] (the strip's extent along that axis)";
  return {};
}

std::string check_lines(const std::string& key, const std::vector<Real>& lines, Real extent) {
  if (lines.size() < 2)
    return key + " has " + std::to_string(lines.size()) + " entries: needs at least 2 (from 0 to the strip's extent)";
  for (std::size_t i = 0; i < lines.size(); ++i) {
    if (!std::isfinite(lines[i]))
      return key + "[" + std::to_string(i) + "] = " + to_text(lines[i]) + ": must be finite";
  }
  if (std::abs(lines.front()) > kEndTolerance * extent) return key + "[0] = " + to_text(lines.front()) + ": must be 0";
  if (std::abs(lines.back() - extent) > kEndTolerance * extent)
    return key + "[" + std::to_string(lines.size() - 1) + "] = " + to_text(lines.back()) +
           ": must equal the strip's extent " + to_text(extent);
  for (std::size_t i = 1; i < lines.size(); ++i) {
    if (lines[i] <= lines[i - 1])
      return key + "[" + std::to_string(i) + "] = " + to_text(lines[i]) + ": must be > " + key + "[" +
             std::to_string(i - 1) + "] = " + to_text(lines[i - 1]) + " (strictly increasing)";
  }
  return {};
}

// One axis: explicit lines, or a count with its grading.
std::string check_axis(const std::string& axis, const std::vector<Real>& lines, int n, const Grading& grading,
                       Real extent) {
  if (!lines.empty()) return check_lines("mesh." + axis + "_lines", lines, extent);
  if (n < 1) return "mesh.n" + axis + " = " + std::to_string(n) + ": must be >= 1";
  return check_grading("mesh.grading_" + axis, grading, extent);
}

int intervals_along(const std::vector<Real>& lines, int n) {
  return lines.empty() ? n : static_cast<int>(lines.size()) - 1;
}

std::string check_size(const StripMeshSpec& spec) {
  const Real n_nodes = strip_node_count(spec);
  if (n_nodes <= kMaxNodes) return {};
  return "mesh.refine = " + std::to_string(spec.refine) + ": the mesh would have " + to_text(n_nodes) +
         " nodes, more than the limit " + to_text(kMaxNodes) + " (lower refine, nx or ny)";
}

std::string first_problem(const StripMeshSpec& spec) {
  if (spec.element != ElementType::T3 && spec.element != ElementType::Q4)
    return "mesh.element = " + std::to_string(static_cast<int>(spec.element)) + ": must be T3 or Q4";
  if (spec.diagonal != Diagonal::Rising && spec.diagonal != Diagonal::Falling && spec.diagonal != Diagonal::Alternating)
    return "mesh.diagonal = " + std::to_string(static_cast<int>(spec.diagonal)) +
           ": must be rising, falling or alternating";
  for (const std::string& problem :
       {check_positive("mesh.length", spec.length), check_positive("mesh.height", spec.height)}) {
    if (!problem.empty()) return problem;
  }
  for (const std::string& problem : {check_axis("x", spec.x_lines, spec.nx, spec.grading_x, spec.length),
                                     check_axis("y", spec.y_lines, spec.ny, spec.grading_y, spec.height)}) {
    if (!problem.empty()) return problem;
  }
  if (spec.refine < 1) return "mesh.refine = " + std::to_string(spec.refine) + ": must be >= 1";
  return check_size(spec);
}

// ---------------------------------------------------------------------------------------------
// Connectivity (numbering of mesh.hpp: column by column from the left, top to bottom)
// ---------------------------------------------------------------------------------------------

struct Grid {
  Index n_columns;  // intervals along x
  Index n_rows;     // intervals along y

  // Node in column i (from the left) and row j (from the top).
  Index node(Index i, Index j) const { return i * (n_rows + 1) + j; }
};

// Corners of the quad in column i, row j (from the top): bottom-left, bottom-right,
// top-right, top-left, i.e. counter-clockwise.
std::vector<Index> quad_corners(const Grid& grid, Index i, Index j) {
  return {grid.node(i, j + 1), grid.node(i + 1, j + 1), grid.node(i + 1, j), grid.node(i, j)};
}

// Alternating flips the diagonal in a checkerboard anchored at the bottom-left quad, so that
// four quads around every other node form a "union jack": no preferred direction, and less
// volumetric locking of constant-strain triangles than one uniform diagonal.
bool rising_diagonal(Diagonal diagonal, const Grid& grid, Index i, Index j) {
  if (diagonal != Diagonal::Alternating) return diagonal == Diagonal::Rising;
  const Index row_from_bottom = grid.n_rows - 1 - j;
  return (i + row_from_bottom) % 2 == 0;
}

// The two counter-clockwise triangles of a quad, the one on the bottom edge first.
void append_triangles(const std::vector<Index>& q, bool rising, std::vector<std::vector<Index>>* elements) {
  if (rising) {
    elements->push_back({q[0], q[1], q[2]});
    elements->push_back({q[0], q[2], q[3]});
  } else {
    elements->push_back({q[0], q[1], q[3]});
    elements->push_back({q[1], q[2], q[3]});
  }
}

std::vector<std::vector<Index>> strip_elements(const Grid& grid, ElementType type, Diagonal diagonal) {
  std::vector<std::vector<Index>> elements;
  elements.reserve(static_cast<std::size_t>(grid.n_columns * grid.n_rows * (type == ElementType::T3 ? 2 : 1)));
  for (Index i = 0; i < grid.n_columns; ++i) {
    for (Index j = 0; j < grid.n_rows; ++j) {
      const std::vector<Index> quad = quad_corners(grid, i, j);
      if (type == ElementType::Q4)
        elements.push_back(quad);
      else
        append_triangles(quad, rising_diagonal(diagonal, grid, i, j), &elements);
    }
  }
  return elements;
}

std::vector<Vec2> strip_nodes(const std::vector<Real>& xs, const std::vector<Real>& ys) {
  std::vector<Vec2> nodes;
  nodes.reserve(xs.size() * ys.size());
  for (const Real x : xs) {
    for (auto y = ys.rbegin(); y != ys.rend(); ++y) nodes.emplace_back(x, *y);
  }
  return nodes;
}

std::map<std::string, std::vector<Index>> strip_node_sets(const Grid& grid) {
  const Index last_column = grid.n_columns;
  const Index bottom_row = grid.n_rows;
  std::map<std::string, std::vector<Index>> sets;
  for (Index i = 0; i <= last_column; ++i) {
    sets["top"].push_back(grid.node(i, 0));
    sets["bottom"].push_back(grid.node(i, bottom_row));
  }
  for (Index j = bottom_row; j >= 0; --j) {
    sets["left"].push_back(grid.node(0, j));
    sets["right"].push_back(grid.node(last_column, j));
  }
  sets["top_left"] = {grid.node(0, 0)};
  sets["top_right"] = {grid.node(last_column, 0)};
  sets["bottom_left"] = {grid.node(0, bottom_row)};
  sets["bottom_right"] = {grid.node(last_column, bottom_row)};
  sets["contact"] = sets["top"];
  auto& all = sets["all"];
  all.resize(static_cast<std::size_t>((last_column + 1) * (bottom_row + 1)));
  for (std::size_t k = 0; k < all.size(); ++k) all[k] = static_cast<Index>(k);
  return sets;
}

}  // namespace

Real strip_node_count(const StripMeshSpec& spec) {
  const Real columns = static_cast<Real>(intervals_along(spec.x_lines, spec.nx)) * spec.refine;
  const Real rows =
      static_cast<Real>(intervals_along(spec.y_lines, spec.ny) + static_cast<int>(spec.pinned_y.size())) * spec.refine;
  return (columns + 1.0) * (rows + 1.0);
}

bool StripMeshSpec::is_valid(std::string* why) const {
  const std::string problem = first_problem(*this);
  if (why != nullptr) *why = problem;
  return problem.empty();
}

std::vector<Real> pin_lines(std::vector<Real> lines, const std::vector<Real>& pins) {
  // Lines that sit on a pin stay where they are; the others may be moved onto one.
  std::vector<bool> pinned(lines.size(), false);
  pinned.front() = pinned.back() = true;
  for (const Real pin : pins) {
    if (!(pin > lines.front() && pin < lines.back())) continue;
    // Lines k-1 < pin <= k.
    const auto k = static_cast<std::size_t>(std::lower_bound(lines.begin(), lines.end(), pin) - lines.begin());
    if (lines[k] == pin) {
      pinned[k] = true;
      continue;
    }
    const Real width = lines[k] - lines[k - 1];
    const std::size_t nearest = pin - lines[k - 1] < lines[k] - pin ? k - 1 : k;
    if (!pinned[nearest] && std::abs(lines[nearest] - pin) < 0.3 * width) {
      lines[nearest] = pin;
      pinned[nearest] = true;
    } else {
      lines.insert(lines.begin() + static_cast<std::ptrdiff_t>(k), pin);
      pinned.insert(pinned.begin() + static_cast<std::ptrdiff_t>(k), true);
    }
  }
  return lines;
}

std::vector<Real> grid_lines(Real extent, int n, const Grading& grading) {
  require_input(std::isfinite(extent) && extent > 0.0,
                "grid_lines: extent = " + to_text(extent) + ": must be a finite number > 0");
  require_input(n >= 1, "grid_lines: n = " + std::to_string(n) + ": must be >= 1");
  const std::string problem = check_grading("grid_lines: grading", grading, extent);
  require_input(problem.empty(), problem);

  std::vector<Real> lines =
      grading.kind == Grading::Kind::Uniform ? uniform_lines(extent, n) : geometric_lines(extent, n, grading);
  require_input(strictly_increasing(lines), "grid_lines: grading.ratio = " + to_text(grading.ratio) + " over " +
                                                std::to_string(n) +
                                                " intervals shrinks some below round-off: lower it");
  return lines;
}

Mesh make_strip_mesh(const StripMeshSpec& spec) {
  std::string why;
  if (!spec.is_valid(&why)) throw InputError(why);

  const std::vector<Real> xs =
      refine_lines(base_lines(spec.x_lines, spec.length, spec.nx, spec.grading_x), spec.refine);
  const std::vector<Real> ys = refine_lines(
      pin_lines(base_lines(spec.y_lines, spec.height, spec.ny, spec.grading_y), spec.pinned_y), spec.refine);
  const Grid grid{static_cast<Index>(xs.size()) - 1, static_cast<Index>(ys.size()) - 1};

  Mesh mesh;
  mesh.element_type = spec.element;
  mesh.nodes = strip_nodes(xs, ys);
  mesh.elements = strip_elements(grid, spec.element, spec.diagonal);
  mesh.node_sets = strip_node_sets(grid);
  if (spec.periodic) mesh.period = spec.length;
  return mesh;
}

}  // namespace roller
