#include "roller/io/toml_section.hpp"

#include <cmath>

#include <algorithm>
#include <sstream>

#include <fmt/format.h>

#include "roller/core/error.hpp"

namespace roller {

TomlSection::TomlSection(const toml::table& table, std::string path, std::filesystem::path file)
    : table_(&table), path_(std::move(path)), file_(std::move(file)) {}

std::string TomlSection::full_key(const std::string& key) const { return path_.empty() ? key : path_ + "." + key; }

std::string TomlSection::where(const std::string& key) const {
  const toml::node* n = key.empty() ? nullptr : table_->get(key);
  const auto line = n ? n->source().begin.line : table_->source().begin.line;
  std::string location = file_.empty() ? std::string("scene") : file_.string();
  if (line > 0) location += fmt::format(":{}", line);
  return fmt::format("{}: {}", location, key.empty() ? path_ : full_key(key));
}

void TomlSection::fail_invalid(const std::string& why,
                               const std::vector<std::pair<std::string, std::string>>& key_of_field) const {
  const auto dot = why.find('.');
  const auto eq = why.find(" = ");
  const auto colon = why.find(": ", eq == std::string::npos ? 0 : eq);
  if (dot == std::string::npos || eq == std::string::npos || colon == std::string::npos || dot > eq)
    throw InputError(fmt::format("{}: {}", where(""), why));
  std::string key = why.substr(dot + 1, eq - dot - 1);
  for (const auto& [field, scene_key] : key_of_field)
    if (key == field) key = scene_key;
  fail(key, why.substr(colon + 2));
}

std::string TomlSection::value_text(const std::string& key) const {
  const toml::node* n = table_->get(key);
  if (!n) return "(missing)";
  if (auto d = n->value_exact<double>()) return fmt::format("{}", *d);  // shortest round-trip form
  std::ostringstream s;
  n->visit([&s](const auto& v) { s << v; });
  return s.str();
}

void TomlSection::fail(const std::string& key, const std::string& expected) const {
  if (table_->contains(key)) throw InputError(fmt::format("{} = {}: {}", where(key), value_text(key), expected));
  throw InputError(fmt::format("{}: {}", where(key), expected));
}

bool TomlSection::has(const std::string& key) const { return table_->contains(key); }

std::vector<std::string> TomlSection::keys() const {
  std::vector<std::string> out;
  for (const auto& [k, v] : *table_) out.emplace_back(k.str());
  return out;
}

const toml::node* TomlSection::node(const std::string& key) {
  read_.insert(key);
  return table_->get(key);
}

std::optional<Real> TomlSection::real(const std::string& key) {
  const toml::node* n = node(key);
  if (!n) return std::nullopt;
  if (auto v = n->value_exact<double>()) {
    // TOML allows nan and inf; no quantity of a scene may be either (they would pass range
    // checks written as comparisons and poison the run).
    if (!std::isfinite(*v)) fail(key, "expected a finite number (nan and inf are not allowed)");
    return *v;
  }
  if (auto i = n->value_exact<int64_t>()) return static_cast<Real>(*i);
  fail(key, "expected a number");
}

std::optional<Index> TomlSection::integer(const std::string& key) {
  const toml::node* n = node(key);
  if (!n) return std::nullopt;
  if (auto i = n->value_exact<int64_t>()) return static_cast<Index>(*i);
  fail(key, "expected an integer");
}

std::optional<bool> TomlSection::boolean(const std::string& key) {
  const toml::node* n = node(key);
  if (!n) return std::nullopt;
  if (auto b = n->value_exact<bool>()) return *b;
  fail(key, "expected true or false");
}

std::optional<std::string> TomlSection::string(const std::string& key) {
  const toml::node* n = node(key);
  if (!n) return std::nullopt;
  if (auto s = n->value_exact<std::string>()) return *s;
  fail(key, "expected a quoted string");
}

std::optional<std::vector<Real>> TomlSection::real_array(const std::string& key) {
  const toml::node* n = node(key);
  if (!n) return std::nullopt;
  const toml::array* arr = n->as_array();
  if (!arr) fail(key, "expected an array of numbers, e.g. [0.0, 1.5, 3.0]");
  std::vector<Real> out;
  for (const auto& item : *arr) {
    if (auto v = item.value_exact<double>()) {
      if (!std::isfinite(*v)) fail(key, "expected finite numbers (nan and inf are not allowed)");
      out.push_back(*v);
    } else if (auto i = item.value_exact<int64_t>())
      out.push_back(static_cast<Real>(*i));
    else
      fail(key, "expected an array of numbers, e.g. [0.0, 1.5, 3.0]");
  }
  return out;
}

std::optional<TomlSection> TomlSection::table(const std::string& key) {
  const toml::node* n = node(key);
  if (!n) return std::nullopt;
  const toml::table* t = n->as_table();
  if (!t) fail(key, fmt::format("expected a table ([{}] or {{ ... }})", full_key(key)));
  return TomlSection(*t, full_key(key), file_);
}

std::vector<TomlSection> TomlSection::table_array(const std::string& key) {
  const toml::node* n = node(key);
  std::vector<TomlSection> out;
  if (!n) return out;
  const toml::array* arr = n->as_array();
  if (!arr || !arr->is_array_of_tables()) fail(key, fmt::format("expected one or more [[{}]] blocks", full_key(key)));
  for (std::size_t i = 0; i < arr->size(); ++i)
    out.emplace_back(*arr->get(i)->as_table(), fmt::format("{}[{}]", full_key(key), i), file_);
  return out;
}

std::optional<std::string> TomlSection::choice(const std::string& key, const std::vector<std::string>& choices) {
  const auto value = string(key);
  if (!value || std::find(choices.begin(), choices.end(), *value) != choices.end()) return value;
  std::string list;
  for (const auto& c : choices) list += (list.empty() ? "\"" : ", \"") + c + "\"";
  fail(key, "expected one of " + list);
}

void TomlSection::finish() const {
  for (const auto& [k, v] : *table_) {
    const std::string key(k.str());
    if (read_.count(key)) continue;
    std::string suggestion;
    std::size_t best = 3;  // suggest only close matches
    for (const auto& known : read_) {
      const std::size_t d = edit_distance(key, known);
      if (d < best) {
        best = d;
        suggestion = known;
      }
    }
    std::string message = fmt::format("{}: unknown key", where(key));
    if (!suggestion.empty())
      message += fmt::format("; did you mean '{}'?", full_key(suggestion));
    else {
      std::string known;
      for (const auto& r : read_) known += (known.empty() ? "" : ", ") + r;
      message += fmt::format(" (known keys here: {})", known.empty() ? "none" : known);
    }
    throw InputError(message);
  }
}

std::size_t edit_distance(const std::string& a, const std::string& b) {
  std::vector<std::size_t> prev(b.size() + 1), cur(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) prev[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    cur[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j)
      cur[j] = std::min(
          {prev[j] + 1, cur[j - 1] + 1, prev[j - 1] + (std::tolower(a[i - 1]) == std::tolower(b[j - 1]) ? 0 : 1)});
    std::swap(prev, cur);
  }
  return prev[b.size()];
}

}  // namespace roller
