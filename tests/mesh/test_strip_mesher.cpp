#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <functional>
#include <string>
#include <vector>

#include "../support/strip_spec.hpp"
#include "roller/core/error.hpp"
#include "roller/mesh/mesh.hpp"
#include "roller/mesh/strip_mesher.hpp"

using namespace roller;

namespace {

// The thesis's scenes (docs/thesis-meshes.md).
StripMeshSpec z1_spec() {
  StripMeshSpec spec = test::strip_spec(ElementType::T3, 225.0, 20.0, 45, 3, Diagonal::Alternating);
  return spec;
}

StripMeshSpec z2_spec() {
  StripMeshSpec spec;
  spec.length = 100.0;
  spec.height = 40.0;
  spec.nx = 10;
  spec.ny = 4;
  return spec;
}

StripMeshSpec z3_spec() {
  StripMeshSpec spec;
  spec.length = 427.5;
  spec.height = 50.0;
  spec.x_lines = {0.0, 35.0, 60.0, 77.5, 90.0};
  for (int k = 1; k <= 21; ++k) spec.x_lines.push_back(90.0 + 10.0 * k);
  for (const Real x : {312.5, 330.0, 355.0, 387.5, 427.5}) spec.x_lines.push_back(x);
  spec.y_lines = {0.0, 15.0, 27.5, 37.5, 45.0, 50.0};
  return spec;
}

StripMeshSpec z4_spec() {
  StripMeshSpec spec;
  spec.length = 200.0;
  spec.height = 40.0;
  spec.nx = 20;
  spec.ny = 4;
  return spec;
}

const Vec2& node_at(const Mesh& mesh, Index n) { return mesh.nodes[static_cast<std::size_t>(n)]; }

// Coordinate `axis` of the nodes of a set, in the set's order.
std::vector<Real> coordinates(const Mesh& mesh, const std::string& set, int axis) {
  std::vector<Real> values;
  for (const Index n : mesh.node_set(set)) values.push_back(node_at(mesh, n)[axis]);
  return values;
}

bool all_equal(const std::vector<Real>& values, Real value) {
  return std::all_of(values.begin(), values.end(), [&](Real v) { return v == value; });
}

bool strictly_increasing(const std::vector<Real>& values) {
  return std::adjacent_find(values.begin(), values.end(), std::greater_equal<Real>()) == values.end();
}

Real signed_area(const Mesh& mesh, const std::vector<Index>& element) {
  Real twice_area = 0.0;
  for (std::size_t k = 0; k < element.size(); ++k) {
    const Vec2& a = node_at(mesh, element[k]);
    const Vec2& b = node_at(mesh, element[(k + 1) % element.size()]);
    twice_area += a.x() * b.y() - b.x() * a.y();
  }
  return 0.5 * twice_area;
}

// Every corner turns left: the element is convex and counter-clockwise.
bool turns_left_at_every_corner(const Mesh& mesh, const std::vector<Index>& element) {
  const std::size_t n = element.size();
  for (std::size_t k = 0; k < n; ++k) {
    const Vec2& a = node_at(mesh, element[k]);
    const Vec2& b = node_at(mesh, element[(k + 1) % n]);
    const Vec2& c = node_at(mesh, element[(k + 2) % n]);
    const Vec2 ab = b - a;
    const Vec2 bc = c - b;
    if (ab.x() * bc.y() - ab.y() * bc.x() <= 0.0) return false;
  }
  return true;
}

std::vector<Real> intervals_of(const std::vector<Real>& lines) {
  std::vector<Real> intervals;
  for (std::size_t i = 0; i + 1 < lines.size(); ++i) intervals.push_back(lines[i + 1] - lines[i]);
  return intervals;
}

Real max_over_min(const std::vector<Real>& intervals) {
  const auto [lo, hi] = std::minmax_element(intervals.begin(), intervals.end());
  return *hi / *lo;
}

bool contains(const std::vector<Real>& values, Real value) {
  return std::find(values.begin(), values.end(), value) != values.end();
}

std::vector<Real> node_xs(const Mesh& mesh) {
  std::vector<Real> xs;
  for (const Vec2& p : mesh.nodes) xs.push_back(p.x());
  return xs;
}

std::vector<Real> node_ys(const Mesh& mesh) {
  std::vector<Real> ys;
  for (const Vec2& p : mesh.nodes) ys.push_back(p.y());
  return ys;
}

Grading geometric(Real ratio, Real focus) {
  Grading grading;
  grading.kind = Grading::Kind::Geometric;
  grading.ratio = ratio;
  grading.focus = focus;
  return grading;
}

// Every element variant the mesher can build, on uniform, graded and explicit lines.
std::vector<StripMeshSpec> assorted_specs() {
  std::vector<StripMeshSpec> specs;
  for (const Diagonal diagonal : {Diagonal::Rising, Diagonal::Falling, Diagonal::Alternating}) {
    for (const ElementType element : {ElementType::T3, ElementType::Q4}) {
      StripMeshSpec uniform = z2_spec();
      uniform.element = element;
      uniform.diagonal = diagonal;
      specs.push_back(uniform);

      StripMeshSpec graded = uniform;
      graded.nx = 17;
      graded.ny = 5;
      graded.grading_x = geometric(6.0, 37.0);
      graded.grading_y = geometric(3.0, graded.height);
      specs.push_back(graded);

      StripMeshSpec explicit_lines = z3_spec();
      explicit_lines.element = element;
      explicit_lines.diagonal = diagonal;
      explicit_lines.refine = 2;
      specs.push_back(explicit_lines);
    }
  }
  return specs;
}

void require_spec_rejected(const StripMeshSpec& spec, const std::string& key) {
  std::string why;
  CHECK_FALSE(spec.is_valid(&why));
  CHECK_THAT(why, Catch::Contains(key));
  CHECK_THROWS_AS(make_strip_mesh(spec), InputError);
  CHECK_THROWS_WITH(make_strip_mesh(spec), Catch::Contains(key));
}

}  // namespace

