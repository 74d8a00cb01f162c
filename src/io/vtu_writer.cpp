// VTK XML UnstructuredGrid (.vtu) and collection (.pvd) writers.
//
// File layout (VTK XML format 0.1, byte_order LittleEndian, header_type UInt64): every
// DataArray is inline, format="binary". Uncompressed: base64 of one stream [UInt64 payload byte
// count][payload bytes]. Compressed (compressor="vtkZLibDataCompressor", the default): the payload
// cut into 32 KiB blocks, each deflated; base64 of the header [UInt64 number of blocks, block
// size, size of the last partial block (0 if full), compressed size of each block] followed by
// base64 of the compressed blocks, as VTK's writer does. Values are serialised byte by byte in
// little-endian order so the output does not depend on the host's endianness.
//
// Both writers assemble the whole document in memory, write it to "<path>.tmp" and rename it
// over <path> (atomic on POSIX within one file system), so a crash or a thrown error never
// leaves a half-written file where ParaView would look.
#include "roller/io/vtu_writer.hpp"

#include "roller/io/atomic_file.hpp"

#include <fmt/format.h>
#include <zlib.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <set>
#include <stdexcept>
#include <system_error>
#include <utility>

namespace roller {

namespace {

namespace fs = std::filesystem;

constexpr std::uint8_t kVtkTriangle = 5;
constexpr std::uint8_t kVtkQuad = 9;

void append_le(std::string& bytes, std::uint64_t value, int n_bytes) {
  for (int b = 0; b < n_bytes; ++b) {
    bytes.push_back(static_cast<char>((value >> (8 * b)) & 0xFFu));
  }
}

void append_f64(std::string& bytes, double value) {
  std::uint64_t bits = 0;
  static_assert(sizeof(bits) == sizeof(value), "Float64 must be 8 bytes");
  std::memcpy(&bits, &value, sizeof(bits));
  append_le(bytes, bits, 8);
}

void append_i64(std::string& bytes, std::int64_t value) { append_le(bytes, static_cast<std::uint64_t>(value), 8); }

std::string base64(const std::string& bytes) {
  static const char* const table = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  out.reserve((bytes.size() + 2) / 3 * 4);
  std::size_t i = 0;
  for (; i + 2 < bytes.size(); i += 3) {
    const std::uint32_t v = (std::uint32_t(std::uint8_t(bytes[i])) << 16) |
                            (std::uint32_t(std::uint8_t(bytes[i + 1])) << 8) |
                            std::uint32_t(std::uint8_t(bytes[i + 2]));
    out.push_back(table[(v >> 18) & 63]);
    out.push_back(table[(v >> 12) & 63]);
    out.push_back(table[(v >> 6) & 63]);
    out.push_back(table[v & 63]);
  }
  const std::size_t rest = bytes.size() - i;
  if (rest > 0) {
    std::uint32_t v = std::uint32_t(std::uint8_t(bytes[i])) << 16;
    if (rest == 2) v |= std::uint32_t(std::uint8_t(bytes[i + 1])) << 8;
    out.push_back(table[(v >> 18) & 63]);
    out.push_back(table[(v >> 12) & 63]);
    out.push_back(rest == 2 ? table[(v >> 6) & 63] : '=');
    out.push_back('=');
  }
  return out;
}

// Base64 of [UInt64 byte count][payload], as VTK expects for uncompressed inline binary data.
std::string encode_block(const std::string& payload) {
  std::string bytes;
  bytes.reserve(8 + payload.size());
  append_le(bytes, static_cast<std::uint64_t>(payload.size()), 8);
  bytes += payload;
  return base64(bytes);
}

// The zlib-compressed form of one DataArray (header comment).
std::string encode_compressed(const std::string& payload) {
  constexpr std::size_t kBlock = 32768;
  const std::size_t n_blocks = (payload.size() + kBlock - 1) / kBlock;
  std::string header, data;
  append_le(header, n_blocks, 8);
  append_le(header, kBlock, 8);
  append_le(header, payload.size() % kBlock, 8);
  std::string buffer(compressBound(kBlock), '\0');
  for (std::size_t b = 0; b < n_blocks; ++b) {
    const std::size_t begin = b * kBlock;
    const std::size_t size = std::min(kBlock, payload.size() - begin);
    uLongf compressed = static_cast<uLongf>(buffer.size());
    const int rc =
        compress2(reinterpret_cast<Bytef*>(buffer.data()), &compressed,
                  reinterpret_cast<const Bytef*>(payload.data() + begin), static_cast<uLong>(size), Z_BEST_SPEED);
    if (rc != Z_OK) throw std::runtime_error(fmt::format("write_vtu: zlib compress2 failed ({})", rc));
    append_le(header, compressed, 8);
    data.append(buffer.data(), compressed);
  }
  return base64(header) + base64(data);
}

std::string encode(const std::string& payload, VtuCompression compression) {
  return compression == VtuCompression::ZLib ? encode_compressed(payload) : encode_block(payload);
}

// Escapes text for use inside a double-quoted XML attribute.
std::string xml_attr(const std::string& text) {
  std::string out;
  out.reserve(text.size());
  for (const char c : text) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      case '\'': out += "&apos;"; break;
      case '\n': out += "&#10;"; break;
      case '\r': out += "&#13;"; break;
      case '\t': out += "&#9;"; break;
      default: out.push_back(c);
    }
  }
  return out;
}

