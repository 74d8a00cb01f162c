// Tests of the .vtu / .pvd writers: files are read back with an independent XML scanner and
// base64 decoder, and every number is compared exactly.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <random>
#include <regex>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "../support/temp_files.hpp"
#include "roller/io/vtu_writer.hpp"

#include <zlib.h>

namespace fs = std::filesystem;
using Catch::Matchers::Contains;
using namespace roller;

using test::read_text;

namespace {

bool have_python() { return fs::exists("/usr/bin/python3"); }

// True when python's minidom parses the file, i.e. the file is well-formed XML.
bool xml_well_formed(const fs::path& path) {
  const std::string command =
      "/usr/bin/python3 -c \"import xml.dom.minidom,sys; xml.dom.minidom.parse(sys.argv[1])\" '" + path.string() +
      "' > /dev/null 2>&1";
  return std::system(command.c_str()) == 0;
}

std::vector<std::uint8_t> base64_decode(const std::string& text) {
  auto value_of = [](char c) -> int {
    if (c >= 'A' && c <= 'Z') return c - 'A';
    if (c >= 'a' && c <= 'z') return c - 'a' + 26;
    if (c >= '0' && c <= '9') return c - '0' + 52;
    if (c == '+') return 62;
    if (c == '/') return 63;
    return -1;
  };
  std::vector<std::uint8_t> out;
  std::uint32_t buffer = 0;
  int bits = 0;
  for (const char c : text) {
    if (c == '=') break;
    if (c == ' ' || c == '\n' || c == '\r' || c == '\t') continue;
    const int v = value_of(c);
    if (v < 0) throw std::runtime_error(std::string("invalid base64 character '") + c + "'");
    buffer = (buffer << 6) | static_cast<std::uint32_t>(v);
    bits += 6;
    if (bits >= 8) {
      bits -= 8;
      out.push_back(static_cast<std::uint8_t>((buffer >> bits) & 0xFFu));
    }
  }
  return out;
}

std::uint64_t le_u64(const std::vector<std::uint8_t>& bytes, std::size_t at) {
  std::uint64_t v = 0;
  for (int b = 7; b >= 0; --b) v = (v << 8) | bytes.at(at + static_cast<std::size_t>(b));
  return v;
}

// One <DataArray> of the file: its opening tag and its decoded payload (header checked).
struct DataArray {
  std::string tag;
  std::vector<std::uint8_t> payload;