TEST_CASE("The thesis meshes Z1-Z4 have the thesis's node, element and top-node counts", "[mesh]") {
  struct Expected {
    StripMeshSpec spec;
    Index n_nodes, n_elements, n_top;
  };
  const std::vector<Expected> scenes = {
      {z1_spec(), 184, 270, 46}, {z2_spec(), 55, 40, 11}, {z3_spec(), 186, 150, 31}, {z4_spec(), 105, 80, 21}};
  for (const auto& scene : scenes) {
    const Mesh mesh = make_strip_mesh(scene.spec);
    CHECK(mesh.n_nodes() == scene.n_nodes);
    CHECK(mesh.n_elements() == scene.n_elements);
    CHECK(static_cast<Index>(mesh.node_set("top").size()) == scene.n_top);
    CHECK(mesh.node_set("contact") == mesh.node_set("top"));
  }
  CHECK(make_strip_mesh(z1_spec()).element_type == ElementType::T3);
  CHECK(make_strip_mesh(z2_spec()).element_type == ElementType::Q4);
}

TEST_CASE("Z4's thesis node 5 is the bottom-left and node 101 the top-right corner", "[mesh]") {
  const Mesh mesh = make_strip_mesh(z4_spec());
  CHECK(mesh.nodes[4].x() == 0.0);
  CHECK(mesh.nodes[4].y() == 0.0);
  CHECK(mesh.nodes[100].x() == 200.0);
  CHECK(mesh.nodes[100].y() == 40.0);
  CHECK(mesh.node_set("bottom_left") == std::vector<Index>{4});
  CHECK(mesh.node_set("top_right") == std::vector<Index>{100});
}

