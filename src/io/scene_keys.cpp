// The declaration of every scene-file key (include/roller/io/scene_keys.hpp). A plain key is a
// field of the Scene reached by an accessor; its default is that field of a default-constructed
// Scene, its type, range or choices drive reading, checking, writing and listing. Keys with a
// structured shape (ramps, node selectors, gradings, ...) have hand-written readers and writers
// below, declared in the same list. docs/scenes.md documents them for users.
#include "roller/io/scene_keys.hpp"

#include <algorithm>
#include <climits>
#include <cmath>
#include <optional>
#include <stdexcept>
#include <type_traits>
#include <utility>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "layer_keys.hpp"
#include "roller/analysis/hertz.hpp"

namespace roller {

namespace {

// ---- value rules -----------------------------------------------------------------------------

// Allowed interval of a number (bounds inclusive unless open). Written so that NaN fails.
struct Range {
  std::optional<Real> min, max;
  bool min_open = false;
  bool max_open = false;

  bool contains(Real v) const {
    if (min && !(min_open ? v > *min : v >= *min)) return false;
    if (max && !(max_open ? v < *max : v <= *max)) return false;
    return true;
  }
  // "> 0", ">= 1", "0 <= nu < 0.5"; "" for any value.
  std::string text(const std::string& name) const {
    if (min && max)
      return fmt::format("{} {} {} {} {}", *min, min_open ? "<" : "<=", name, max_open ? "<" : "<=", *max);
    if (min) return fmt::format("{} {}", min_open ? ">" : ">=", *min);
    if (max) return fmt::format("{} {}", max_open ? "<" : "<=", *max);
    return "";
  }
  std::string rule(const std::string& name) const {
    return (min && max ? "must satisfy " : "must be ") + text(name) + (hint.empty() ? "" : "; " + hint);
  }
  std::string hint;  // the likely slip of units beyond the bounds
};

Range at_least(Real v) { return {v, std::nullopt, false, false, {}}; }
Range above(Real v) { return {v, std::nullopt, true, false, {}}; }
Range closed(Real lo, Real hi) { return {lo, hi, false, false, {}}; }
Range open(Real lo, Real hi) { return {lo, hi, true, true, {}}; }
Range right_open(Real lo, Real hi) { return {lo, hi, false, true, {}}; }
Range with_hint(Range r, std::string hint) {
  r.hint = std::move(hint);
  return r;
}

// Plausibility bounds in scene units (mm, N, MPa, s, t) for quantities that have no natural
// upper limit: far beyond any strip, roller or material (E 1e9 MPa is 800 times diamond's), yet
// small enough that the solvers' products of them (E* l^2, c/dt, k R) stay finite; values
// outside them were found by fuzzing to overflow into NaN or into Ipopt options of 0.
constexpr Real kMaxLength = 1e9;    // mm
constexpr Real kMinLength = 1e-6;   // mm
constexpr Real kMaxModulus = 1e9;   // MPa
constexpr Real kMinModulus = 1e-6;  // MPa (1 Pa: below foams; 1e-308 underflowed the stresses)
// A fatigue limit above any metal's strength (steels' shear fatigue limits are a few hundred MPa):
// a larger value is one in Pa.
constexpr Real kMaxFatigueLimit = 1e4;  // MPa
constexpr Real kMaxDensity = 1e-3;      // t/mm^3 (osmium: 2.3e-8)
constexpr Real kMaxTime = 1e9;          // s
// A nanosecond is far below any step of a rolling or impact scene (Z4: 1e-6 s); at dt = 1e-308
// the inertia M/dt^2 overflowed and the contact solve failed without naming dt.
constexpr Real kMinTime = 1e-12;       // s
constexpr Real kMaxSuspension = 1e12;  // t, N s/mm, N/mm per mm
constexpr Real kMaxForce = 1e15;       // N per mm
// Sub-steps of the thesis's stress integration: its error falls as 1/n, 100 are past any use, and
// 1e6 kept a run busy for hours.
constexpr Real kMaxSubsteps = 1000;

// Lengths of the roller and of the motions, measured against the strip's size S = max(length,
// height): the absolute bounds above let a 1e9 mm roller onto a 10 mm strip, where the gap
// |x - c| - R loses every digit the element size needs. A displacement, a travel or the roller's
// distance from the strip may be kMaxReach S; the radius lies within kRadiusRatio^(+-1) S (the
// bar-impact striker is a 1e7 mm roller, 5e4 S, standing in for a flat face).
constexpr Real kMaxReach = 1e3;
constexpr Real kRadiusRatio = 1e6;

Real strip_size(const Scene& scene) { return std::max(scene.mesh.length, scene.mesh.height); }

// Fails at `key` unless |value| <= ratio S.
void check_reach(TomlSection& s, const Scene& scene, const std::string& key, Real value, Real ratio = kMaxReach) {
  const Real size = strip_size(scene);
  if (!(std::abs(value) <= ratio * size))
    s.fail(key, fmt::format("must be within +-{:g} times the strip's size max(mesh.length, mesh.height) = {:g} mm, "
                            "i.e. |value| <= {:g} mm",
                            ratio, size, ratio * size));
}

void check_roller_scale(TomlSection& s, const Scene& scene) {
  const RollerSpec& r = *scene.roller;
  const Real size = strip_size(scene);
  if (!(r.radius >= size / kRadiusRatio && r.radius <= size * kRadiusRatio))
    s.fail("radius", fmt::format("must lie within {:g} and {:g} times the strip's size max(mesh.length, "
                                 "mesh.height) = {:g} mm, i.e. {:g} <= radius <= {:g} mm",
                                 1.0 / kRadiusRatio, kRadiusRatio, size, size / kRadiusRatio, size * kRadiusRatio));
  if (r.start_centre) {
    // Distance from the roller's surface to the strip's rectangle [0, L] x [0, H].
    const Vec2 c = *r.start_centre;
    const Real dx = std::max({0.0, -c.x(), c.x() - scene.mesh.length});
    const Real dy = std::max({0.0, -c.y(), c.y() - scene.mesh.height});
    const Real gap = std::hypot(dx, dy) - r.radius;
    if (!(gap <= kMaxReach * size))
      s.fail("centre", fmt::format("the roller starts {:g} mm away from the strip: at most {:g} times the strip's "
                                   "size max(mesh.length, mesh.height) = {:g} mm",
                                   gap, kMaxReach, size));
  }
}

// What a value must satisfy: a range (numbers) or a list of choices (strings).
struct Rule {
  Rule() = default;
  Rule(Range r) : range(std::move(r)) {}  // NOLINT: a range is a rule
  Range range;
  std::vector<std::string> choices;
};

Rule one_of(std::vector<std::string> choices) {
  Rule r;
  r.choices = std::move(choices);
  return r;
}

std::string choices_text(const std::vector<std::string>& choices) {
  std::string out;
  for (const auto& c : choices) out += (out.empty() ? "\"" : " | \"") + c + "\"";
  return out;
}

// ---- value types: Real, int, bool, std::string, std::vector<Real> and option enums -----------

template <class T>
std::string type_name() {
  if constexpr (std::is_same_v<T, Real>)
    return "number";
  else if constexpr (std::is_same_v<T, int>)
    return "integer";
  else if constexpr (std::is_same_v<T, bool>)
    return "bool";
  else if constexpr (std::is_same_v<T, std::string>)
    return "string";
  else if constexpr (std::is_same_v<T, std::vector<Real>>)
    return "array of numbers";
  else {
    static_assert(std::is_enum_v<T>, "a scene key is a number, integer, bool, string, array or enum");
    return "choice";
  }
}

template <class T>
std::string value_text(const T& v) {
  if constexpr (std::is_same_v<T, bool>)
    return v ? "true" : "false";
  else if constexpr (std::is_same_v<T, std::string>)
    return fmt::format("\"{}\"", v);
  else if constexpr (std::is_same_v<T, std::vector<Real>>)
    return fmt::format("[{}]", fmt::join(v, ", "));
  else if constexpr (std::is_enum_v<T>)
    return fmt::format("\"{}\"", enum_name(v));
  else
    return fmt::format("{}", v);
}

template <class T>
void insert(toml::table& t, const std::string& name, const T& v) {
  if constexpr (std::is_same_v<T, int>)
    t.insert(name, static_cast<int64_t>(v));
  else if constexpr (std::is_same_v<T, std::vector<Real>>) {
    toml::array a;
    for (Real x : v) a.push_back(x);
    t.insert(name, a);
  } else if constexpr (std::is_enum_v<T>)
    t.insert(name, std::string(enum_name(v)));
  else
    t.insert(name, v);
}

// Reads and checks one value; nullopt when the key is absent.
template <class T>
std::optional<T> read_value(TomlSection& s, const std::string& name, const Rule& rule) {
  if constexpr (std::is_same_v<T, Real>) {
    const auto v = s.real(name);
    if (v && !rule.range.contains(*v)) s.fail(name, rule.range.rule(name));
    return v;
  } else if constexpr (std::is_same_v<T, int>) {
    const auto v = s.integer(name);  // 64-bit: checked before it is narrowed
    if (!v) return std::nullopt;
    if (!rule.range.contains(static_cast<Real>(*v))) s.fail(name, rule.range.rule(name));
    if (*v < INT_MIN || *v > INT_MAX) s.fail(name, fmt::format("must satisfy {} <= {} <= {}", INT_MIN, name, INT_MAX));
    return static_cast<int>(*v);
  } else if constexpr (std::is_same_v<T, bool>) {
    return s.boolean(name);
  } else if constexpr (std::is_same_v<T, std::string>) {
    return rule.choices.empty() ? s.string(name) : s.choice(name, rule.choices);
  } else if constexpr (std::is_same_v<T, std::vector<Real>>) {
    return s.real_array(name);
  } else {
    const auto v = s.choice(name, enum_names<T>());
    if (!v) return std::nullopt;
    return parse_enum<T>(*v);
  }
}

// material.chaboche_C and chaboche_gamma: two arrays of one length, read together.
void read_chaboche(TomlSection& s, Scene& scene) {
  const auto c = s.real_array("chaboche_C");
  const auto gamma = s.real_array("chaboche_gamma");
  if (!c) return;
  if (!scene.material.plastic) s.fail("chaboche_C", "back-stresses need yield_stress (set it, or remove this key)");
  if (scene.material.hardening != Hardening::Chaboche)
    s.fail("chaboche_C", "back-stresses need hardening = \"chaboche\"");
  if (c->empty() || c->size() > static_cast<std::size_t>(kMaxBackStresses))
    s.fail("chaboche_C", fmt::format("must hold 1 to {} moduli (one per back-stress)", kMaxBackStresses));
  if (!gamma || gamma->size() != c->size())
    s.fail(gamma ? "chaboche_gamma" : "chaboche_C",
           fmt::format("chaboche_gamma must hold one recovery per modulus ({} values, like chaboche_C)", c->size()));
  scene.material.n_chaboche = static_cast<int>(c->size());
  for (std::size_t i = 0; i < c->size(); ++i) scene.material.chaboche[i] = {(*c)[i], (*gamma)[i]};
}

void write_chaboche(toml::table& t, const Scene& scene) {
  const MaterialParams& m = scene.material;
  if (!m.plastic || m.hardening != Hardening::Chaboche) return;
  toml::array c, gamma;
  for (int i = 0; i < m.n_chaboche; ++i) {
    c.push_back(m.chaboche[static_cast<std::size_t>(i)].modulus);
    gamma.push_back(m.chaboche[static_cast<std::size_t>(i)].recovery);
  }
  t.insert("chaboche_C", c);
  t.insert("chaboche_gamma", gamma);
}

// ---- declarations ----------------------------------------------------------------------------

// roller.path.p0 / p0_over_k: the segment's vertical force in the users' terms, converted to fy
// with Hertz's line contact on the strip's plane-strain modulus (the roller rigid), the formula
// kept for the resolved scene. Needs the [material] read before the [roller].
void read_load_as_pressure(TomlSection& s, Scene& scene, std::size_t i, const char* key) {
  const std::optional<Real> value = s.real(key);
  if (!value) return;
  PathSegment& seg = scene.roller->path[i];
  if (!(*value > 0.0 && *value < 1e6)) s.fail(key, "expected a value > 0 (and below 1e6)");
  if (seg.fy || s.has("fy") || (std::string(key) == "p0_over_k" && s.has("p0")))
    s.fail(key, "give the segment's vertical force once: fy [N/mm], p0 [MPa] or p0_over_k");
  const MaterialParams& m = scene.material;
  const Real e_star = scene.contact_modulus();
  const Real radius = scene.roller->radius;
  Real p0 = *value;
  std::string how = fmt::format("p0 = {:g} MPa", p0);
  if (std::string(key) == "p0_over_k") {
    if (!m.plastic) s.fail(key, "p0/k needs a yield stress: give material.yield_stress (k = yield_stress/sqrt(3))");
    const Real k = m.yield_stress / std::sqrt(3.0);
    p0 = *value * k;
    how = fmt::format("p0_over_k = {:g}: k = yield_stress/sqrt(3) = {:.6g} MPa, p0 = {:.6g} MPa", *value, k, p0);
  }
  seg.fy = hertz_line_load(p0, radius, e_star);
  seg.fy_origin =
      fmt::format("{}; fy = pi R p0^2 / E* with R = {:g} mm, E* = E/(1 - nu^2) = {:.6g} MPa", how, radius, e_star);
}

// A scene with one of everything optional, for the defaults of keys inside them.
const Scene& default_scene() {
  static const Scene scene = [] {
    Scene s;
    s.roller.emplace();
    s.roller->suspension.emplace();
    s.roller->path.emplace_back();
    s.displacements.emplace_back();
    s.loads.emplace_back();
    return s;
  }();
  return scene;
}

std::pair<std::string, std::string> split_dotted(const std::string& dotted) {
  const auto dot = dotted.rfind('.');
  if (dot == std::string::npos) return {"", dotted};
  return {dotted.substr(0, dot), dotted.substr(dot + 1)};
}

// A key under construction; the modifiers adjust how it is read, written or listed.
struct Decl {
  SceneKey key;