  std::string attribute(const std::string& name) const {
    const std::regex re("\\s" + name + "=\"([^\"]*)\"");
    std::smatch m;
    return std::regex_search(tag, m, re) ? m[1].str() : std::string("<missing>");
  }
  std::vector<double> as_f64() const {
    REQUIRE(payload.size() % 8 == 0);
    std::vector<double> v(payload.size() / 8);
    for (std::size_t i = 0; i < v.size(); ++i) {
      const std::uint64_t bits = le_u64(payload, 8 * i);
      std::memcpy(&v[i], &bits, 8);
    }
    return v;
  }
  std::vector<std::int64_t> as_i64() const {
    REQUIRE(payload.size() % 8 == 0);
    std::vector<std::int64_t> v(payload.size() / 8);
    for (std::size_t i = 0; i < v.size(); ++i) {
      v[i] = static_cast<std::int64_t>(le_u64(payload, 8 * i));
    }
    return v;
  }
  std::vector<int> as_u8() const { return std::vector<int>(payload.begin(), payload.end()); }
};

DataArray find_array(const std::string& xml, const std::string& name) {
  std::size_t pos = 0;
  while ((pos = xml.find("<DataArray", pos)) != std::string::npos) {
    const std::size_t tag_end = xml.find('>', pos);
    REQUIRE(tag_end != std::string::npos);
    DataArray a;
    a.tag = xml.substr(pos, tag_end - pos + 1);
    if (a.attribute("Name") == name) {
      const std::size_t close = xml.find("</DataArray>", tag_end);
      REQUIRE(close != std::string::npos);
      REQUIRE(a.attribute("format") == "binary");
      std::string text = xml.substr(tag_end + 1, close - tag_end - 1);
      text.erase(std::remove_if(text.begin(), text.end(), [](char c) { return std::isspace(c); }), text.end());
      if (xml.find("compressor=\"vtkZLibDataCompressor\"") == std::string::npos) {
        const auto bytes = base64_decode(text);
        REQUIRE(bytes.size() >= 8);
        const std::uint64_t n = le_u64(bytes, 0);
        REQUIRE(n == bytes.size() - 8);  // UInt64 header = payload byte count
        a.payload.assign(bytes.begin() + 8, bytes.end());
        return a;
      }
      // Compressed: base64 of [blocks, block size, last block size, compressed sizes...], then
      // base64 of the deflated blocks; the header's encoded length follows from its block count.
      const std::uint64_t n_blocks = le_u64(base64_decode(text.substr(0, 32)), 0);
      const std::size_t header_bytes = 8 * (3 + n_blocks);
      const std::size_t header_chars = 4 * ((header_bytes + 2) / 3);
      const auto header = base64_decode(text.substr(0, header_chars));
      const auto data = base64_decode(text.substr(header_chars));
      const std::uint64_t block = le_u64(header, 8), last = le_u64(header, 16);
      std::size_t at = 0;
      for (std::uint64_t b = 0; b < n_blocks; ++b) {
        const std::uint64_t compressed = le_u64(header, 24 + 8 * b);
        uLongf size = static_cast<uLongf>(b + 1 == n_blocks && last != 0 ? last : block);
        std::vector<std::uint8_t> out(size);
        REQUIRE(uncompress(out.data(), &size, data.data() + at, static_cast<uLong>(compressed)) == Z_OK);
        REQUIRE(size == (b + 1 == n_blocks && last != 0 ? last : block));
        a.payload.insert(a.payload.end(), out.begin(), out.end());
        at += compressed;
      }
      REQUIRE(at == data.size());
      return a;
    }
    pos = tag_end;
  }
  FAIL("no DataArray named '" << name << "'");
  return {};
}

std::string piece_attribute(const std::string& xml, const std::string& name) {
  const std::regex re("<Piece[^>]*\\s" + name + "=\"([0-9]+)\"");
  std::smatch m;
  return std::regex_search(xml, m, re) ? m[1].str() : std::string("<missing>");
}

template <class E, class F>
std::string thrown_message(F&& f) {
  try {
    f();
  } catch (const E& e) {
    return e.what();
  }
  return "<nothing thrown>";
}

// 3 x 2 nodes, two unit squares side by side, or each square split into two triangles
// (then only the left square is used, giving 4 nodes and 2 triangles).
Mesh two_element_mesh(ElementType type) {
  Mesh mesh;
  mesh.element_type = type;
  if (type == ElementType::Q4) {
    mesh.nodes = {Vec2(0, 0), Vec2(1, 0), Vec2(2, 0), Vec2(0, 1), Vec2(1, 1), Vec2(2, 1)};
    mesh.elements = {{0, 1, 4, 3}, {1, 2, 5, 4}};
  } else {
    mesh.nodes = {Vec2(0, 0), Vec2(1, 0), Vec2(1, 1), Vec2(0, 1)};
    mesh.elements = {{0, 1, 2}, {0, 2, 3}};
  }
  return mesh;
}

// Values that survive only an exact round trip: thirds, tiny, huge, negative zero.
double awkward(std::size_t i) {
  static const double pool[] = {1.0 / 3.0, -0.1, 2.5e-300,   -1.7976931348623157e300,
                                0.0,       -0.0, 123456.789, 4.9406564584124654e-324};
  return pool[i % 8] * (1.0 + static_cast<double>(i) * 1e-3);
}

VtuField make_field(const std::string& name, int n_components, std::size_t n_tuples, std::size_t seed,
                    std::vector<std::string> component_names = {}) {
  VtuField f;
  f.name = name;
  f.n_components = n_components;
  f.values.resize(n_tuples * static_cast<std::size_t>(n_components));
  for (std::size_t i = 0; i < f.values.size(); ++i) f.values[i] = awkward(i + seed);
  f.component_names = std::move(component_names);
  return f;
}

void check_bitwise_equal(const std::vector<double>& got, const std::vector<double>& expected) {
  REQUIRE(got.size() == expected.size());
  for (std::size_t i = 0; i < got.size(); ++i) {
    INFO("index " << i);
    CHECK(got[i] == expected[i]);
    CHECK(std::signbit(got[i]) == std::signbit(expected[i]));
  }
}

void check_round_trip(ElementType type, VtuCompression compression) {
  test::TempDir dir("roller_vtu_test");
  const fs::path file = dir.path() / "mesh.vtu";
  const Mesh mesh = two_element_mesh(type);
  const std::size_t n_nodes = mesh.nodes.size();
  const std::size_t n_cells = mesh.elements.size();

  std::vector<Vec2> coordinates;  // current configuration, different from mesh.nodes
  for (std::size_t i = 0; i < n_nodes; ++i) {
    coordinates.push_back(mesh.nodes[i] + Vec2(awkward(i), awkward(i + 3)));
  }
  const std::vector<VtuField> point_data = {make_field("temperature", 1, n_nodes, 0),
                                            make_field("displacement", 3, n_nodes, 1, {"x", "y", "z"}),
                                            make_field("stress", 4, n_nodes, 2, {"xx", "yy", "zz", "xy"})};
  const std::vector<VtuField> cell_data = {make_field("plastic_strain", 1, n_cells, 5)};

  write_vtu(file, mesh, coordinates, point_data, cell_data, compression);

  REQUIRE(fs::exists(file));
  const std::string xml = read_text(file);
  CHECK_THAT(xml, Contains("type=\"UnstructuredGrid\""));
  CHECK_THAT(xml, Contains("version=\"0.1\""));
  CHECK_THAT(xml, Contains("byte_order=\"LittleEndian\""));
  CHECK_THAT(xml, Contains("header_type=\"UInt64\""));
  CHECK(piece_attribute(xml, "NumberOfPoints") == std::to_string(n_nodes));
  CHECK(piece_attribute(xml, "NumberOfCells") == std::to_string(n_cells));

  const DataArray points = find_array(xml, "Points");
  CHECK(points.attribute("type") == "Float64");
  CHECK(points.attribute("NumberOfComponents") == "3");
  std::vector<double> expected_points;
  for (const Vec2& x : coordinates) {
    expected_points.insert(expected_points.end(), {x[0], x[1], 0.0});
  }
  check_bitwise_equal(points.as_f64(), expected_points);

  const DataArray connectivity = find_array(xml, "connectivity");
  const DataArray offsets = find_array(xml, "offsets");
  const DataArray types = find_array(xml, "types");
  CHECK(connectivity.attribute("type") == "Int64");
  CHECK(offsets.attribute("type") == "Int64");
  CHECK(types.attribute("type") == "UInt8");
  std::vector<std::int64_t> expected_connectivity;
  for (const auto& e : mesh.elements) {
    expected_connectivity.insert(expected_connectivity.end(), e.begin(), e.end());
  }
  CHECK(connectivity.as_i64() == expected_connectivity);
  if (type == ElementType::Q4) {
    CHECK(offsets.as_i64() == std::vector<std::int64_t>{4, 8});
    CHECK(types.as_u8() == std::vector<int>{9, 9});
  } else {
    CHECK(offsets.as_i64() == std::vector<std::int64_t>{3, 6});
    CHECK(types.as_u8() == std::vector<int>{5, 5});
  }

  for (const auto& f : point_data) {
    INFO("point field " << f.name);
    const DataArray a = find_array(xml, f.name);
    CHECK(a.attribute("type") == "Float64");
    CHECK(a.attribute("NumberOfComponents") == std::to_string(f.n_components));
    for (std::size_t c = 0; c < f.component_names.size(); ++c) {
      CHECK(a.attribute("ComponentName" + std::to_string(c)) == f.component_names[c]);
    }
    check_bitwise_equal(a.as_f64(), f.values);
  }
  CHECK(find_array(xml, "temperature").attribute("ComponentName0") == "<missing>");
  // Point data arrays sit inside <PointData>, cell data inside <CellData>.
  const auto point_begin = xml.find("<PointData>");
  const auto point_end = xml.find("</PointData>");
  const auto cell_begin = xml.find("<CellData>");
  const auto cell_end = xml.find("</CellData>");
  REQUIRE(point_begin != std::string::npos);
  REQUIRE(cell_begin != std::string::npos);
  const auto stress_at = xml.find("Name=\"stress\"");
  const auto plastic_at = xml.find("Name=\"plastic_strain\"");
  CHECK((point_begin < stress_at && stress_at < point_end));
  CHECK((cell_begin < plastic_at && plastic_at < cell_end));

  const DataArray plastic = find_array(xml, "plastic_strain");
  CHECK(plastic.attribute("NumberOfComponents") == "1");
  check_bitwise_equal(plastic.as_f64(), cell_data[0].values);

  REQUIRE(have_python());  // scripts/install-deps.sh installs it; without it nothing is checked
  CHECK(xml_well_formed(file));
  // Only the target remains: the temporary file was renamed, not left beside it.
  std::size_t n_entries = 0;
  for (const auto& entry : fs::directory_iterator(dir.path())) {
    (void)entry;
    ++n_entries;
  }
  CHECK(n_entries == 1);
}

}  // namespace