// Checks a field against the number of tuples it must hold; `kind` is "point" or "cell".
void check_field(const VtuField& field, Index n_tuples, const char* kind, std::set<std::string>& seen_names) {
  if (field.name.empty()) {
    throw std::invalid_argument(
        fmt::format("write_vtu: a {} data field has an empty name; give every field a name", kind));
  }
  if (!seen_names.insert(field.name).second) {
    throw std::invalid_argument(
        fmt::format("write_vtu: {} data field '{}' appears twice; field names must be unique", kind, field.name));
  }
  if (field.n_components < 1) {
    throw std::invalid_argument(fmt::format("write_vtu: {} data field '{}' has n_components = {}; expected >= 1", kind,
                                            field.name, field.n_components));
  }
  const std::size_t expected = static_cast<std::size_t>(n_tuples) * static_cast<std::size_t>(field.n_components);
  if (field.values.size() != expected) {
    throw std::invalid_argument(
        fmt::format("write_vtu: {} data field '{}' has {} values; expected {} ({} {}s x {} components)", kind,
                    field.name, field.values.size(), expected, n_tuples,
                    std::string(kind) == "point" ? "node" : "element", field.n_components));
  }
  if (!field.component_names.empty() && field.component_names.size() != static_cast<std::size_t>(field.n_components)) {
    throw std::invalid_argument(
        fmt::format("write_vtu: {} data field '{}' has {} component names for {} components; give one "
                    "name per component or none",
                    kind, field.name, field.component_names.size(), field.n_components));
  }
  for (std::size_t i = 0; i < field.values.size(); ++i) {
    if (!std::isfinite(field.values[i])) {
      const std::size_t nc = static_cast<std::size_t>(field.n_components);
      throw std::invalid_argument(fmt::format(
          "write_vtu: {} data field '{}' has a non-finite value ({}) at index {} ({} {}, "
          "component {}); refusing to write NaN/Inf",
          kind, field.name, field.values[i], i, std::string(kind) == "point" ? "node" : "element", i / nc, i % nc));
    }
  }
}

void append_field(std::string& xml, const VtuField& field, VtuCompression compression) {
  std::string payload;
  payload.reserve(8 * field.values.size());
  for (const Real v : field.values) append_f64(payload, v);
  xml += fmt::format(R"(        <DataArray type="Float64" Name="{}" NumberOfComponents="{}")", xml_attr(field.name),
                     field.n_components);
  for (std::size_t c = 0; c < field.component_names.size(); ++c) {
    xml += fmt::format(R"( ComponentName{}="{}")", c, xml_attr(field.component_names[c]));
  }
  xml += " format=\"binary\">\n          ";
  xml += encode(payload, compression);
  xml += "\n        </DataArray>\n";
}

}  // namespace