TEST_CASE("Nodes and elements are numbered column by column, top to bottom", "[mesh]") {
  const Mesh mesh = make_strip_mesh(z2_spec());  // 10 mm squares, 5 nodes per column
  CHECK(mesh.nodes[0] == Vec2(0.0, 40.0));
  CHECK(mesh.nodes[1] == Vec2(0.0, 30.0));
  CHECK(mesh.nodes[5] == Vec2(10.0, 40.0));
  CHECK(mesh.nodes[54] == Vec2(100.0, 0.0));
  // Element 0: top-left quad as bottom-left, bottom-right, top-right, top-left.
  CHECK(mesh.elements[0] == std::vector<Index>{1, 6, 5, 0});
  // Element 3: bottom quad of the first column; element 4 starts the second column.
  CHECK(mesh.elements[3] == std::vector<Index>{4, 9, 8, 3});
  CHECK(mesh.elements[4] == std::vector<Index>{6, 11, 10, 5});
}

TEST_CASE("Edge sets are sorted along their edge and the corner sets hold one node", "[mesh]") {
  const Mesh mesh = make_strip_mesh(z3_spec());
  CHECK(strictly_increasing(coordinates(mesh, "top", 0)));
  CHECK(strictly_increasing(coordinates(mesh, "bottom", 0)));
  CHECK(strictly_increasing(coordinates(mesh, "left", 1)));
  CHECK(strictly_increasing(coordinates(mesh, "right", 1)));
  CHECK(all_equal(coordinates(mesh, "top", 1), 50.0));
  CHECK(all_equal(coordinates(mesh, "bottom", 1), 0.0));
  CHECK(all_equal(coordinates(mesh, "left", 0), 0.0));
  CHECK(all_equal(coordinates(mesh, "right", 0), 427.5));
  CHECK(mesh.node_set("left").size() == 6);
  CHECK(mesh.node_set("top_left") == std::vector<Index>{0});
  CHECK(mesh.node_set("bottom_left") == std::vector<Index>{5});
  CHECK(mesh.node_set("top_right") == std::vector<Index>{180});
  CHECK(mesh.node_set("bottom_right") == std::vector<Index>{185});
  CHECK(mesh.node_set("all").size() == 186);
  CHECK(mesh.node_set("all").back() == 185);
}

TEST_CASE("Every element is counter-clockwise with positive area and the areas sum to L x H", "[mesh]") {
  for (const StripMeshSpec& spec : assorted_specs()) {
    const Mesh mesh = make_strip_mesh(spec);
    Real total = 0.0;
    bool all_left_turning = true;
    for (const auto& element : mesh.elements) {
      REQUIRE(element.size() == static_cast<std::size_t>(nodes_per_element(mesh.element_type)));
      total += signed_area(mesh, element);
      all_left_turning = all_left_turning && turns_left_at_every_corner(mesh, element);
    }
    CHECK(all_left_turning);
    CHECK(total == Approx(spec.length * spec.height).epsilon(1e-12));
  }
}

TEST_CASE("The diagonal option decides how quads are split into triangles", "[mesh]") {
  StripMeshSpec spec = z2_spec();
  spec.element = ElementType::T3;
  const auto triangles_at = [](const Mesh& mesh, Index node) {
    return std::count_if(mesh.elements.begin(), mesh.elements.end(),
                         [&](const auto& e) { return std::find(e.begin(), e.end(), node) != e.end(); });
  };
  const Index bottom_left = 4;
  const Index first_interior_node = 8;  // column 1, one row above the bottom

  spec.diagonal = Diagonal::Rising;
  CHECK(triangles_at(make_strip_mesh(spec), bottom_left) == 2);
  CHECK(triangles_at(make_strip_mesh(spec), first_interior_node) == 6);

  spec.diagonal = Diagonal::Falling;
  CHECK(triangles_at(make_strip_mesh(spec), bottom_left) == 1);

  spec.diagonal = Diagonal::Alternating;  // union jack centred on the first interior node
  CHECK(triangles_at(make_strip_mesh(spec), bottom_left) == 2);
  CHECK(triangles_at(make_strip_mesh(spec), first_interior_node) == 8);
  CHECK(triangles_at(make_strip_mesh(spec), first_interior_node + 5) == 4);
}

