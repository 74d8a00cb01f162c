#include "roller/io/checksum.hpp"

#include <fmt/format.h>

#include <cstdint>

namespace roller {

std::string fnv1a_hex(std::string_view bytes) {
  std::uint64_t h = 14695981039346656037ull;
  for (const char c : bytes) h = (h ^ static_cast<std::uint8_t>(c)) * 1099511628211ull;
  return fmt::format("{:016x}", h);
}

}  // namespace roller