namespace {

// The coordinates and the connectivity checked against the mesh before anything is written.
void check_mesh(const Mesh& mesh, const std::vector<Vec2>& coordinates) {
  const Index n_nodes = mesh.n_nodes();
  if (static_cast<Index>(coordinates.size()) != n_nodes) {
    throw std::invalid_argument(
        fmt::format("write_vtu: 'coordinates' has {} points; the mesh has {} nodes", coordinates.size(), n_nodes));
  }
  for (std::size_t i = 0; i < coordinates.size(); ++i) {
    for (int d = 0; d < 2; ++d) {
      if (!std::isfinite(coordinates[i][d])) {
        throw std::invalid_argument(
            fmt::format("write_vtu: 'coordinates' has a non-finite value ({}) at index {} (node {}, "
                        "component {}); refusing to write NaN/Inf",
                        coordinates[i][d], 2 * i + static_cast<std::size_t>(d), i, d));
      }
    }
  }
  const std::size_t npe = static_cast<std::size_t>(nodes_per_element(mesh.element_type));
  for (std::size_t e = 0; e < mesh.elements.size(); ++e) {
    const auto& conn = mesh.elements[e];
    if (conn.size() != npe) {
      throw std::invalid_argument(fmt::format("write_vtu: element {} has {} nodes; a {} mesh needs {}", e, conn.size(),
                                              mesh.element_type == ElementType::T3 ? "T3" : "Q4", npe));
    }
    for (const Index node : conn) {
      if (node < 0 || node >= n_nodes) {
        throw std::invalid_argument(
            fmt::format("write_vtu: element {} refers to node {}; valid nodes are 0..{}", e, node, n_nodes - 1));
      }
    }
  }
}

void append_points(std::string& xml, const std::vector<Vec2>& coordinates, VtuCompression compression) {
  std::string points;
  points.reserve(24 * coordinates.size());
  for (const Vec2& x : coordinates) {
    append_f64(points, x[0]);
    append_f64(points, x[1]);
    append_f64(points, 0.0);
  }
  xml += "      <Points>\n";
  xml +=
      "        <DataArray type=\"Float64\" Name=\"Points\" NumberOfComponents=\"3\" "
      "format=\"binary\">\n          ";
  xml += encode(points, compression);
  xml += "\n        </DataArray>\n";
  xml += "      </Points>\n";
}

void append_cells(std::string& xml, const Mesh& mesh, VtuCompression compression) {
  const std::size_t npe = static_cast<std::size_t>(nodes_per_element(mesh.element_type));
  std::string connectivity;
  std::string offsets;
  std::string types;
  connectivity.reserve(8 * npe * mesh.elements.size());
  offsets.reserve(8 * mesh.elements.size());
  types.reserve(mesh.elements.size());
  const std::uint8_t cell_type = mesh.element_type == ElementType::T3 ? kVtkTriangle : kVtkQuad;
  std::int64_t offset = 0;
  for (const auto& conn : mesh.elements) {
    for (const Index node : conn) append_i64(connectivity, node);
    offset += static_cast<std::int64_t>(conn.size());
    append_i64(offsets, offset);
    types.push_back(static_cast<char>(cell_type));
  }
  xml += "      <Cells>\n";
  xml += "        <DataArray type=\"Int64\" Name=\"connectivity\" format=\"binary\">\n          ";
  xml += encode(connectivity, compression);
  xml += "\n        </DataArray>\n";
  xml += "        <DataArray type=\"Int64\" Name=\"offsets\" format=\"binary\">\n          ";
  xml += encode(offsets, compression);
  xml += "\n        </DataArray>\n";
  xml += "        <DataArray type=\"UInt8\" Name=\"types\" format=\"binary\">\n          ";
  xml += encode(types, compression);
  xml += "\n        </DataArray>\n";
  xml += "      </Cells>\n";
}

// The dataset's own arrays (one tuple each), as ASCII: a few numbers that any reader shows.
void append_field_data(std::string& xml, const std::vector<VtuField>& field_data) {
  if (field_data.empty()) return;
  xml += "    <FieldData>\n";
  for (const VtuField& f : field_data) {
    xml += fmt::format(
        R"(      <DataArray type="Float64" Name="{}" NumberOfTuples="1" NumberOfComponents="{}" format="ascii">)",
        xml_attr(f.name), f.n_components);
    for (const Real v : f.values) xml += fmt::format(" {:.17g}", v);
    xml += " </DataArray>\n";
  }
  xml += "    </FieldData>\n";
}

}  // namespace

void write_vtu(const std::filesystem::path& path, const Mesh& mesh, const std::vector<Vec2>& coordinates,
               const std::vector<VtuField>& point_data, const std::vector<VtuField>& cell_data,
               VtuCompression compression, const std::vector<VtuField>& field_data) {
  const Index n_nodes = mesh.n_nodes();
  const Index n_elements = mesh.n_elements();
  // Validate everything before touching the file system.
  check_mesh(mesh, coordinates);
  std::set<std::string> point_names;
  for (const auto& f : point_data) check_field(f, n_nodes, "point", point_names);
  std::set<std::string> cell_names;
  for (const auto& f : cell_data) check_field(f, n_elements, "cell", cell_names);
  std::set<std::string> field_names;
  for (const auto& f : field_data) check_field(f, 1, "field", field_names);

  std::string xml;
  xml += "<?xml version=\"1.0\"?>\n";
  xml += fmt::format(
      "<VTKFile type=\"UnstructuredGrid\" version=\"0.1\" byte_order=\"LittleEndian\" "
      "header_type=\"UInt64\"{}>\n",
      compression == VtuCompression::ZLib ? " compressor=\"vtkZLibDataCompressor\"" : "");
  xml += "  <UnstructuredGrid>\n";
  append_field_data(xml, field_data);
  xml += fmt::format("    <Piece NumberOfPoints=\"{}\" NumberOfCells=\"{}\">\n", n_nodes, n_elements);
  xml += "      <PointData>\n";
  for (const auto& f : point_data) append_field(xml, f, compression);
  xml += "      </PointData>\n";
  xml += "      <CellData>\n";
  for (const auto& f : cell_data) append_field(xml, f, compression);
  xml += "      </CellData>\n";
  append_points(xml, coordinates, compression);
  append_cells(xml, mesh, compression);
  xml += "    </Piece>\n";
  xml += "  </UnstructuredGrid>\n";
  xml += "</VTKFile>\n";

  write_file_atomically(path, xml);
}

