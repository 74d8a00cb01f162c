#include "scene_from_python.hpp"

#include <sstream>

#include <fmt/format.h>
#include <toml++/toml.h>

#include "roller/core/error.hpp"

namespace py = pybind11;

namespace roller::python {

namespace {

// Python's bool is an int: it is tested first.
std::unique_ptr<toml::node> to_node(const py::handle& value, const std::string& key) {
  if (py::isinstance<py::bool_>(value)) return std::make_unique<toml::value<bool>>(value.cast<bool>());
  if (py::isinstance<py::int_>(value)) return std::make_unique<toml::value<int64_t>>(value.cast<int64_t>());
  if (py::isinstance<py::float_>(value)) return std::make_unique<toml::value<double>>(value.cast<double>());
  if (py::isinstance<py::str>(value)) return std::make_unique<toml::value<std::string>>(value.cast<std::string>());
  if (py::isinstance<py::dict>(value)) {
    auto table = std::make_unique<toml::table>();
    for (const auto& [k, v] : value.cast<py::dict>()) {
      const std::string name = py::str(k).cast<std::string>();
      table->insert(name, std::move(*to_node(v, key + "." + name)));
    }
    return table;
  }
  if (py::isinstance<py::list>(value) || py::isinstance<py::tuple>(value)) {
    auto array = std::make_unique<toml::array>();
    int i = 0;
    for (const py::handle& item : value) array->push_back(std::move(*to_node(item, fmt::format("{}[{}]", key, i++))));
    return array;
  }
  // numpy scalars and other numbers: by their float value.
  if (py::hasattr(value, "__float__")) return std::make_unique<toml::value<double>>(value.cast<double>());
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
  holder.push_back(std::move(*to_node(value, key)));
  std::ostringstream out;
  out << toml::toml_formatter{holder};
  std::string text = out.str();
  const std::size_t first = text.find('['), last = text.rfind(']');
  text = text.substr(first + 1, last - first - 1);
  const std::size_t begin = text.find_first_not_of(' '), end = text.find_last_not_of(' ');
  return begin == std::string::npos ? std::string() : text.substr(begin, end - begin + 1);
}

std::string toml_document(const py::dict& scene) {
  std::unique_ptr<toml::node> node = to_node(scene, "scene");
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
