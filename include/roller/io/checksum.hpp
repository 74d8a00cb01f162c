#pragma once
// The checksum of roller's state files: FNV-1a over 64 bits, as 16 lowercase hex digits. It guards
// against damaged files, not against tampering (docs/scenes.md, Outputs: `checkpoint.cbor`).
#include <string>
#include <string_view>

namespace roller {

std::string fnv1a_hex(std::string_view bytes);

}  // namespace roller