TEST_CASE("Refinement by 2 gives four times the elements and nests the coarse grid", "[mesh]") {
  for (const StripMeshSpec& coarse_spec : assorted_specs()) {
    if (coarse_spec.refine != 1) continue;
    StripMeshSpec fine_spec = coarse_spec;
    fine_spec.refine = 2;
    const Mesh coarse = make_strip_mesh(coarse_spec);
    const Mesh fine = make_strip_mesh(fine_spec);
    CHECK(fine.n_elements() == 4 * coarse.n_elements());
    const std::vector<Real> fine_xs = node_xs(fine);
    const std::vector<Real> fine_ys = node_ys(fine);
    bool nested = true;
    for (const Vec2& p : coarse.nodes) nested = nested && contains(fine_xs, p.x()) && contains(fine_ys, p.y());
    CHECK(nested);
  }
  StripMeshSpec z3 = z3_spec();
  z3.refine = 3;
  const Mesh fine = make_strip_mesh(z3);
  CHECK(fine.n_elements() == 9 * 150);
  CHECK(fine.node_set("top").size() == 91);
  CHECK(coordinates(fine, "top", 0)[3] == 35.0);
  CHECK(coordinates(fine, "top", 0)[1] == Approx(35.0 / 3));
}

TEST_CASE("Uniform grid lines are equally spaced from exactly 0 to exactly the extent", "[mesh]") {
  const std::vector<Real> lines = grid_lines(427.5, 30, Grading{});
  REQUIRE(lines.size() == 31);
  CHECK(lines.front() == 0.0);
  CHECK(lines.back() == 427.5);
  for (const Real h : intervals_of(lines)) CHECK(h == Approx(14.25));
}

TEST_CASE("Geometric grading from an end is a progression with the requested ratio", "[mesh]") {
  const Real extent = 50.0;
  for (const Real focus : {0.0, extent}) {
    const std::vector<Real> lines = grid_lines(extent, 5, geometric(4.0, focus));
    REQUIRE(lines.size() == 6);
    CHECK(lines.front() == 0.0);
    CHECK(lines.back() == extent);
    std::vector<Real> h = intervals_of(lines);
    if (focus == extent) std::reverse(h.begin(), h.end());  // list from the fine end
    CHECK(h.back() / h.front() == Approx(4.0));
    for (std::size_t k = 1; k < h.size(); ++k) CHECK(h[k] / h[k - 1] == Approx(std::pow(4.0, 0.25)));
  }
}

TEST_CASE("Geometric grading around an inside focus is finest and equal on both sides of it", "[mesh]") {
  struct Case {
    Real extent;
    int n;
    Real ratio, focus;
  };
  for (const Case c : {Case{427.5, 30, 3.0, 202.19}, Case{100.0, 11, 5.0, 50.0}, Case{200.0, 20, 8.0, 160.0},
                       Case{225.0, 45, 2.0, 30.0}, Case{10.0, 7, 1.5, 3.3}}) {
    CAPTURE(c.extent, c.n, c.ratio, c.focus);
    const std::vector<Real> lines = grid_lines(c.extent, c.n, geometric(c.ratio, c.focus));
    REQUIRE(lines.size() == static_cast<std::size_t>(c.n) + 1);
    CHECK(lines.front() == 0.0);
    CHECK(lines.back() == c.extent);
    const auto at_focus =
        std::find_if(lines.begin(), lines.end(), [&](Real x) { return std::abs(x - c.focus) < 1e-9 * c.extent; });
    REQUIRE(at_focus != lines.end());
    const std::size_t f = static_cast<std::size_t>(at_focus - lines.begin());
    REQUIRE(f > 0);
    REQUIRE(f < lines.size() - 1);
    const std::vector<Real> h = intervals_of(lines);
    CHECK(h[f - 1] == Approx(h[f]));
    CHECK(max_over_min(h) == Approx(c.ratio));
    for (std::size_t k = 0; k + 1 < f; ++k) CHECK(h[k] >= h[k + 1] * (1.0 - 1e-12));
    for (std::size_t k = f; k + 1 < h.size(); ++k) CHECK(h[k + 1] >= h[k] * (1.0 - 1e-12));
  }
}