TEST_CASE("write_vtu writes a Q4 mesh whose arrays decode to exactly the numbers given", "[io]") {
  check_round_trip(ElementType::Q4, VtuCompression::ZLib);
  check_round_trip(ElementType::Q4, VtuCompression::None);
}

TEST_CASE("write_vtu writes a T3 mesh whose arrays decode to exactly the numbers given", "[io]") {
  check_round_trip(ElementType::T3, VtuCompression::ZLib);
  check_round_trip(ElementType::T3, VtuCompression::None);
}

TEST_CASE("write_vtu compresses a large array in several blocks that inflate to the exact values", "[io]") {
  test::TempDir dir("roller_vtu_test");
  const fs::path file = dir.path() / "big.vtu";
  const Mesh mesh = two_element_mesh(ElementType::Q4);
  // 6 nodes x 5001 components x 8 bytes = 240 kB: 7 full 32 KiB blocks and a partial one.
  const VtuField big = make_field("big", 5001, mesh.nodes.size(), 7);
  write_vtu(file, mesh, mesh.nodes, {big}, {});
  const std::string xml = read_text(file);
  CHECK_THAT(xml, Contains("compressor=\"vtkZLibDataCompressor\""));
  check_bitwise_equal(find_array(xml, "big").as_f64(), big.values);
  CHECK(fs::file_size(file) < 8 * big.values.size());  // smaller than the raw values
}