  // Absent is an error saying what the key holds.
  Decl&& required(const std::string& message) && {
    key.read = [read = std::move(key.read), name = key.name, message](TomlSection& s, Scene& scene, std::size_t block) {
      if (!s.has(name)) s.fail(name, message);
      read(s, scene, block);
    };
    key.default_text = "required";
    return std::move(*this);
  }
  // Absent: `fill` sets a default that depends on other keys (listed as `text`).
  Decl&& when_absent(const std::string& text, std::function<void(Scene&)> fill) && {
    key.read = [read = std::move(key.read), name = key.name, fill](TomlSection& s, Scene& scene, std::size_t block) {
      if (s.has(name))
        read(s, scene, block);
      else
        fill(scene);
    };
    key.default_text = text;
    return std::move(*this);
  }
  // Written to the resolved scene only when `keep` holds (it means nothing otherwise).
  Decl&& written_if(std::function<bool(const Scene&)> keep) && {
    key.write = [write = std::move(key.write), keep](toml::table& t, const Scene& scene, std::size_t block) {
      if (keep(scene)) write(t, scene, block);
    };
    return std::move(*this);
  }
  Decl&& shown_default(const std::string& text) && {
    key.default_text = text;
    return std::move(*this);
  }
  operator SceneKey() && { return std::move(key); }  // NOLINT: a finished declaration
};

// A key that is one field of the scene, read and written through get/set.
template <class T>
Decl field(const std::string& dotted, std::function<T(const Scene&, std::size_t)> get,
           std::function<void(Scene&, std::size_t, const T&)> set, const std::string& doc, const Rule& rule) {
  Decl d;
  SceneKey& k = d.key;
  std::tie(k.table, k.name) = split_dotted(dotted);
  const bool choice = std::is_enum_v<T> || !rule.choices.empty();
  k.type = choice ? "choice" : type_name<T>();
  k.default_text = value_text(get(default_scene(), 0));
  if constexpr (std::is_enum_v<T>)
    k.range = choices_text(enum_names<T>());
  else
    k.range = choice ? choices_text(rule.choices) : rule.range.text(k.name);
  k.doc = doc;
  k.read = [name = k.name, set, rule](TomlSection& s, Scene& scene, std::size_t block) {
    if (auto v = read_value<T>(s, name, rule)) set(scene, block, *v);
  };
  k.write = [name = k.name, get](toml::table& t, const Scene& scene, std::size_t block) {
    insert(t, name, get(scene, block));
  };
  return d;
}

// A key that is one field of the scene, reached by `access`: a generic lambda returning a
// reference, `[](auto& s) -> auto& { return s.mesh.nx; }`, or in an array of tables
// `[](auto& s, std::size_t i) -> auto& { return s.roller->path[i].dx; }`.
template <class Access>
Decl key(const std::string& dotted, Access access, const std::string& doc, const Rule& rule = {}) {
  if constexpr (std::is_invocable_v<Access, const Scene&, std::size_t>) {
    using T = std::decay_t<std::invoke_result_t<Access, const Scene&, std::size_t>>;
    return field<T>(
        dotted, [access](const Scene& s, std::size_t i) { return access(s, i); },
        [access](Scene& s, std::size_t i, const T& v) { access(s, i) = v; }, doc, rule);
  } else {
    using T = std::decay_t<std::invoke_result_t<Access, const Scene&>>;
    return field<T>(
        dotted, [access](const Scene& s, std::size_t) { return access(s); },
        [access](Scene& s, std::size_t, const T& v) { access(s) = v; }, doc, rule);
  }
}

// A key with a structured shape and its own reader and writer.
Decl custom(const std::string& dotted, const std::string& type, const std::string& default_text,
            const std::string& range, const std::string& doc,
            std::function<void(TomlSection&, Scene&, std::size_t)> read,
            std::function<void(toml::table&, const Scene&, std::size_t)> write) {
  Decl d;
  std::tie(d.key.table, d.key.name) = split_dotted(dotted);
  d.key.type = type;
  d.key.default_text = default_text;
  d.key.range = range;
  d.key.doc = doc;
  d.key.read = std::move(read);
  d.key.write = std::move(write);
  return d;
}

void write_nothing(toml::table&, const Scene&, std::size_t) {}

// A step number written as a TOML number: an integer in 1..INT_MAX (checked before the cast).
bool is_step(Real v) { return v >= 1 && v <= INT_MAX && v == std::floor(v); }

toml::array pair_array(Real a, Real b) { return toml::array{a, b}; }

// ---- structured keys -------------------------------------------------------------------------

Grading read_grading(TomlSection& s, const std::string& key) {
  Grading g;
  auto t = s.table(key);
  if (!t) return g;
  g.kind = Grading::Kind::Geometric;
  t->allow({"ratio", "focus"});
  t->finish();
  g.ratio = t->real_or("ratio", 1.0);
  g.focus = t->real_or("focus", 0.0);
  if (!(g.ratio >= 1.0)) t->fail("ratio", "expected ratio >= 1 (largest over smallest interval)");
  return g;
}

void write_grading(toml::table& t, const std::string& key, const Grading& g) {
  if (g.kind == Grading::Kind::Geometric) t.insert(key, toml::table{{"ratio", g.ratio}, {"focus", g.focus}});
}

// { history = [[step, value], ...] }: steps whole, >= 1 and increasing; values within the bound.
void read_history(TomlSection& t, Real bound, Ramp& r) {
  if (t.has("value") || t.has("ramp")) t.fail("history", "give either history or value/ramp, not both");
  const toml::node* n = t.node("history");
  const toml::array* rows = n ? n->as_array() : nullptr;
  const std::string expected =
      fmt::format("expected [[step, value], ...]: whole steps >= 1, increasing, |value| <= {:g}", bound);
  if (!rows || rows->empty()) t.fail("history", expected);
  Real last_step = 0.0;
  for (const toml::node& row : *rows) {
    const toml::array* pair = row.as_array();
    if (!pair || pair->size() != 2) t.fail("history", expected);
    const auto step = (*pair)[0].value<double>();
    const auto value = (*pair)[1].value<double>();
    if (!step || !value || !is_step(*step) || *step <= last_step || !(std::abs(*value) <= bound))
      t.fail("history", expected);
    r.history.push_back({*step, *value});
    last_step = *step;
  }
}

// `bound`: the plausibility bound of |value| (a displacement or a force).
Ramp read_ramp(TomlSection& s, const std::string& key, int n_steps, Real bound) {
  const toml::node* n = s.node(key);
  Ramp r;
  r.ramp_first = 1;
  r.ramp_last = 1;
  const std::string expected = fmt::format("expected |value| <= {:g} (a plausibility bound)", bound);
  if (n->is_number()) {  // a constant: reached at once and held
    r.value = *s.real(key);
    if (!(std::abs(r.value) <= bound)) s.fail(key, expected);
    return r;
  }
  auto t = s.table(key);
  if (!t)
    s.fail(key,
           "expected a number, { value = .., ramp = [first_step, last_step] } or { history = [[step, value], ...] }");
  t->allow({"value", "ramp", "history"});
  t->finish();
  if (t->has("history")) {
    read_history(*t, bound, r);
    return r;
  }
  const auto v = t->real("value");
  if (!v) t->fail("value", "the value reached at the end of the ramp is required");
  if (!(std::abs(*v) <= bound)) t->fail("value", expected);
  r.value = *v;
  if (auto steps = t->real_array("ramp")) {
    if (steps->size() != 2 || !is_step((*steps)[0]) || !is_step((*steps)[1]) || (*steps)[1] < (*steps)[0])
      t->fail("ramp", "expected [first_step, last_step] with 1 <= first_step <= last_step");
    r.ramp_first = static_cast<int>((*steps)[0]);
    r.ramp_last = static_cast<int>((*steps)[1]);
  } else {
    r.ramp_last = n_steps;  // default: linear over the whole run
  }
  return r;
}

// A ramp key of a [[displacement]] or [[load]] block (`ramp` selects the member).
template <class Block>
Decl ramp_key(const std::string& dotted, std::vector<Block> Scene::*blocks, std::optional<Ramp> Block::*ramp,
              Real bound, const std::string& doc) {
  const std::string name = split_dotted(dotted).second;
  return custom(
      dotted, "number or ramp table", "absent (free)", fmt::format("|value| <= {:g}", bound), doc,
      [=](TomlSection& s, Scene& scene, std::size_t i) {
        if (s.has(name)) ((scene.*blocks)[i].*ramp) = read_ramp(s, name, scene.total_steps(), bound);
      },
      [=](toml::table& t, const Scene& scene, std::size_t i) {
        if (const auto& r = (scene.*blocks)[i].*ramp; r && !r->history.empty()) {
          toml::array rows;
          for (const auto& [step, value] : r->history) rows.push_back(toml::array{static_cast<int64_t>(step), value});
          t.insert(name, toml::table{{"history", rows}});
        } else if (r)
          t.insert(name, toml::table{{"value", r->value},
                                     {"ramp", toml::array{static_cast<int64_t>(r->ramp_first),
                                                          static_cast<int64_t>(r->ramp_last)}}});
      });
}

NodeSelector read_selector(TomlSection& s) {
  NodeSelector sel;
  const toml::node* n = s.node("nodes");
  if (!n) s.fail("nodes", "required: a node set name (\"top\", \"left\", ...) or thesis node numbers [5, 101]");
  if (auto name = n->value_exact<std::string>()) {
    sel.set_name = *name;
  } else if (n->is_table()) {
    auto t = s.table("nodes");
    t->allow({"near"});
    t->finish();
    const auto p = t->real_array("near");
    if (!p || p->size() != 2) t->fail("near", "expected { near = [x, y] }: the node nearest to that point");
    sel.near = Vec2((*p)[0], (*p)[1]);
  } else if (const toml::array* arr = n->as_array()) {
    for (const auto& item : *arr) {
      auto i = item.value_exact<int64_t>();
      if (!i) s.fail("nodes", "expected an array of integer node numbers (1-based, thesis numbering)");
      sel.numbers.push_back(*i);
    }
    if (sel.numbers.empty()) s.fail("nodes", "the node list is empty");
  } else {
    s.fail("nodes", "expected a node set name, an array of node numbers, or { near = [x, y] }");
  }
  return sel;
}

void write_selector(toml::table& t, const NodeSelector& s) {
  if (s.near) {
    t.insert("nodes", toml::table{{"near", pair_array(s.near->x(), s.near->y())}});
  } else if (s.numbers.empty()) {
    t.insert("nodes", s.set_name);
  } else {
    toml::array a;
    for (Index n : s.numbers) a.push_back(static_cast<int64_t>(n));
    t.insert("nodes", a);
  }
}

template <class Block>
Decl nodes_key(const std::string& dotted, std::vector<Block> Scene::*blocks) {
  return custom(
      dotted, "set name | [numbers] | { near = [x, y] }", "required", "",
      "which nodes: a set (\"bottom\", \"top+right\"), thesis node numbers, or the node nearest to a point",
      [=](TomlSection& s, Scene& scene, std::size_t i) { (scene.*blocks)[i].nodes = read_selector(s); },
      [=](toml::table& t, const Scene& scene, std::size_t i) { write_selector(t, (scene.*blocks)[i].nodes); });
}

void read_ipopt_options(TomlSection& s, Scene& scene, std::size_t) {
  auto raw = s.table("options");
  if (!raw) return;
  // Any Ipopt option, passed through (checked by Ipopt when the backend is built).
  for (const std::string& key : raw->keys()) {
    const toml::node* v = raw->node(key);
    // Options naming files or libraries would let a scene file write, truncate or load any file
    // of the machine: refused (docs/scenes.md, Ipopt's options).
    if (key == "output_file" || key == "option_file_name" || key.find("file_name") != std::string::npos ||
        (key.size() > 3 && key.compare(key.size() - 3, 3, "lib") == 0))
      raw->fail(key,
                "not passed through: an option naming a file or a library is refused (a scene writes only into its "
                "output folder); Ipopt's log goes to the terminal with contact.ipopt.print_level");
    if (key == "linear_solver")  // set per NLP by roller (contact/ipopt/ipopt_common.cpp, kkt_linear_solver)
      raw->fail(key,
                "not passed through: roller chooses Ipopt's linear solver per NLP; use contact.ipopt.kkt_solver = "
                "\"auto\", \"dense\" or \"mumps\"");
    RawIpoptOption r{key, RawIpoptOption::Kind::String, ""};
    if (v->is_integer()) {
      r.kind = RawIpoptOption::Kind::Integer;
      r.text = std::to_string(v->value<int64_t>().value());
    } else if (v->is_floating_point()) {
      r.kind = RawIpoptOption::Kind::Number;
      r.text = fmt::format("{:.17g}", *raw->real(key));  // finite (TomlSection::real)
    } else if (v->is_boolean()) {
      r.text = v->value<bool>().value() ? "yes" : "no";
    } else if (v->is_string()) {
      r.text = v->value<std::string>().value();
    } else {
      raw->fail(key, "expected a string, integer, number or boolean (an Ipopt option value)");
    }
    scene.contact.ipopt.raw.push_back(r);
  }
  raw->finish();
}

void write_ipopt_options(toml::table& t, const Scene& scene, std::size_t) {
  toml::table raw_options;
  for (const RawIpoptOption& r : scene.contact.ipopt.raw) {
    if (r.kind == RawIpoptOption::Kind::Integer)
      raw_options.insert(r.name, std::stoll(r.text));
    else if (r.kind == RawIpoptOption::Kind::Number)
      raw_options.insert(r.name, std::stod(r.text));
    else
      raw_options.insert(r.name, r.text);
  }
  t.insert("options", raw_options);
}

bool plastic(const Scene& s) { return s.material.plastic; }

// ---- the keys --------------------------------------------------------------------------------

std::vector<SceneKey> make_keys() {
  using Ref = std::size_t;  // block index of keys in arrays of tables
  std::vector<SceneKey> keys{
      // The root.
      key(
          "name", [](auto& s) -> auto& { return s.name; }, "name of the run, used for the output folder out/<name>")
          .when_absent("file stem", [](Scene& s) { s.name = s.file.stem().string(); }),
      key(
          "title", [](auto& s) -> auto& { return s.title; }, "one-line description")
          .written_if([](const Scene& s) { return !s.title.empty(); }),
      key(
          "kinematics", [](auto& s) -> auto& { return s.element.kinematics; },
          "finite: updated Lagrangian, Green-Lagrange strain, geometric stiffness (thesis LARGE); "
          "small: linear strain on the initial mesh (thesis INFINI)"),

      // [material], read before [mesh]: the Q4 default depends on plasticity.
      key(
          "material.E", [](auto& s) -> auto& { return s.material.youngs_modulus; }, "Young's modulus [MPa]",
          with_hint(closed(kMinModulus, kMaxModulus),
                    "E in Pa? roller works in MPa (steel: E = 2.1e5, that is 2.1e11 Pa)"))
          .required("Young's modulus E [MPa] is required"),
      key(
          "material.nu", [](auto& s) -> auto& { return s.material.poisson_ratio; }, "Poisson's ratio",
          right_open(0.0, 0.5)),
      key(
          "material.density", [](auto& s) -> auto& { return s.material.density; },
          "density [t/mm^3] (steel 7.8e-9), needed by strip inertia", closed(0.0, kMaxDensity)),
      custom(
          "material.yield_stress", "number", "absent = elastic", "> 0",
          "initial yield stress sigma_y0 [MPa]; its presence makes the material J2-plastic",
          [](TomlSection& s, Scene& scene, Ref) {
            const auto yield = s.real("yield_stress");
            scene.material.plastic = yield.has_value();
            if (yield) scene.material.yield_stress = *yield;
          },
          [](toml::table& t, const Scene& scene, Ref) {
            if (scene.material.plastic) t.insert("yield_stress", scene.material.yield_stress);
          }),
      custom(
          "material.tangent_modulus", "number", "0", "0 <= E_T < E",
          "slope E_T of the bilinear uniaxial curve after yield [MPa] (or kappa)",
          [](TomlSection& s, Scene& scene, Ref) {
            const auto et = s.real("tangent_modulus");
            if (et && !scene.material.plastic)
              s.fail("tangent_modulus", "hardening needs yield_stress (set it, or remove this key)");
            if (et) scene.material.tangent_modulus = *et;
          },
          [](toml::table& t, const Scene& scene, Ref) {
            if (scene.material.plastic) t.insert("tangent_modulus", scene.material.tangent_modulus);
          }),
      custom(
          "material.kappa", "number", "absent", "0 <= kappa < 1",
          "the thesis's hardening parameter kappa = E_T/E, instead of tangent_modulus (written as tangent_modulus)",
          [](TomlSection& s, Scene& scene, Ref) {
            const auto kappa = s.real("kappa");
            if (!kappa) return;
            if (!scene.material.plastic) s.fail("kappa", "hardening needs yield_stress (set it, or remove this key)");
            if (s.has("tangent_modulus")) s.fail("kappa", "give either tangent_modulus or kappa = E_T/E, not both");
            if (!(*kappa >= 0.0 && *kappa < 1.0)) s.fail("kappa", "must satisfy 0 <= kappa < 1");
            scene.material.tangent_modulus = *kappa * scene.material.youngs_modulus;
          },
          write_nothing),
      key(
          "material.stress_integration", [](auto& s) -> auto& { return s.material.integration; },
          "return_mapping: radial return with the consistent tangent; substep: the thesis's sub-stepped "
          "continuum tangent")
          .written_if(plastic),
      key(
          "material.substeps", [](auto& s) -> auto& { return s.material.n_substeps; },
          "sub-steps of the substep integration", closed(1, kMaxSubsteps))
          .written_if(plastic),
      key(
          "material.hardening", [](auto& s) -> auto& { return s.material.hardening; },
          "isotropic: yield surface grows (H' from tangent_modulus); kinematic: it moves (Prager, C = H'); "
          "mixed: a kinematic_fraction of H' moves it; chaboche: back-stresses chaboche_C/chaboche_gamma")
          .written_if(plastic),
      key(
          "material.kinematic_fraction", [](auto& s) -> auto& { return s.material.kinematic_fraction; },
          "mixed hardening: the share m of H' that is kinematic (the rest isotropic)", closed(0.0, 1.0))
          .written_if([](const Scene& s) { return s.material.plastic && s.material.hardening == Hardening::Mixed; }),
      custom(
          "material.chaboche_C", "array of numbers", "absent", "1 to 4 values >= 0",
          "moduli C_i [MPa] of the Chaboche back-stresses (hardening = \"chaboche\")",
          [](TomlSection& s, Scene& scene, Ref) { read_chaboche(s, scene); },
          [](toml::table& t, const Scene& scene, Ref) { write_chaboche(t, scene); }),
      custom(
          "material.chaboche_gamma", "array of numbers", "absent", "one value >= 0 per chaboche_C",
          "recovery gamma_i [-] of each back-stress (0: linear; > 0: Armstrong-Frederick, saturating at C_i/gamma_i)",
          [](TomlSection& s, Scene&, Ref) {
            if (s.has("chaboche_gamma") && !s.has("chaboche_C"))
              s.fail("chaboche_gamma", "needs chaboche_C (one modulus per recovery)");
          },
          write_nothing),
      key(
          "material.voce_Q", [](auto& s) -> auto& { return s.material.voce_saturation; },
          "Voce isotropic term Q (1 - exp(-b eps_p)): saturation Q [MPa], < 0 for cyclic softening "
          "(yield_stress + Q > 0)",
          closed(-kMaxModulus, kMaxModulus))
          .written_if([](const Scene& s) { return s.material.plastic && s.material.voce_saturation != 0.0; }),
      key(
          "material.voce_b", [](auto& s) -> auto& { return s.material.voce_rate; }, "Voce rate b [-]", closed(0.0, 1e6))
          .written_if([](const Scene& s) { return s.material.plastic && s.material.voce_saturation != 0.0; }),

      // [mesh]
      key(
          "mesh.element", [](auto& s) -> auto& { return s.mesh.element; },
          "bilinear quads (2x2 Gauss) or linear triangles (each quad split in two)"),
      key(
          "mesh.length", [](auto& s) -> auto& { return s.mesh.length; }, "strip length L_s [mm]",
          closed(kMinLength, kMaxLength)),
      key(
          "mesh.height", [](auto& s) -> auto& { return s.mesh.height; }, "half-thickness H [mm]",
          closed(kMinLength, kMaxLength)),
      key(
          "mesh.nx", [](auto& s) -> auto& { return s.mesh.nx; }, "elements along x before refinement", at_least(1)),
      key(
          "mesh.ny", [](auto& s) -> auto& { return s.mesh.ny; }, "elements along y before refinement", at_least(1)),
      key(
          "mesh.refine", [](auto& s) -> auto& { return s.mesh.refine; },
          "every interval split into refine equal parts (--refine)", at_least(1)),
      key(
          "mesh.periodic", [](auto& s) -> auto& { return s.mesh.periodic; },
          "the right edge is the left edge: the strip repeats along x with period length (an endless track, a "
          "ring's rolled surface; no track ends)"),
      custom(
          "mesh.grading_x", "{ ratio, focus }", "uniform", "ratio >= 1",
          "geometric grading along x: largest/smallest interval ratio, finest at coordinate focus",
          [](TomlSection& s, Scene& scene, Ref) { scene.mesh.grading_x = read_grading(s, "grading_x"); },
          [](toml::table& t, const Scene& scene, Ref) { write_grading(t, "grading_x", scene.mesh.grading_x); }),
      custom(
          "mesh.grading_y", "{ ratio, focus }", "uniform", "ratio >= 1", "geometric grading along y, as grading_x",
          [](TomlSection& s, Scene& scene, Ref) { scene.mesh.grading_y = read_grading(s, "grading_y"); },
          [](toml::table& t, const Scene& scene, Ref) { write_grading(t, "grading_y", scene.mesh.grading_y); }),
      key(
          "mesh.x_lines", [](auto& s) -> auto& { return s.mesh.x_lines; },
          "explicit grid lines from 0 to length, strictly increasing; replace nx and grading_x")
          .written_if([](const Scene& s) { return !s.mesh.x_lines.empty(); })
          .shown_default("absent"),
      key(
          "mesh.y_lines", [](auto& s) -> auto& { return s.mesh.y_lines; },
          "explicit grid lines from 0 to height, strictly increasing; replace ny and grading_y")
          .written_if([](const Scene& s) { return !s.mesh.y_lines.empty(); })
          .shown_default("absent"),
      key(
          "mesh.diagonal", [](auto& s) -> auto& { return s.mesh.diagonal; }, "how T3 split the quads"),
      key(
          "mesh.q4_formulation", [](auto& s) -> auto& { return s.element.q4; },
          "B-bar (volumetric strain averaged over the element) or full integration")
          .when_absent("\"bbar\" if plastic, else \"standard\"",
                       [](Scene& s) {
                         // Full-integration Q4 locks under isochoric plastic flow: B-bar is the plastic default.
                         s.element.q4 =
                             s.strip_material().any_plastic() ? Q4Formulation::BBar : Q4Formulation::Standard;
                       }),

      // [steps]
      key(
          "steps.count", [](auto& s) -> auto& { return s.steps.n_steps; },
          "number of steps (of one pass with [passes]); fields are written at the end of steps (--steps)",
          closed(1, 1e7)),
      key(
          "steps.dt", [](auto& s) -> auto& { return s.steps.dt; }, "time step [s]", closed(kMinTime, kMaxTime)),
      key(
          "steps.max_cuts", [](auto& s) -> auto& { return s.steps.max_cuts; },
          "a failed step is split in 2, 4, ... up to 2^max_cuts sub-increments", closed(0, 20)),

      // [passes]
      key(
          "passes.count", [](auto& s) -> auto& { return s.passes.count; },
          "passes of the roller: steps 1..steps.count and the path are one pass, repeated", closed(1, 1e4)),
      key(
          "passes.direction", [](auto& s) -> auto& { return s.passes.direction; },
          "same: every pass from the same start; alternate: every second pass back, the path mirrored in x"),
      key(
          "passes.method", [](auto& s) -> auto& { return s.passes.method; },
          "transient: each pass marched over the steps; stationary: each pass solved as the steady state in the "
          "roller's frame, one step a pass (small strain, quasi-static; docs/model.md)"),
      key(
          "passes.stationary_contact", [](auto& s) -> auto& { return s.passes.stationary_contact; },
          "the stationary pass's load: roller, the rigid roller's contact with its exact gap solved in every "
          "iteration (the problem a transient pass marches); hertz, a Hertz pressure of the travel force moving "
          "over the strip (Johnson's shakedown-map load, a different problem: the flow does not reshape it); "
          "q = mu p when it slides, Carter's traction under fx, laid on either"),
      key(
          "passes.stationary_phases", [](auto& s) -> auto& { return s.passes.stationary_phases; },
          "the stationary pass solved at this many places of the roller between two nodes at once, k/P of an "
          "element apart, as a transient pass in steps of h/P meets them (docs/model.md, Phases)",
          closed(1, 16)),
      key(
          "passes.stationary_path_parts", [](auto& s) -> auto& { return s.passes.stationary_path_parts; },
          "a lane's step along which the material yields walked in this many equal parts of its straight strain path; "
          "1: one return mapping a step, as the transient's (docs/model.md, Stationary pass)",
          closed(1, 64)),
      key(
          "passes.until_verdict", [](auto& s) -> auto& { return s.passes.until_verdict; },
          "stop after the first pass that decides the shakedown verdict (at most count passes)"),

      // [fatigue]
      key(
          "fatigue.dang_van_a", [](auto& s) -> auto& { return s.fatigue->dang_van_a; },
          "Dang Van's weight a_DV of the hydrostatic stress in tau + a_DV sigma_h [-] (steels ~0.3)", closed(0.0, 10.0))
          .required("Dang Van's a_DV is required in [fatigue] (steels ~0.3)"),
      key(
          "fatigue.dang_van_limit", [](auto& s) -> auto& { return s.fatigue->dang_van_limit; },
          "Dang Van's shear fatigue limit tau_w [MPa] (the index is max(tau + a_DV sigma_h) / tau_w)",
          with_hint(closed(kMinModulus, kMaxFatigueLimit), "tau_w in Pa? roller works in MPa"))
          .required("Dang Van's shear fatigue limit tau_w [MPa] is required in [fatigue]"),
      key(
          "fatigue.shear_fatigue_limit", [](auto& s) -> auto& { return s.fatigue->shear_fatigue_limit; },
          "Ekberg's subsurface fatigue limit tau_e [MPa] (the index is FI_sub / tau_e)",
          with_hint(closed(kMinModulus, kMaxFatigueLimit), "tau_e in Pa? roller works in MPa"))
          .required("Ekberg's shear fatigue limit tau_e [MPa] is required in [fatigue]"),
      key(
          "fatigue.critical_shear_strain", [](auto& s) -> auto& { return s.fatigue->critical_shear_strain; },
          "Kapoor's critical shear strain gamma_c [-]: the surface's ductility (passes to initiation = gamma_c / its "
          "shear strain per pass)",
          closed(1e-6, 1e3))
          .required("Kapoor's critical shear strain gamma_c is required in [fatigue] (a number of order 10 for a rail "
                    "steel)"),

      // [newton]
      key(
          "newton.max_iterations", [](auto& s) -> auto& { return s.newton.max_iterations; },
          "Newton iterations per increment", at_least(1)),
      key(
          "newton.residual_tolerance", [](auto& s) -> auto& { return s.newton.residual_tolerance; },
          "converged when |r| <= tol * force scale", open(0.0, 1.0)),
      key(
          "newton.line_search", [](auto& s) -> auto& { return s.newton.line_search; },
          "backtracking on the incremental energy"),

      // [linear_solver]
      key(
          "linear_solver.out_of_core", [](auto& s) -> auto& { return s.newton.linear.out_of_core; },
          "MUMPS factors written to disk instead of kept in memory"),
      key(
          "linear_solver.ordering", [](auto& s) -> auto& { return s.newton.linear.ordering; },
          "fill-reducing ordering of MUMPS (auto: MUMPS chooses)", one_of(LinearSolverOptions::orderings())),
      key(
          "linear_solver.directory", [](auto& s) -> auto& { return s.newton.linear.directory; },
          "existing directory for the out-of-core files (\"\": MUMPS's default, /tmp)"),

      // [output]
      key(
          "output.every", [](auto& s) -> auto& { return s.output.every; },
          "write fields every N steps (the last step always)", at_least(1))
          .when_absent("1; steps.count (every pass's end) with transient [passes]",
                       // Long multi-pass studies would otherwise fill the disk with every step.
                       [](Scene& s) {
                         const bool marched = s.passes.method == PassMethod::Transient;
                         s.output.every = s.passes.count > 1 && marched ? s.steps.n_steps : 1;
                       }),
      key(
          "output.mid_pass", [](auto& s) -> auto& { return s.output.mid_pass; },
          "[passes]: also write the fields of each pass's loaded state beside output.every's: transient, the step "
          "in the middle of its travel (the roller at mid-track); stationary, the pass's steady state as "
          "step_NNNN_loaded.vtu"),
      key(
          "output.vtu", [](auto& s) -> auto& { return s.output.vtu; }, "write step_NNNN.vtu and fields.pvd"),
      key(
          "output.monitor", [](auto& s) -> auto& { return s.output.monitor; },
          "run-time monotonicity monitor (one extra assembly and factorisation per step)"),
      key(
          "output.checkpoint_every", [](auto& s) -> auto& { return s.output.checkpoint_every; },
          "write checkpoint.cbor every N steps (0 = never), for --resume", at_least(0)),
      custom(
          "output.save_states", "array of steps", "[]", "1..steps.count",
          "keep the full state of these steps as state_NNNN.cbor",
          [](TomlSection& s, Scene& scene, Ref) {
            if (auto steps = s.real_array("save_states")) {
              for (Real v : *steps) {
                if (v != std::floor(v) || v < 1 || v > scene.total_steps())
                  s.fail("save_states", fmt::format("expected step numbers in 1..{} (steps.count x passes.count)",
                                                    scene.total_steps()));
                scene.output.save_states.push_back(static_cast<int>(v));
              }
            }
          },
          [](toml::table& t, const Scene& scene, Ref) {
            toml::array a;
            for (int step : scene.output.save_states) a.push_back(static_cast<int64_t>(step));
            t.insert("save_states", a);
          }),

      // [dynamics]
      key(
          "dynamics.strip_inertia", [](auto& s) -> auto& { return s.dynamics.strip_inertia; },
          "Houbolt inertia of the strip; needs material.density > 0"),
      field<MassMatrix>(
          "dynamics.mass",
          [](const Scene& s, Ref) { return s.dynamics.lumped_mass ? MassMatrix::Lumped : MassMatrix::Consistent; },
          [](Scene& s, Ref, const MassMatrix& m) { s.dynamics.lumped_mass = m == MassMatrix::Lumped; },
          "consistent or row-sum lumped mass matrix", {}),

      // [restart]
      custom(
          "restart.from", "path", "required in [restart]", "",
          "state file of another run (state_final.cbor), relative to the scene file (--initial-state)",
          [](TomlSection& s, Scene& scene, Ref) {
            const auto from = s.string("from");
            if (!from || from->empty()) s.fail("from", "expected the path of a state file (state_final.cbor of a run)");
            std::filesystem::path p(*from);
            // Relative to the scene file, so that a scene and its predecessor's output travel together.
            if (p.is_relative() && !scene.file.empty()) p = scene.file.parent_path() / p;
            scene.initial_state = p;
          },
          [](toml::table& t, const Scene& scene, Ref) { t.insert("from", scene.initial_state.string()); }),

      // [[displacement]] and [[load]]
      nodes_key("displacement.nodes", &Scene::displacements),
      ramp_key("displacement.x", &Scene::displacements, &DisplacementBC::x, kMaxLength,
               "total displacement in x [mm]: a number (from step 1) or { value, ramp = [first, last] }"),
      ramp_key("displacement.y", &Scene::displacements, &DisplacementBC::y, kMaxLength,
               "total displacement in y [mm], as x"),
      nodes_key("load.nodes", &Scene::loads),
      ramp_key("load.fx", &Scene::loads, &NodalLoad::fx, kMaxForce,
               "force on each selected node [N per mm width]: a number or a ramp table"),
      ramp_key("load.fy", &Scene::loads, &NodalLoad::fy, kMaxForce, "force on each selected node in y, as fx"),

      // [roller]
      key(
          "roller.radius", [](auto& s) -> auto& { return s.roller->radius; }, "R [mm]", closed(kMinLength, kMaxLength)),
      key(
          "roller.E", [](auto& s) -> auto& { return s.roller->youngs_modulus; },
          "an elastic roller's Young's modulus [MPa] (docs/model.md, Elastic roller)",
          with_hint(closed(kMinModulus, kMaxModulus), "E in Pa? roller works in MPa (steel: E = 2.1e5)"))
          .shown_default("absent: rigid")
          .written_if([](const Scene& s) { return s.roller->elastic(); }),
      key(
          "roller.nu", [](auto& s) -> auto& { return s.roller->poisson_ratio; }, "an elastic roller's Poisson's ratio",
          open(-1.0, 0.5))
          .written_if([](const Scene& s) { return s.roller->elastic(); }),
      key(
          "roller.inner_radius", [](auto& s) -> auto& { return s.roller->inner_radius; },
          "an elastic roller's bore [mm]: a ring or sleeve held there (0: a solid disc, held at its axle)",
          closed(0.0, kMaxLength))
          .written_if([](const Scene& s) { return s.roller->elastic(); }),
      custom(
          "roller.centre", "[x, y]", "[length/2, height + radius] (touching)", "", "centre at the start [mm]",
          [](TomlSection& s, Scene& scene, Ref) {
            if (auto c = s.real_array("centre")) {
              if (c->size() != 2) s.fail("centre", "expected [x, y] of the roller centre at the start [mm]");
              scene.roller->start_centre = Vec2((*c)[0], (*c)[1]);
            }
          },
          [](toml::table& t, const Scene& scene, Ref) {
            if (const auto& c = scene.roller->start_centre) t.insert("centre", pair_array(c->x(), c->y()));
          }),
      key(
          "roller.angle", [](auto& s) -> auto& { return s.roller->start_angle; },
          "rotation angle at the start [rad], counter-clockwise positive"),
      key(
          "roller.touch_strip", [](auto& s) -> auto& { return s.roller->touch_strip; },
          "move the start centre vertically (at its x) until the roller touches the strip as it is at the "
          "start (after [restart]): the path's dy become depths below the present surface"),
      key(
          "roller.suspension.mass", [](auto& s) -> auto& { return s.roller->suspension->mass; },
          "m [t per mm of roller length]", closed(0.0, kMaxSuspension)),
      key(
          "roller.suspension.damping", [](auto& s) -> auto& { return s.roller->suspension->damping; },
          "c [N s/mm per mm]", closed(0.0, kMaxSuspension)),
      key(
          "roller.suspension.stiffness", [](auto& s) -> auto& { return s.roller->suspension->stiffness; },
          "k [N/mm per mm]; k or m must be > 0", closed(0.0, kMaxSuspension)),
      custom(
          "roller.path.steps", "[first, last]", "required", "1 <= first <= last",
          "the steps the segment acts over (1-based, inclusive)",
          [](TomlSection& s, Scene& scene, Ref i) {
            const auto steps = s.real_array("steps");
            if (!steps || steps->size() != 2 || !is_step((*steps)[0]) || !is_step((*steps)[1]))
              s.fail("steps", "expected [first_step, last_step] (integers, 1-based, inclusive)");
            scene.roller->path[i].first_step = static_cast<int>((*steps)[0]);
            scene.roller->path[i].last_step = static_cast<int>((*steps)[1]);
          },
          [](toml::table& t, const Scene& scene, Ref i) {
            const PathSegment& p = scene.roller->path[i];
            t.insert("steps", toml::array{static_cast<int64_t>(p.first_step), static_cast<int64_t>(p.last_step)});
          }),
      key(
          "roller.path.dx", [](auto& s, Ref i) -> auto& { return s.roller->path[i].dx; },
          "travel of the centre in x over the segment [mm]", closed(-kMaxLength, kMaxLength)),
      key(
          "roller.path.dy", [](auto& s, Ref i) -> auto& { return s.roller->path[i].dy; },
          "travel of the centre in y over the segment [mm] (negative = press in)", closed(-kMaxLength, kMaxLength)),
      custom(
          "roller.path.slip", "number or [start, end]", "0", "-1 <= slip <= 1",
          "creep ratio s = (v - omega R)/v, linear from start to end over the segment",
          [](TomlSection& s, Scene& scene, Ref i) {
            PathSegment& p = scene.roller->path[i];
            if (const toml::node* slip = s.node("slip")) {
              if (slip->is_number()) {
                p.slip_start = p.slip_end = *s.real("slip");
              } else if (auto pair = s.real_array("slip"); pair && pair->size() == 2) {
                p.slip_start = (*pair)[0];
                p.slip_end = (*pair)[1];
              } else {
                s.fail("slip", "expected a slip ratio s = (v - omega R)/v, or [s_start, s_end]");
              }
            }
          },
          [](toml::table& t, const Scene& scene, Ref i) {
            const PathSegment& p = scene.roller->path[i];
            t.insert("slip", pair_array(p.slip_start, p.slip_end));
          }),
      custom(
          "roller.path.harmonic", "{ amplitude, wavelength }", "none", "wavelength > 0",
          "adds amplitude sin(2 pi u / wavelength) to y, u = distance rolled in the segment [mm]",
          [](TomlSection& s, Scene& scene, Ref i) {
            PathSegment& p = scene.roller->path[i];
            if (auto h = s.table("harmonic")) {
              h->allow({"amplitude", "wavelength"});
              h->finish();
              p.harmonic_amplitude = h->real_or("amplitude", 0.0);
              const auto wl = h->real("wavelength");
              if (!wl || !(*wl > 0.0)) h->fail("wavelength", "expected the wavelength L_p > 0 [mm]");
              p.harmonic_wavelength = *wl;
            }
          },
          [](toml::table& t, const Scene& scene, Ref i) {
            const PathSegment& p = scene.roller->path[i];
            if (p.harmonic_wavelength > 0.0)
              t.insert("harmonic",
                       toml::table{{"amplitude", p.harmonic_amplitude}, {"wavelength", p.harmonic_wavelength}});
          }),

      custom(
          "roller.path.fy", "number", "absent (dy: motion)", "0 <= fy <= 1e15",
          "vertical force of the strip on the roller at the segment's end [N per mm], linear from the last earlier "
          "segment's fy (0 if none); the centre's height becomes an unknown (replaces dy)",
          [](TomlSection& s, Scene& scene, Ref i) {
            if (const auto fy = s.real("fy")) {
              if (!(*fy >= 0.0 && *fy <= kMaxForce))
                s.fail("fy", fmt::format("must satisfy 0 <= fy <= {:g} (the contact only pushes)", kMaxForce));
              scene.roller->path[i].fy = *fy;
            }
          },
          [](toml::table& t, const Scene& scene, Ref i) {
            if (const auto& fy = scene.roller->path[i].fy) t.insert("fy", *fy);
          }),
      custom(
          "roller.path.p0", "number", "absent", "> 0",
          "the vertical force as the Hertz peak pressure p0 [MPa] of a line contact: fy = pi R p0^2 / E*, "
          "E* = E/(1 - nu^2) of the strip (rigid roller); instead of fy",
          [](TomlSection& s, Scene& scene, Ref i) { read_load_as_pressure(s, scene, i, "p0"); },
          [](toml::table&, const Scene&, Ref) {}),  // written as the fy it gives
      custom(
          "roller.path.p0_over_k", "number", "absent", "> 0",
          "the vertical force as p0/k, the Hertz peak pressure over the strip's shear yield stress "
          "k = yield_stress/sqrt(3) (Johnson's shakedown measure): fy = pi R (p0/k k)^2 / E*; instead of fy",
          [](TomlSection& s, Scene& scene, Ref i) { read_load_as_pressure(s, scene, i, "p0_over_k"); },
          [](toml::table&, const Scene&, Ref) {}),
      custom(
          "roller.path.fx", "number", "absent (dx: motion)", "-1e15 <= fx <= 1e15",
          "horizontal force of the strip on the roller at the segment's end [N per mm], linear from the last "
          "earlier segment's fx (0 if none); the centre's x becomes an unknown while dx still turns the roller "
          "(dx = 0: rotation blocked); a steady pass holds the end value (q_over_p holds in both)",
          [](TomlSection& s, Scene& scene, Ref i) {
            if (const auto fx = s.real("fx")) {
              if (!(std::abs(*fx) <= kMaxForce)) s.fail("fx", fmt::format("must satisfy |fx| <= {:g}", kMaxForce));
              scene.roller->path[i].fx = *fx;
            }
          },
          [](toml::table& t, const Scene& scene, Ref i) {
            if (const auto& fx = scene.roller->path[i].fx) t.insert("fx", *fx);
          }),
      custom(
          "roller.path.q_over_p", "number", "absent", "|q_over_p| <= 10",
          "the traction ratio q/p instead of fx: the roller's tangential force on the strip along the travel over "
          "its normal force, held from the segment's first step (fx = -sign(dx) q/p fy at every step; no ramp), "
          "as the stationary pass and shakedown-limit take it; needs the segment's fy (or p0, p0_over_k) and dx",
          [](TomlSection& s, Scene& scene, Ref i) {
            if (const auto q = s.real("q_over_p")) {
              if (s.has("fx")) s.fail("q_over_p", "give fx or q_over_p, not both");
              scene.roller->path[i].q_over_p = *q;
            }
          },
          [](toml::table& t, const Scene& scene, Ref i) {
            if (const auto& q = scene.roller->path[i].q_over_p) t.insert("q_over_p", *q);
          }),
      custom(
          "roller.path.friction", "number", "contact.friction", "0 <= friction <= 10",
          "Coulomb coefficient over the segment's steps (e.g. 0 while pressing, mu once the roller rolls)",
          [](TomlSection& s, Scene& scene, Ref i) {
            if (const auto mu = s.real("friction")) {
              if (!(*mu >= 0.0 && *mu <= 10.0)) s.fail("friction", "must satisfy 0 <= friction <= 10");
              scene.roller->path[i].friction = *mu;
            }
          },
          [](toml::table& t, const Scene& scene, Ref i) {
            if (const auto& mu = scene.roller->path[i].friction) t.insert("friction", *mu);
          }),

      // [contact]
      key(
          "contact.backend", [](auto& s) -> auto& { return s.contact.backend; },
          "contact solver (--contact): interior point (exact non-penetration) or the thesis's penalty Newton"),
      key(
          "contact.friction", [](auto& s) -> auto& { return s.contact.friction; }, "Coulomb coefficient mu",
          closed(0.0, 10.0)),
      key(
          "contact.candidates", [](auto& s) -> auto& { return s.contact.candidates; },
          "node set (or union \"top+right\") of the nodes that may touch the roller"),
      key(
          "contact.predictor", [](auto& s) -> auto& { return s.contact.predictor; },
          "start of each increment: the previous increment scaled, or that and the thesis's arc rule, or "
          "it carried along with the roller (rolling)"),
      key(
          "contact.roller_coupling", [](auto& s) -> auto& { return s.contact.roller_coupling; },
          "the height of a suspended or force-loaded roller: solved with the strip in one contact solve (joint; "
          "ipopt's condensed formulation, the penalty backend always uses passes) or by coupling passes"),
      key(
          "contact.penalty.factor", [](auto& s) -> auto& { return s.contact.penalty.factor; },
          "normal penalty kappa_N = factor * E* * l_i / h_i", above(0.0)),
      key(
          "contact.penalty.tangential_factor", [](auto& s) -> auto& { return s.contact.penalty.tangential_factor; },
          "kappa_T = tangential_factor * kappa_N", above(0.0)),
      key(
          "contact.ipopt.formulation", [](auto& s) -> auto& { return s.contact.ipopt.formulation; },
          "condensed: MUMPS condensation onto the contact dofs, small dense NLP; full: every free dof in the NLP"),
      key(
          "contact.ipopt.tol", [](auto& s) -> auto& { return s.contact.ipopt.tol; }, "Ipopt's tol on the scaled NLP",
          open(0.0, 1.0)),
      key(
          "contact.ipopt.max_iter", [](auto& s) -> auto& { return s.contact.ipopt.max_iter; },
          "Ipopt's iteration limit per NLP", at_least(1)),
      key(
          "contact.ipopt.mu_strategy", [](auto& s) -> auto& { return s.contact.ipopt.mu_strategy; },
          "Ipopt's barrier update"),
      key(
          "contact.ipopt.print_level", [](auto& s) -> auto& { return s.contact.ipopt.print_level; },
          "Ipopt's output level", closed(0, 12)),
      key(
          "contact.ipopt.warm_start", [](auto& s) -> auto& { return s.contact.ipopt.warm_start; },
          "warm-start the first Ipopt pass of each linearisation from the last forces (the first one from the "
          "previous increment's); a failed warm start is repeated cold"),
      key(
          "contact.ipopt.friction", [](auto& s) -> auto& { return s.contact.ipopt.friction; },
          "split: v_T = s+ - s-, exact; regularized: sqrt(v_T^2 + eps^2)"),
      key(
          "contact.ipopt.regularization", [](auto& s) -> auto& { return s.contact.ipopt.regularization; },
          "eps of the regularized friction [mm]", above(0.0)),
      key(
          "contact.ipopt.fixed_point", [](auto& s) -> auto& { return s.contact.ipopt.fixed_point; },
          "converge: Coulomb's normal-force fixed point iterated; single: one pass with the previous F_N"),
      key(
          "contact.ipopt.fixed_point_tol", [](auto& s) -> auto& { return s.contact.ipopt.fixed_point_tol; },
          "max |dF_N| / max F_N that ends the friction fixed point", above(0.0)),
      key(
          "contact.ipopt.fixed_point_max", [](auto& s) -> auto& { return s.contact.ipopt.fixed_point_max; },
          "passes of the friction fixed point at most", at_least(1)),
      key(
          "contact.ipopt.kkt_solver", [](auto& s) -> auto& { return s.contact.ipopt.kkt_solver; },
          "Ipopt's linear solver: dense (LAPACK, for small NLPs), mumps (sparse), auto: dense up to 200 KKT rows"),
      custom("contact.ipopt.options", "table", "{}", "Ipopt's options",
             "any further Ipopt option, passed through after roller's own settings (booleans become yes/no)",
             read_ipopt_options, write_ipopt_options),
  };
  add_layer_keys(keys);  // [[layer]]: the [material] keys above, read into each layer
  return keys;
}

// ---- the tables ------------------------------------------------------------------------------

std::vector<SceneTable> make_tables() {
  using Ref = std::size_t;
  std::vector<SceneTable> tables;
  tables.reserve(32);  // the references returned by add stay valid
  auto add = [&tables](const std::string& path, bool array = false) -> SceneTable& {
    tables.emplace_back();
    tables.back().path = path;
    tables.back().array = array;
    return tables.back();
  };
  add("").check = [](TomlSection& s, Scene& scene, Ref) {
    // The name becomes a folder under out/: one path component that stays inside it.
    const std::string& n = scene.name;
    const bool printable = std::all_of(n.begin(), n.end(), [](char c) { return c > ' ' && c != 0x7f; });
    if (n.empty() || n == "." || n == ".." || n.find_first_of("/\\") != std::string::npos || !printable ||
        n.size() > 200)
      s.fail("name",
             "expected a non-empty name of at most 200 characters without '/', '\\', spaces, tabs or control "
             "characters (it names the output folder out/<name>)");
    if (scene.passes.count > 1 && !scene.roller)
      s.fail("passes", "repeated passes need a [roller] whose [[roller.path]] describes one pass");
    if (scene.passes.method == PassMethod::Stationary && !scene.roller)
      s.fail("passes", "the stationary method needs a [roller] and its [[roller.path]]");
  };

  SceneTable& material = add("material");
  material.required = "a [material] table is required (at least E and nu)";
  material.check = [](TomlSection& s, Scene& scene, Ref) {
    std::string why;
    if (!scene.material.is_valid(&why))
      s.fail_invalid(why, {{"youngs_modulus", "E"},
                           {"poisson_ratio", "nu"},
                           {"tangent_modulus", s.has("kappa") ? "kappa" : "tangent_modulus"},
                           {"n_substeps", "substeps"}});
  };
  declare_layer_table(add("layer", true));

  SceneTable& mesh = add("mesh");
  mesh.required = "a [mesh] table is required (element, length, height, nx, ny)";
  mesh.check = [](TomlSection& s, Scene& scene, Ref) {
    std::string why;
    for (const char* lines : {"x_lines", "y_lines"})
      if (s.has(lines) && (lines[0] == 'x' ? scene.mesh.x_lines : scene.mesh.y_lines).empty())
        s.fail(lines, "expected at least two grid lines (or no key: nx/ny and grading)");
    if (!scene.mesh.is_valid(&why)) s.fail_invalid(why, {});
    check_layers_fit(s, scene);
  };

  add("steps");
  SceneTable& passes = add("passes");
  passes.check = [](TomlSection& s, Scene& scene, Ref) {
    if (scene.total_steps() > 1e7)
      s.fail("count", fmt::format("count x steps.count = {} steps: at most 1e7", scene.total_steps()));
    if (scene.passes.method != PassMethod::Stationary) return;
    if (scene.mesh.periodic)
      s.fail("method",
             "the stationary method solves a pass on a strip with two ends (its residual strip a long track's): set "
             "mesh.periodic = false, or method = \"transient\" to roll the periodic strip");
    if (scene.element.kinematics != Kinematics::Small)
      s.fail("method", "the stationary method is small-strain: set kinematics = \"small\" (or method = \"transient\")");
    if (scene.dynamics.strip_inertia)
      s.fail("method", "the stationary method is quasi-static: set dynamics.strip_inertia = false");
    // A lane follows one integration point of every element along a row, on one side of the
    // elements' centres; T3's one point is its centroid, the centre itself.
    if (scene.mesh.element != ElementType::Q4)
      s.fail("method", fmt::format("the stationary method needs mesh.element = \"Q4\" (its lanes follow the Q4 "
                                   "integration points along a row; mesh.element = \"{}\" has none such): set "
                                   "mesh.element = \"Q4\", or method = \"transient\" for T3",
                                   enum_name(scene.mesh.element)));
  };
  passes.count = [](const Scene& s) -> std::size_t { return s.passes.count > 1; };
  SceneTable& fatigue = add("fatigue");
  fatigue.enter = [](TomlSection&, Scene& scene) { scene.fatigue.emplace(); };
  fatigue.check = [](TomlSection& s, Scene& scene, Ref) {
    std::string why;
    if (!scene.fatigue->is_valid(&why)) s.fail_invalid(why, {});
    // The indices judge the stabilised pass, and a pass's start is the last one's end.
    if (scene.passes.count < 2)
      s.fail("dang_van_a", fmt::format("[fatigue] judges a repeated pass: set passes.count >= 2 (it is {}) and "
                                       "the indices of every pass go to fatigue.csv",
                                       scene.passes.count));
  };
  fatigue.count = [](const Scene& s) -> std::size_t { return s.fatigue.has_value(); };
  add("newton").check = [](TomlSection& s, Scene& scene, Ref) {
    std::string why;
    if (!scene.newton.is_valid(&why)) s.fail_invalid(why, {});
  };
  add("linear_solver").check = [](TomlSection& s, Scene& scene, Ref) {
    std::string why;
    if (!scene.newton.linear.is_valid(&why)) s.fail_invalid(why, {});
  };
  add("output");
  add("dynamics").check = [](TomlSection& s, Scene& scene, Ref) {
    if (scene.dynamics.strip_inertia && !(scene.material.density > 0.0))
      s.fail("strip_inertia", fmt::format("strip inertia needs material.density > 0 [t/mm^3] (it is {}); steel: 7.8e-9",
                                          scene.material.density));
    check_layers_have_density(s, scene);
  };
  add("restart").count = [](const Scene& s) -> std::size_t { return !s.initial_state.empty(); };

  SceneTable& displacement = add("displacement", true);
  displacement.enter = [](TomlSection&, Scene& scene) { scene.displacements.emplace_back(); };
  displacement.check = [](TomlSection& s, Scene& scene, Ref i) {
    const DisplacementBC& d = scene.displacements[i];
    if (!d.x && !d.y) s.fail("x", "a [[displacement]] block needs x and/or y");
    // As large as the strip: the elements between these nodes and the supports would be crushed
    // through or torn apart, which the solvers would report as a step too large.
    if (d.x && !(d.x->peak() < scene.mesh.length))
      s.fail("x", fmt::format("|x| must be smaller than the strip's length mesh.length = {:g} mm (a displacement as "
                              "large as the strip crushes or tears it)",
                              scene.mesh.length));
    if (d.y && !(d.y->peak() < scene.mesh.height))
      s.fail("y", fmt::format("|y| must be smaller than the strip's height mesh.height = {:g} mm (a displacement as "
                              "large as the strip crushes or tears it)",
                              scene.mesh.height));
  };
  displacement.count = [](const Scene& s) { return s.displacements.size(); };

  SceneTable& load = add("load", true);
  load.enter = [](TomlSection&, Scene& scene) { scene.loads.emplace_back(); };
  load.check = [](TomlSection& s, Scene& scene, Ref i) {
    if (!scene.loads[i].fx && !scene.loads[i].fy) s.fail("fx", "a [[load]] block needs fx and/or fy");
  };
  load.count = [](const Scene& s) { return s.loads.size(); };

  SceneTable& roller = add("roller");
  roller.enter = [](TomlSection&, Scene& scene) { scene.roller.emplace(); };
  roller.check = [](TomlSection& s, Scene& scene, Ref) {
    std::string why;
    if (!scene.roller->is_valid(&why)) s.fail_invalid(why, {});
    if (!scene.roller->elastic())
      for (const char* k : {"nu", "inner_radius"})
        if (s.has(k)) s.fail(k, "belongs to an elastic roller: give roller.E too (absent: a rigid roller)");
    check_roller_scale(s, scene);
  };
  roller.count = [](const Scene& s) -> std::size_t { return s.roller.has_value(); };

  SceneTable& suspension = add("roller.suspension");
  suspension.enter = [](TomlSection&, Scene& scene) { scene.roller->suspension.emplace(); };
  suspension.count = [](const Scene& s) -> std::size_t { return s.roller && s.roller->suspension; };

  SceneTable& path = add("roller.path", true);
  path.enter = [](TomlSection&, Scene& scene) { scene.roller->path.emplace_back(); };
  path.count = [](const Scene& s) -> std::size_t { return s.roller ? s.roller->path.size() : 0; };
  path.check = [](TomlSection& s, Scene& scene, Ref i) {
    const PathSegment& p = scene.roller->path[i];
    check_reach(s, scene, "dx", p.dx);
    check_reach(s, scene, "dy", p.dy);
    if (p.harmonic_wavelength > 0.0) {
      check_reach(s, scene, "harmonic", p.harmonic_amplitude);
      check_reach(s, scene, "harmonic", p.harmonic_wavelength);
    }
  };

  SceneTable& contact = add("contact");
  contact.enter = [](TomlSection& s, Scene& scene) {
    if (!scene.roller) s.fail("backend", "a [contact] table needs a [roller]");
  };
  contact.check = [](TomlSection& s, Scene& scene, Ref) {
    std::string why;
    if (!scene.contact.is_valid(&why)) s.fail_invalid(why, {});
  };
  contact.count = [](const Scene& s) -> std::size_t { return s.roller.has_value(); };

  add("contact.penalty");
  add("contact.ipopt");
  return tables;
}

}  // namespace

std::string SceneTable::name() const { return split_dotted(path).second; }
std::string SceneTable::parent() const { return split_dotted(path).first; }

std::string SceneKey::dotted() const {
  std::string out;
  std::string prefix;
  if (!table.empty()) {
    std::size_t start = 0;
    while (true) {
      const auto dot = table.find('.', start);
      prefix = table.substr(0, dot);
      out += table.substr(start, dot == std::string::npos ? std::string::npos : dot - start);
      if (scene_table(prefix).array) out += "[]";
      out += ".";
      if (dot == std::string::npos) break;
      start = dot + 1;
    }
  }
  return out + name;
}

const std::vector<SceneTable>& scene_tables() {
  static const std::vector<SceneTable> tables = make_tables();
  return tables;
}

const std::vector<SceneKey>& scene_keys() {
  static const std::vector<SceneKey> keys = make_keys();
  return keys;
}

const SceneTable& scene_table(const std::string& path) {
  for (const SceneTable& t : scene_tables())
    if (t.path == path) return t;
  throw std::out_of_range("scene_table: no table '" + path + "' is declared");
}

std::vector<const SceneKey*> keys_of(const std::string& table) {
  std::vector<const SceneKey*> out;
  for (const SceneKey& k : scene_keys())
    if (k.table == table) out.push_back(&k);
  return out;
}

std::vector<const SceneTable*> sub_tables_of(const std::string& table) {
  std::vector<const SceneTable*> out;
  for (const SceneTable& t : scene_tables())
    if (!t.path.empty() && t.parent() == table) out.push_back(&t);
  return out;
}

}  // namespace roller