TEST_CASE("Geometric grading around the centre is mirror-symmetric", "[mesh]") {
  const std::vector<Real> lines = grid_lines(100.0, 10, geometric(3.0, 50.0));
  for (std::size_t k = 0; k < lines.size(); ++k)
    CHECK(lines[k] == Approx(100.0 - lines[lines.size() - 1 - k]).margin(1e-12));
  CHECK(lines[5] == Approx(50.0));
}

TEST_CASE("A focus about one finest interval from an end grades from that end", "[mesh]") {
  for (const Real focus : {0.1, 3.0}) {
    CAPTURE(focus);
    const std::vector<Real> h = intervals_of(grid_lines(100.0, 10, geometric(4.0, focus)));
    CHECK(max_over_min(h) == Approx(4.0));
    for (std::size_t k = 1; k < h.size(); ++k) CHECK(h[k] / h[k - 1] == Approx(std::pow(4.0, 1.0 / 9)));
  }
  const std::vector<Real> h = intervals_of(grid_lines(100.0, 10, geometric(4.0, 97.0)));
  CHECK(h.front() / h.back() == Approx(4.0));
}

TEST_CASE("The ratio stays exact when one focus side could hold only a single interval", "[mesh]") {
  // A single interval [0, focus] cannot span the ratio, so it must not set the focus spacing.
  for (const Real focus : {1.119, 1.6785, 2.7975}) {
    CAPTURE(focus);
    CHECK(max_over_min(intervals_of(grid_lines(37.3, 10, geometric(10.0, focus)))) == Approx(10.0));
  }
}

TEST_CASE("When counts forbid a common focus spacing each side grades on its own", "[mesh]") {
  // 59 intervals, centred focus, nearly uniform: 29 on one side, 30 on the other.
  const std::vector<Real> lines = grid_lines(100.0, 59, geometric(1.05, 50.0));
  const auto at_focus = std::find_if(lines.begin(), lines.end(), [](Real x) { return std::abs(x - 50.0) < 1e-9; });
  REQUIRE(at_focus != lines.end());
  const std::size_t f = static_cast<std::size_t>(at_focus - lines.begin());
  const std::vector<Real> h = intervals_of(lines);
  CHECK(std::max(h[f - 1], h[f]) / std::min(h[f - 1], h[f]) < 30.0 / 29.0 * 1.001);
  for (std::size_t k = 0; k + 1 < f; ++k) CHECK(h[k] > h[k + 1]);
  for (std::size_t k = f; k + 1 < h.size(); ++k) CHECK(h[k + 1] > h[k]);
}

TEST_CASE("Geometric grading with ratio 1 is uniform", "[mesh]") {
  const std::vector<Real> lines = grid_lines(40.0, 4, geometric(1.0, 13.0));
  CHECK(lines == std::vector<Real>{0.0, 10.0, 20.0, 30.0, 40.0});
}

TEST_CASE("A graded mesh puts its grid lines where grid_lines says", "[mesh]") {
  StripMeshSpec spec = z2_spec();
  spec.grading_x = geometric(4.0, 30.0);
  spec.grading_y = geometric(2.0, 40.0);
  const Mesh mesh = make_strip_mesh(spec);
  const std::vector<Real> xs = grid_lines(100.0, 10, spec.grading_x);
  const std::vector<Real> ys = grid_lines(40.0, 4, spec.grading_y);
  CHECK(coordinates(mesh, "top", 0) == xs);
  CHECK(coordinates(mesh, "left", 1) == ys);
}

TEST_CASE("Explicit grid lines replace nx and the grading", "[mesh]") {
  StripMeshSpec spec = z3_spec();
  spec.nx = 3;
  spec.grading_x = geometric(10.0, 5.0);
  const Mesh mesh = make_strip_mesh(spec);
  CHECK(coordinates(mesh, "top", 0) == spec.x_lines);
  CHECK(coordinates(mesh, "left", 1) == spec.y_lines);
}