TEST_CASE("the python XML check used by these tests rejects a malformed file", "[io]") {
  REQUIRE(have_python());
  test::TempDir dir("roller_vtu_test");
  const fs::path bad = dir.path() / "bad.xml";
  std::ofstream(bad) << "<a><b></a>\n";
  CHECK_FALSE(xml_well_formed(bad));
}

TEST_CASE("write_vtu escapes field and component names so the XML stays well-formed", "[io]") {
  test::TempDir dir("roller_vtu_test");
  const fs::path file = dir.path() / "names.vtu";
  const Mesh mesh = two_element_mesh(ElementType::Q4);
  VtuField f = make_field("a<b & \"c\"", 2, mesh.nodes.size(), 0, {"x'", "y>"});
  write_vtu(file, mesh, mesh.nodes, {f}, {});
  const std::string xml = read_text(file);
  CHECK_THAT(xml, Contains("Name=\"a&lt;b &amp; &quot;c&quot;\""));
  CHECK_THAT(xml, Contains("ComponentName0=\"x&apos;\""));
  CHECK_THAT(xml, Contains("ComponentName1=\"y&gt;\""));
  if (have_python()) CHECK(xml_well_formed(file));
}

TEST_CASE("write_vtu rejects fields whose size does not match, naming the field", "[io]") {
  test::TempDir dir("roller_vtu_test");
  const fs::path file = dir.path() / "bad.vtu";
  const Mesh mesh = two_element_mesh(ElementType::Q4);
  const auto ok_point = make_field("displacement", 3, mesh.nodes.size(), 0);
  const auto ok_cell = make_field("plastic_strain", 1, mesh.elements.size(), 0);

  SECTION("a point field one value short") {
    auto f = make_field("stress", 4, mesh.nodes.size(), 0);
    f.values.pop_back();
    const auto msg = thrown_message<std::invalid_argument>([&] {
      write_vtu(file, mesh, mesh.nodes, {ok_point, f}, {ok_cell});
    });
    CHECK_THAT(msg, Contains("stress"));
    CHECK_THAT(msg, Contains("23"));
    CHECK_THAT(msg, Contains("24"));
  }
  SECTION("a cell field sized per node") {
    auto f = make_field("equivalent_plastic_strain", 1, mesh.nodes.size(), 0);
    const auto msg = thrown_message<std::invalid_argument>([&] { write_vtu(file, mesh, mesh.nodes, {ok_point}, {f}); });
    CHECK_THAT(msg, Contains("equivalent_plastic_strain"));
  }
  SECTION("component names that do not match the component count") {
    auto f = make_field("velocity", 3, mesh.nodes.size(), 0, {"x", "y"});
    const auto msg = thrown_message<std::invalid_argument>([&] { write_vtu(file, mesh, mesh.nodes, {f}, {}); });
    CHECK_THAT(msg, Contains("velocity"));
  }
  SECTION("coordinates for fewer nodes than the mesh has") {
    std::vector<Vec2> coordinates = mesh.nodes;
    coordinates.pop_back();
    const auto msg = thrown_message<std::invalid_argument>([&] { write_vtu(file, mesh, coordinates, {}, {}); });
    CHECK_THAT(msg, Contains("coordinates"));
  }
  SECTION("an element with a node index out of range") {
    Mesh broken = mesh;
    broken.elements[1][2] = 6;
    const auto msg = thrown_message<std::invalid_argument>([&] { write_vtu(file, broken, broken.nodes, {}, {}); });
    CHECK_THAT(msg, Contains("element 1"));
  }
  CHECK_FALSE(fs::exists(file));
}

