#pragma once
// One list of names per option enum: the scene loader parses with it, the scene writer and the
// messages print with it, and the list of choices in an error message comes from it. An enum
// opts in by specialising EnumNames next to its declaration:
//   template <> struct EnumNames<IpoptFriction> {
//     static constexpr std::array<std::pair<IpoptFriction, const char*>, 2> names{
//         {{IpoptFriction::Split, "split"}, {IpoptFriction::Regularized, "regularized"}}};
//   };
#include <array>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace roller {

template <class E>
struct EnumNames;

template <class E>
const char* enum_name(E value) {
  for (const auto& [v, name] : EnumNames<E>::names)
    if (v == value) return name;
  return "?";
}

template <class E>
std::optional<E> parse_enum(std::string_view text) {
  for (const auto& [v, name] : EnumNames<E>::names)
    if (text == name) return v;
  return std::nullopt;
}

// Every name, in declaration order (the choices of a scene key).
template <class E>
std::vector<std::string> enum_names() {
  std::vector<std::string> out;
  for (const auto& [v, name] : EnumNames<E>::names) out.emplace_back(name);
  return out;
}

}  // namespace roller