void write_roller_vtp(const std::filesystem::path& path, const Vec2& centre, Real radius, Real angle,
                      const std::vector<VtuField>& field_data, int segments) {
  std::set<std::string> field_names;
  for (const auto& f : field_data) check_field(f, 1, "field", field_names);
  if (!centre.allFinite() || !std::isfinite(radius) || !std::isfinite(angle))
    throw std::invalid_argument("write_roller_vtp: a non-finite centre, radius or angle; refusing to write NaN/Inf");
  // Points 0..segments-1 on the circle, then the centre; line 1 the closed circle, line 2 the
  // radius from the centre to the rim point at the rotation angle.
  std::string points, circle;
  for (int k = 0; k < segments; ++k) {
    const Real t = angle + 2.0 * M_PI * k / segments;
    points += fmt::format(" {:.17g} {:.17g} 0", centre.x() + radius * std::cos(t), centre.y() + radius * std::sin(t));
    circle += fmt::format(" {}", k);
  }
  points += fmt::format(" {:.17g} {:.17g} 0", centre.x(), centre.y());
  std::string xml = "<?xml version=\"1.0\"?>\n";
  xml += "<VTKFile type=\"PolyData\" version=\"0.1\" byte_order=\"LittleEndian\" header_type=\"UInt64\">\n";
  xml += "  <PolyData>\n";
  append_field_data(xml, field_data);
  xml += fmt::format(
      "    <Piece NumberOfPoints=\"{}\" NumberOfVerts=\"0\" NumberOfLines=\"2\" NumberOfStrips=\"0\" "
      "NumberOfPolys=\"0\">\n",
      segments + 1);
  xml += "      <Points>\n        <DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">" + points +
         " </DataArray>\n      </Points>\n";
  xml += "      <Lines>\n        <DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">" + circle +
         fmt::format(" 0 {} 0 </DataArray>\n", segments);
  xml += fmt::format(
      "        <DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\"> {} {} </DataArray>\n      </Lines>\n",
      segments + 1, segments + 3);
  xml += "    </Piece>\n  </PolyData>\n</VTKFile>\n";
  write_file_atomically(path, xml);
}

PvdSeries::PvdSeries(std::filesystem::path pvd_path) : path_(std::move(pvd_path)) {
  // An empty collection at once: ParaView can open it, and an unwritable path fails here,
  // before the first (possibly expensive) step rather than after it.
  rewrite();
}

void PvdSeries::add(Real time, const std::filesystem::path& vtu_file) {
  if (!std::isfinite(time)) {
    throw std::invalid_argument(fmt::format("PvdSeries::add: time {} for '{}' is not finite", time, vtu_file.string()));
  }
  const fs::path folder = fs::absolute(path_).parent_path().lexically_normal();
  const fs::path file = fs::absolute(vtu_file).lexically_normal();
  const fs::path relative = file.lexically_relative(folder);
  const bool inside = !relative.empty() && *relative.begin() != "..";
  // In time order whatever order the files come in (the background writer finishes step n+1's
  // file before step n's when step n's is larger); equal times keep their order of arrival.
  const auto at = std::upper_bound(entries_.begin(), entries_.end(), time,
                                   [](Real t, const std::pair<Real, std::string>& e) { return t < e.first; });
  const auto added = entries_.emplace(at, time, inside ? relative.generic_string() : file.generic_string());
  try {
    rewrite();
  } catch (...) {
    entries_.erase(added);  // keep the in-memory series equal to the file on disk
    throw;
  }
}

void PvdSeries::rewrite() const {
  std::string xml;
  xml += "<?xml version=\"1.0\"?>\n";
  xml += "<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n";
  xml += "  <Collection>\n";
  for (const auto& [time, file] : entries_) {
    xml += fmt::format("    <DataSet timestep=\"{:.17g}\" group=\"\" part=\"0\" file=\"{}\"/>\n", time, xml_attr(file));
  }
  xml += "  </Collection>\n";
  xml += "</VTKFile>\n";
  write_file_atomically(path_, xml);
}

}  // namespace roller
