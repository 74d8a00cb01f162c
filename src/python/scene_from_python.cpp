#include "scene_from_python.hpp"

#include <sstream>

#include <fmt/format.h>
#include <toml++/toml.h>

#include "roller/core/error.hpp"

namespace py = pybind11;

namespace roller::python {

namespace {

// As the scene file's reader (scene_loader.cpp): a scene needs a handful of levels, and each level
// is a C++ frame here, so a dict nested 100,000 levels deep would overflow the stack.
constexpr int kMaxNesting = 100;

// A Python integer (int, or numpy's, which have __index__) as a 64-bit TOML integer.
std::unique_ptr<toml::node> integer_node(const py::handle& value, const std::string& key) {
  const py::int_ integer = py::reinterpret_steal<py::int_>(PyNumber_Index(value.ptr()));
  if (!integer) throw py::error_already_set();
  int overflow = 0;
  const long long v = PyLong_AsLongLongAndOverflow(integer.ptr(), &overflow);
  if (overflow != 0)
    throw InputError(
        fmt::format("{} = {}: an integer beyond 64 bits; expected a value such as the scene file "
                    "holds (docs/scenes.md)",
                    key, integer.attr("__str__")().cast<std::string>()));
  return std::make_unique<toml::value<int64_t>>(static_cast<int64_t>(v));
}

// Python's bool is an int: it is tested first; numpy's integers are ints (by __index__), its
// floats floats.
std::unique_ptr<toml::node> to_node(const py::handle& value, const std::string& key, int depth) {
  if (depth > kMaxNesting)
    throw InputError(
        fmt::format("{}: dicts or lists nested deeper than {} levels; expected a scene's tables "
                    "(docs/scenes.md)",
                    key.substr(0, 200), kMaxNesting));
  if (py::isinstance<py::bool_>(value) || py::type::handle_of(value).attr("__name__").cast<std::string>() == "bool_")
    return std::make_unique<toml::value<bool>>(py::bool_(py::reinterpret_borrow<py::object>(value)).cast<bool>());
  if (py::isinstance<py::str>(value)) return std::make_unique<toml::value<std::string>>(value.cast<std::string>());
  // numpy's arrays and scalars: as the Python lists and numbers they hold.
  if (py::hasattr(value, "ndim") && py::hasattr(value, "tolist")) {
    const py::object plain = value.attr("tolist")();
    if (!py::hasattr(plain, "ndim")) return to_node(plain, key, depth);
  }
  if (py::isinstance<py::int_>(value) || (!py::isinstance<py::float_>(value) && py::hasattr(value, "__index__")))
    return integer_node(value, key);
  if (py::isinstance<py::dict>(value)) {
    auto table = std::make_unique<toml::table>();
    for (const auto& [k, v] : value.cast<py::dict>()) {
      const std::string name = py::str(k).cast<std::string>();
      table->insert(name, std::move(*to_node(v, key + "." + name, depth + 1)));
    }
    return table;
  }
  if (py::isinstance<py::list>(value) || py::isinstance<py::tuple>(value)) {
    auto array = std::make_unique<toml::array>();
    int i = 0;
    for (const py::handle& item : value)
      array->push_back(std::move(*to_node(item, fmt::format("{}[{}]", key, i++), depth + 1)));
    return array;
  }
  // Python's and numpy's floats and other real numbers: by their float value.
  if (py::isinstance<py::float_>(value) || py::hasattr(value, "__float__"))
    return std::make_unique<toml::value<double>>(value.cast<double>());
  throw InputError(
      fmt::format("{}: a value of Python type '{}' cannot be a scene value (expected bool, int, "
                  "float, str, list or dict)",
                  key, py::str(value.get_type().attr("__name__")).cast<std::string>()));
}

}  // namespace

std::string toml_text(const py::handle& value, const std::string& key) {
  // Formatted as the one element of an array, where toml++ writes tables inline ({a = 1}), then
  // taken out of the array's brackets.
  toml::array holder;
  holder.push_back(std::move(*to_node(value, key, 0)));
  std::ostringstream out;
  out << toml::toml_formatter{holder};
  std::string text = out.str();
  const std::size_t first = text.find('['), last = text.rfind(']');
  text = text.substr(first + 1, last - first - 1);
  const std::size_t begin = text.find_first_not_of(' '), end = text.find_last_not_of(' ');
  return begin == std::string::npos ? std::string() : text.substr(begin, end - begin + 1);
}

std::string toml_document(const py::dict& scene) {
  std::unique_ptr<toml::node> node = to_node(scene, "scene", 0);
  std::ostringstream out;
  out << toml::toml_formatter{*node->as_table()};
  return out.str();
}

std::vector<SceneOverride> overrides_of(const py::dict& set) {
  std::vector<SceneOverride> out;
  for (const auto& [k, v] : set) {
    const std::string key = py::str(k).cast<std::string>();
    out.push_back({key, toml_text(v, key)});
  }
  return out;
}

}  // namespace roller::python