TEST_CASE("write_vtu refuses NaN and Inf, naming the field and the first bad index", "[io]") {
  test::TempDir dir("roller_vtu_test");
  const fs::path file = dir.path() / "step.vtu";
  const Mesh mesh = two_element_mesh(ElementType::Q4);
  auto stress = make_field("stress", 4, mesh.nodes.size(), 0);
  auto plastic = make_field("plastic_strain", 1, mesh.elements.size(), 0);

  // A good file first: a failed write must leave it untouched.
  write_vtu(file, mesh, mesh.nodes, {stress}, {plastic});
  const std::string before = read_text(file);

  SECTION("NaN in a point field") {
    stress.values[9] = std::numeric_limits<double>::quiet_NaN();
    stress.values[13] = std::numeric_limits<double>::quiet_NaN();
    const auto msg =
        thrown_message<std::invalid_argument>([&] { write_vtu(file, mesh, mesh.nodes, {stress}, {plastic}); });
    CHECK_THAT(msg, Contains("stress"));
    CHECK_THAT(msg, Contains("index 9"));
  }
  SECTION("Inf in a cell field") {
    plastic.values[1] = -std::numeric_limits<double>::infinity();
    const auto msg =
        thrown_message<std::invalid_argument>([&] { write_vtu(file, mesh, mesh.nodes, {stress}, {plastic}); });
    CHECK_THAT(msg, Contains("plastic_strain"));
    CHECK_THAT(msg, Contains("index 1"));
  }
  SECTION("NaN in the coordinates") {
    std::vector<Vec2> coordinates = mesh.nodes;
    coordinates[4][1] = std::numeric_limits<double>::quiet_NaN();
    const auto msg =
        thrown_message<std::invalid_argument>([&] { write_vtu(file, mesh, coordinates, {stress}, {plastic}); });
    CHECK_THAT(msg, Contains("coordinates"));
    CHECK_THAT(msg, Contains("index 9"));
  }
  CHECK(read_text(file) == before);
  CHECK_FALSE(fs::exists(dir.path() / "step.vtu.tmp"));
}

TEST_CASE("write_vtu to an unwritable path throws naming the path", "[io]") {
  test::TempDir dir("roller_vtu_test");
  const fs::path file = dir.path() / "no_such_folder" / "step.vtu";
  const Mesh mesh = two_element_mesh(ElementType::T3);
  const auto msg = thrown_message<std::runtime_error>([&] { write_vtu(file, mesh, mesh.nodes, {}, {}); });
  CHECK_THAT(msg, Contains(file.string()));
}

TEST_CASE("a mesh without fields or elements still gives a readable file", "[io]") {
  test::TempDir dir("roller_vtu_test");
  const fs::path file = dir.path() / "empty.vtu";
  Mesh mesh;
  mesh.element_type = ElementType::T3;
  write_vtu(file, mesh, {}, {}, {});
  const std::string xml = read_text(file);
  CHECK(piece_attribute(xml, "NumberOfPoints") == "0");
  CHECK(piece_attribute(xml, "NumberOfCells") == "0");
  CHECK(find_array(xml, "types").payload.empty());
  if (have_python()) CHECK(xml_well_formed(file));
}

