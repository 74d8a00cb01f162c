#include "roller/io/scene_loader.hpp"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "roller/core/error.hpp"
#include "roller/io/scene_keys.hpp"
#include "roller/io/toml_section.hpp"

namespace roller {

namespace {

// The keys of a path segment that give one force each: the vertical (fy, or in the users' terms)
// and the horizontal (fx, or as the traction ratio).
const std::vector<std::vector<std::string>> kSegmentForceKeys{{"fy", "p0", "p0_over_k"}, {"fx", "q_over_p"}};

// ---- overrides -------------------------------------------------------------------------------

// A key's component "path[1]": the block of an array of tables (0-based), or a plain name.
struct KeyPart {
  std::string name;
  std::optional<std::size_t> block;
};

KeyPart parse_part(const SceneOverride& o, const std::string& part) {
  const auto open = part.find('[');
  if (open == std::string::npos) return {part, std::nullopt};
  const std::string index = part.substr(open + 1, part.size() - open - 2);
  const bool digits = !index.empty() && index.size() < 7 &&
                      std::all_of(index.begin(), index.end(), [](char c) { return c >= '0' && c <= '9'; });
  if (part.back() != ']' || open == 0 || !digits)
    throw InputError(
        fmt::format("--set {}={}: '{}': expected name[N] with a block number N >= 0 (e.g. "
                    "roller.path[1].fy)",
                    o.key, o.value, part));
  return {part.substr(0, open), static_cast<std::size_t>(std::stoul(index))};
}

// The table a component names: a sub-table (made when absent) or a block of an array of tables.
toml::table* enter_part(toml::table& t, const SceneOverride& o, const KeyPart& part) {
  toml::node* n = t.get(part.name);
  if (part.block) {
    toml::array* blocks = n ? n->as_array() : nullptr;
    if (!blocks || !blocks->is_array_of_tables())
      throw InputError(fmt::format("--set {}={}: '{}' is not an array of tables ([[{}]] blocks) in the scene", o.key,
                                   o.value, part.name, part.name));
    if (*part.block >= blocks->size())
      throw InputError(
          fmt::format("--set {}={}: the scene has {} [[{}]] block(s), numbered from 0; expected "
                      "{}[0] to {}[{}]",
                      o.key, o.value, blocks->size(), part.name, part.name, part.name, blocks->size() - 1));
    return (*blocks)[*part.block].as_table();
  }
  if (!n) {
    t.insert(part.name, toml::table{});
    n = t.get(part.name);
  }
  toml::table* sub = n->as_table();
  if (!sub) throw InputError(fmt::format("--set {}={}: '{}' is not a table in the scene", o.key, o.value, part.name));
  return sub;
}

void apply_override(toml::table& root, const SceneOverride& o) {
  std::vector<std::string> parts;
  std::stringstream ss(o.key);
  for (std::string p; std::getline(ss, p, '.');) parts.push_back(p);
  // "", ".a", "a..b", "a.": a component without a name (a Python dict's keys are not parsed).
  if (parts.empty() || o.key.back() == '.' ||
      std::any_of(parts.begin(), parts.end(), [](const std::string& p) { return p.empty(); }))
    throw InputError(
        fmt::format("--set '{}={}': expected a key of dotted names, e.g. material.E or "
                    "roller.path[1].fy",
                    o.key, o.value));
  toml::table* t = &root;
  for (std::size_t i = 0; i + 1 < parts.size(); ++i) t = enter_part(*t, o, parse_part(o, parts[i]));
  if (parse_part(o, parts.back()).block)
    throw InputError(
        fmt::format("--set {}={}: a value is set on a key of a block (e.g. roller.path[1].fy), not "
                    "on the block itself",
                    o.key, o.value));
  // A segment's force is given once per direction: an override of one of its keys replaces the
  // force the block gives in any (--set roller.path[0].p0_over_k=4 on a scene with fy).
  for (const std::vector<std::string>& keys : kSegmentForceKeys)
    if (std::find(keys.begin(), keys.end(), parts.back()) != keys.end())
      for (const std::string& k : keys) t->erase(k);
  toml::table parsed;
  try {
    parsed = toml::parse("v = " + o.value);
  } catch (const toml::parse_error&) {
    parsed = toml::table{{"v", o.value}};  // bare word: take it as a string
  }
  t->insert_or_assign(parts.back(), *parsed.get("v"));
}

// ---- tables: the declarations of io/scene_keys.hpp drive the reading ---------------------

void read_table(const SceneTable& table, TomlSection& section, Scene& scene, std::size_t block) {
  if (table.enter) table.enter(section, scene);
  const std::vector<const SceneKey*> keys = keys_of(table.path);
  const std::vector<const SceneTable*> subs = sub_tables_of(table.path);
  // Unknown keys first ("did you mean" the closest declared key of this table).
  std::vector<std::string> known;
  for (const SceneKey* k : keys) known.push_back(k->name);
  for (const SceneTable* t : subs) known.push_back(t->name());
  section.allow(known);
  section.finish();
  for (const SceneKey* k : keys) k->read(section, scene, block);
  for (const SceneTable* sub : subs) {
    if (sub->array) {
      std::vector<TomlSection> blocks = section.table_array(sub->name());
      for (std::size_t i = 0; i < blocks.size(); ++i) read_table(*sub, blocks[i], scene, i);
    } else if (auto s = section.table(sub->name())) {
      read_table(*sub, *s, scene, block);
    } else if (!sub->required.empty()) {
      section.fail(sub->name(), sub->required);
    } else if (!sub->enter && !sub->count) {
      // An absent table of settings means all its defaults, the ones computed from the rest of
      // the scene included (output.every of a multi-pass run); a table whose presence makes or
      // means something (a roller, a restart, passes) stays absent.
      const toml::table empty;
      TomlSection defaults(empty, sub->path, section.file());
      read_table(*sub, defaults, scene, block);
    }
  }
  if (table.check) table.check(section, scene, block);
}

Scene scene_from_table(const toml::table& table, const std::filesystem::path& file) {
  Scene scene;
  scene.file = file;
  TomlSection root(table, "", file);
  read_table(scene_table(""), root, scene, 0);
  return scene;
}

}  // namespace

SceneOverride parse_override(const std::string& text) {
  const auto eq = text.find('=');
  if (eq == std::string::npos || eq == 0 || eq + 1 == text.size())
    throw InputError(fmt::format("--set '{}': expected key=value, e.g. --set material.E=2e5", text));
  return {text.substr(0, eq), text.substr(eq + 1)};
}

namespace {

// toml++ parses nested keys and brackets recursively: 50,000 levels overflow its stack (SIGSEGV).
// A scene needs a handful; anything deeper than kMaxNesting is refused before parsing. Counted
// outside quoted strings: the dots of a line's key (before its '=') and open brackets and braces.
constexpr int kMaxNesting = 100;

void check_nesting(const std::string& text, const std::filesystem::path& file_name) {
  int line = 1, dots = 0, depth = 0;
  bool in_value = false;  // after the line's '=': dots are decimal points there
  char quote = 0;
  for (const char ch : text) {
    if (ch == '\n') {
      ++line;
      dots = 0;
      in_value = false;
      continue;
    }
    if (quote) {
      if (ch == quote) quote = 0;
      continue;
    }
    if (ch == '"' || ch == '\'') quote = ch;
    if (ch == '=') in_value = true;
    if (ch == '.' && !in_value) ++dots;
    if (ch == '[' || ch == '{') ++depth;
    if (ch == ']' || ch == '}') --depth;
    if (dots > kMaxNesting || depth > kMaxNesting)
      throw InputError(
          fmt::format("{}:{}: keys or brackets nested deeper than {} levels; expected a scene file "
                      "(docs/scenes.md)",
                      file_name.string(), line, kMaxNesting));
  }
}

// A [[roller.path]] segment that ends after the run's last step would never be reached: almost
// surely a typo in its steps or in steps.count.
void check_path_within_steps(const Scene& scene, int steps, const char* when) {
  if (!scene.roller) return;
  for (std::size_t i = 0; i < scene.roller->path.size(); ++i) {
    const PathSegment& seg = scene.roller->path[i];
    if (seg.last_step > steps)
      throw InputError(
          fmt::format("{}: roller.path[{}].steps = [{}, {}]{}: the segment ends after the run's last "
                      "step {} (steps.count, one pass); expected a last step <= {}, or a larger "
                      "steps.count",
                      scene.file.string(), i, seg.first_step, seg.last_step, when, steps, steps));
  }
}

// A pass ends with the lift of its last path segment, and every pass after the first starts from
// it: fewer steps than the path's (--steps N, --set steps.count=N) would cut the lift off every
// pass. A path overridden to fit the fewer steps is a pass of its own.
void check_passes_not_shortened(const Scene& written, const Scene& scene) {
  const bool passes = scene.passes.count > 1 || scene.passes.method == PassMethod::Stationary;
  if (!passes || !scene.roller) return;
  int path_end = 0;
  for (const PathSegment& seg : scene.roller->path) path_end = std::max(path_end, seg.last_step);
  if (path_end <= scene.steps.n_steps) return;
  throw InputError(fmt::format(
      "{}: steps.count = {} (--steps or --set) on a scene with [passes] ({} passes, method \"{}\"): every pass runs "
      "the whole roller.path, which ends at step {}, with its lift, so a pass cannot be shortened (the file has "
      "steps.count = {}); expected steps.count >= {}, or fewer passes (--set passes.count=N)",
      scene.file.string(), scene.steps.n_steps, scene.passes.count, enum_name(scene.passes.method), path_end,
      written.steps.n_steps, path_end));
}

// Each key once among the overrides (--set, --steps, --refine, --contact): a later one would
// replace an earlier one before it is checked, and hide a bad value (--set steps.count=nan
// --steps 2). A segment's fy, p0 and p0_over_k are one key, its fx and q_over_p another.
void check_overrides_distinct(const std::vector<SceneOverride>& overrides) {
  auto canonical = [](const std::string& key) {
    const auto dot = key.rfind('.');
    const std::string last = dot == std::string::npos ? key : key.substr(dot + 1);
    for (const std::vector<std::string>& keys : kSegmentForceKeys)
      if (std::find(keys.begin(), keys.end(), last) != keys.end())
        return (dot == std::string::npos ? std::string() : key.substr(0, dot + 1)) + keys.front();
    return key;
  };
  for (std::size_t i = 0; i < overrides.size(); ++i)
    for (std::size_t j = 0; j < i; ++j)
      if (canonical(overrides[i].key) == canonical(overrides[j].key))
        throw InputError(fmt::format(
            "{}={} and {}={} set the same scene value twice (--steps, --refine and --contact set steps.count, "
            "mesh.refine and contact.backend; a segment's fy, p0 and p0_over_k are one force, fx and q_over_p "
            "another); expected each once",
            overrides[j].key, overrides[j].value, overrides[i].key, overrides[i].value));
}

}  // namespace

Scene parse_scene(const std::string& text, const std::filesystem::path& file_name,
                  const std::vector<SceneOverride>& overrides) {
  check_nesting(text, file_name);
  toml::table table;
  try {
    table = toml::parse(text, file_name.string());
  } catch (const toml::parse_error& e) {
    throw InputError(fmt::format("{}:{}:{}: TOML syntax error: {}", file_name.string(), e.source().begin.line,
                                 e.source().begin.column, e.description()));
  }
  // The file as written is checked first: an override must not hide a bad value in it (a nan in
  // steps.count that --steps replaces would otherwise pass unseen).
  const Scene written = scene_from_table(table, file_name);
  check_path_within_steps(written, written.steps.n_steps, "");
  if (overrides.empty()) return written;
  check_overrides_distinct(overrides);
  for (const auto& o : overrides) apply_override(table, o);
  Scene scene = scene_from_table(table, file_name);
  // Fewer steps than the file's (--steps) may cut a path short, except a pass's; more steps than
  // both may not.
  check_passes_not_shortened(written, scene);
  check_path_within_steps(scene, std::max(written.steps.n_steps, scene.steps.n_steps), " (after --set/--steps)");
  return scene;
}

Scene load_scene(const std::filesystem::path& file, const std::vector<SceneOverride>& overrides) {
  // Only a regular file: a device or a FIFO would be read forever or block.
  std::error_code ec;
  if (std::filesystem::exists(file, ec) && !std::filesystem::is_regular_file(file, ec))
    throw InputError(fmt::format("{}: not a regular file (a scene is a TOML text file)", file.string()));
  std::ifstream in(file);
  if (!in) throw InputError(fmt::format("{}: cannot open the scene file (check the path)", file.string()));
  std::stringstream buffer;
  buffer << in.rdbuf();
  return parse_scene(buffer.str(), file, overrides);
}

std::vector<Index> resolve_nodes(const NodeSelector& selector, const Mesh& mesh, const std::string& context) {
  if (selector.near) {
    Index best = 0;
    for (Index a = 1; a < mesh.n_nodes(); ++a)
      if ((mesh.nodes[a] - *selector.near).norm() < (mesh.nodes[best] - *selector.near).norm()) best = a;
    return {best};
  }
  if (selector.numbers.empty()) {
    // "top+right": the union of named sets, in order, each node once.
    std::vector<Index> out;
    std::stringstream names(selector.set_name);
    for (std::string name; std::getline(names, name, '+');) {
      try {
        for (Index a : mesh.node_set(name))
          if (std::find(out.begin(), out.end(), a) == out.end()) out.push_back(a);
      } catch (const InputError& e) {
        throw InputError(fmt::format("{}: {}", context, e.what()));
      }
    }
    return out;
  }
  std::vector<Index> out;
  for (Index number : selector.numbers) {
    if (number < 1 || number > mesh.n_nodes())
      throw InputError(
          fmt::format("{}: node {} does not exist: the mesh has nodes 1..{} "
                      "(thesis numbering: column by column from the left, top to bottom)",
                      context, number, mesh.n_nodes()));
    out.push_back(number - 1);
  }
  return out;
}

std::string NodeSelector::describe() const {
  if (near) return fmt::format("the node nearest to ({}, {})", near->x(), near->y());
  if (numbers.empty()) return fmt::format("set '{}'", set_name);
  return fmt::format("nodes [{}]", fmt::join(numbers, ", "));
}

Real Ramp::peak() const {
  Real largest = std::abs(value);
  for (const auto& point : history) largest = std::max(largest, std::abs(point[1]));
  return largest;
}

Real Ramp::at_step(int step) const {
  if (!history.empty()) {
    Real s0 = 0.0, v0 = 0.0;
    for (const auto& [s1, v1] : history) {
      if (step <= s1) return v0 + (v1 - v0) * (step - s0) / (s1 - s0);
      s0 = s1;
      v0 = v1;
    }
    return v0;
  }
  if (step >= ramp_last) return value;
  if (step < ramp_first) return 0.0;
  return value * static_cast<Real>(step - ramp_first + 1) / static_cast<Real>(ramp_last - ramp_first + 1);
}

const std::vector<std::string>& LinearSolverOptions::orderings() {
  static const std::vector<std::string> names{"auto", "amd", "metis"};
  return names;
}

bool LinearSolverOptions::is_valid(std::string* why) const {
  auto bad = [why](const std::string& m) {
    if (why) *why = m;
    return false;
  };
  const auto& known = orderings();
  if (std::find(known.begin(), known.end(), ordering) == known.end())
    return bad(
        fmt::format("linear_solver.ordering = \"{}\": expected one of \"{}\"", ordering, fmt::join(known, "\", \"")));
  if (!directory.empty()) {
    std::error_code ec;
    if (!std::filesystem::is_directory(directory, ec))
      return bad(
          fmt::format("linear_solver.directory = \"{}\": expected an existing directory (for the "
                      "out-of-core factor files)",
                      directory));
    if (directory.size() > 250)
      return bad(fmt::format("linear_solver.directory = \"{}\": MUMPS takes at most 250 characters", directory));
  }
  return true;
}

bool NewtonOptions::is_valid(std::string* why) const {
  auto bad = [why](const std::string& m) {
    if (why) *why = m;
    return false;
  };
  if (max_iterations < 1) return bad(fmt::format("newton.max_iterations = {}: must be >= 1", max_iterations));
  if (!(residual_tolerance > 0.0 && residual_tolerance < 1.0))
    return bad(fmt::format("newton.residual_tolerance = {}: must be in (0, 1)", residual_tolerance));
  return true;
}

}  // namespace roller