TEST_CASE("Explicit lines whose ends are off by round-off are snapped to the strip", "[mesh]") {
  StripMeshSpec spec = z2_spec();
  spec.x_lines = {1e-13, 50.0, 100.0 - 1e-12};
  const Mesh mesh = make_strip_mesh(spec);
  CHECK(coordinates(mesh, "top", 0).front() == 0.0);
  CHECK(coordinates(mesh, "top", 0).back() == 100.0);
}

TEST_CASE("Bad mesh specs are rejected with the offending key in the message", "[mesh]") {
  struct Bad {
    std::function<void(StripMeshSpec&)> spoil;
    std::string key;
  };
  const std::vector<Bad> bad = {
      {[](StripMeshSpec& s) { s.nx = 0; }, "mesh.nx = 0: must be >= 1"},
      {[](StripMeshSpec& s) { s.ny = -2; }, "mesh.ny = -2"},
      {[](StripMeshSpec& s) { s.length = 0.0; }, "mesh.length = 0"},
      {[](StripMeshSpec& s) { s.height = -1.0; }, "mesh.height = -1"},
      {[](StripMeshSpec& s) { s.height = std::nan(""); }, "mesh.height"},
      {[](StripMeshSpec& s) { s.refine = 0; }, "mesh.refine = 0"},
      {[](StripMeshSpec& s) { s.refine = 100000; }, "mesh.refine = 100000"},
      {[](StripMeshSpec& s) { s.grading_x = geometric(0.5, 0.0); }, "mesh.grading_x.ratio = 0.5"},
      {[](StripMeshSpec& s) { s.grading_y = geometric(2.0, 41.0); }, "mesh.grading_y.focus = 41"},
      {[](StripMeshSpec& s) { s.x_lines = {0.0}; }, "mesh.x_lines"},
      {[](StripMeshSpec& s) {
         s.x_lines = {1.0, 100.0};
       },
       "mesh.x_lines[0] = 1"},
      {[](StripMeshSpec& s) {
         s.x_lines = {0.0, 90.0};
       },
       "mesh.x_lines[1] = 90"},
      {[](StripMeshSpec& s) {
         s.y_lines = {0.0, 20.0, 20.0, 40.0};
       },
       "mesh.y_lines[2] = 20"},
      {[](StripMeshSpec& s) { s.element = static_cast<ElementType>(7); }, "mesh.element"},
      {[](StripMeshSpec& s) { s.diagonal = static_cast<Diagonal>(9); }, "mesh.diagonal"},
  };
  for (const Bad& b : bad) {
    CAPTURE(b.key);
    StripMeshSpec spec = z2_spec();
    b.spoil(spec);
    require_spec_rejected(spec, b.key);
  }
  std::string why = "stale";
  CHECK(z2_spec().is_valid(&why));
  CHECK(why.empty());
  CHECK(z2_spec().is_valid(nullptr));
}

TEST_CASE("grid_lines rejects bad arguments with InputError", "[mesh]") {
  CHECK_THROWS_AS(grid_lines(0.0, 4, Grading{}), InputError);
  CHECK_THROWS_WITH(grid_lines(10.0, 0, Grading{}), Catch::Contains("n = 0"));
  CHECK_THROWS_WITH(grid_lines(10.0, 4, geometric(0.9, 0.0)), Catch::Contains("ratio"));
  CHECK_THROWS_WITH(grid_lines(10.0, 4, geometric(2.0, -1.0)), Catch::Contains("focus"));
}

TEST_CASE("An unknown node set name is an InputError listing the known names", "[mesh]") {
  const Mesh mesh = make_strip_mesh(z2_spec());
  CHECK_THROWS_AS(mesh.node_set("middle"), InputError);
  CHECK_THROWS_WITH(mesh.node_set("middle"),
                    Catch::Contains("'middle'") && Catch::Contains("bottom_left") && Catch::Contains("contact"));
  CHECK_THROWS_WITH(mesh.node_set("topp"), Catch::Contains("did you mean 'top'"));
  CHECK_NOTHROW(mesh.node_set("bottom_right"));
}