TEST_CASE("PvdSeries lists its datasets in order with paths relative to its folder", "[io]") {
  test::TempDir dir("roller_vtu_test");
  fs::create_directory(dir.path() / "vtu");
  const fs::path pvd = dir.path() / "series.pvd";
  PvdSeries series(pvd);
  CHECK(series.path() == pvd);
  REQUIRE(fs::exists(pvd));  // an empty, valid collection from the start
  if (have_python()) CHECK(xml_well_formed(pvd));

  const std::vector<double> times = {0.0, 0.1, 1.0 / 3.0};
  for (std::size_t i = 0; i < times.size(); ++i) {
    series.add(times[i], dir.path() / "vtu" / ("step_" + std::to_string(i) + ".vtu"));
    const std::string xml = read_text(pvd);
    INFO(xml);
    CHECK_THAT(xml, Contains("type=\"Collection\""));
    std::size_t n_datasets = 0;
    for (std::size_t p = xml.find("<DataSet"); p != std::string::npos; p = xml.find("<DataSet", p + 1)) {
      ++n_datasets;
    }
    CHECK(n_datasets == i + 1);
    if (have_python()) CHECK(xml_well_formed(pvd));
  }

  const std::string xml = read_text(pvd);
  const std::regex re("<DataSet timestep=\"([^\"]*)\" group=\"\" part=\"0\" file=\"([^\"]*)\"/>");
  std::vector<std::string> stamps;
  std::vector<std::string> files;
  for (auto it = std::sregex_iterator(xml.begin(), xml.end(), re); it != std::sregex_iterator(); ++it) {
    stamps.push_back((*it)[1].str());
    files.push_back((*it)[2].str());
  }
  CHECK(files == std::vector<std::string>{"vtu/step_0.vtu", "vtu/step_1.vtu", "vtu/step_2.vtu"});
  REQUIRE(stamps.size() == 3);
  for (std::size_t i = 0; i < 3; ++i) {
    CHECK(std::strtod(stamps[i].c_str(), nullptr) == times[i]);  // enough digits to round-trip
  }
  CHECK(stamps[1] == "0.10000000000000001");
  CHECK_FALSE(fs::exists(dir.path() / "series.pvd.tmp"));
}

TEST_CASE("PvdSeries keeps an absolute path for a dataset outside its folder", "[io]") {
  test::TempDir dir("roller_vtu_test");
  fs::create_directory(dir.path() / "out");
  PvdSeries series(dir.path() / "out" / "series.pvd");
  const fs::path outside = dir.path() / "elsewhere" / "step.vtu";
  series.add(2.0, outside);
  const std::string xml = read_text(series.path());
  CHECK_THAT(xml, Contains("file=\"" + outside.lexically_normal().generic_string() + "\""));
  CHECK_THAT(xml, Contains("timestep=\"2\""));
}

TEST_CASE("PvdSeries in an unwritable place throws naming the path", "[io]") {
  test::TempDir dir("roller_vtu_test");
  const fs::path pvd = dir.path() / "missing" / "series.pvd";
  const auto msg = thrown_message<std::runtime_error>([&] { PvdSeries series(pvd); });
  CHECK_THAT(msg, Contains(pvd.string()));
}

TEST_CASE("PvdSeries lists its datasets in time order whatever order they are added in", "[io]") {
  // The background writer may finish step 1's file before step 0's.
  test::TempDir dir("roller_vtu_test");
  PvdSeries series(dir.path() / "series.pvd");
  series.add(1.0, dir.path() / "step_1.vtu");
  series.add(0.0, dir.path() / "step_0.vtu");
  series.add(3.0, dir.path() / "step_3.vtu");
  series.add(2.0, dir.path() / "step_2.vtu");
  const std::string xml = read_text(series.path());
  INFO(xml);
  std::size_t last = 0;
  for (int i = 0; i <= 3; ++i) {
    const std::size_t at = xml.find("step_" + std::to_string(i) + ".vtu");
    REQUIRE(at != std::string::npos);
    CHECK(at > last);
    last = at;
  }
}
