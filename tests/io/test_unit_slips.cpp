// Slips of units that the bounds alone would let through or leave unexplained: a modulus in Pa,
// a yield stress in Pa beside E in MPa; each named with the likely unit before computing.
#include <catch2/catch.hpp>

#include <string>

#include "../support/scene_errors.hpp"

using namespace roller;
using test::error_of;
using Catch::Contains;

namespace {

const std::string kBlock = R"(
[mesh]
element = "Q4"
length = 10.0
height = 5.0
nx = 4
ny = 2
[material]
E = 2.1e5
nu = 0.3
yield_stress = 500.0
[steps]
count = 2
[[displacement]]
nodes = "bottom"
y = 0.0
)";

}  // namespace

TEST_CASE("a modulus or a yield stress in the wrong unit is refused with the likely unit", "[io][scene][errors]") {
  CHECK(error_of(kBlock).empty());
  // E in Pa: beyond the modulus's bound, and the message says why it likely is.
  CHECK_THAT(error_of(kBlock, {{"material.E", "2.1e11"}}),
             Contains("material.E = 210000000000") && Contains("E in Pa? roller works in MPa"));
  // The yield stress in Pa beside E in MPa, or E in GPa beside the yield stress in MPa.
  CHECK_THAT(error_of(kBlock, {{"material.yield_stress", "5e8"}}),
             Contains("material.yield_stress = 500000000") && Contains("yield stress in Pa") &&
                 Contains("roller works in MPa"));
  CHECK_THAT(error_of(kBlock, {{"material.E", "210"}}), Contains("yield_stress") && Contains("E in GPa"));
  // A layer's too.
  CHECK_THAT(error_of(kBlock + "[[layer]]\nthickness = 1.0\nyield_stress = 5e8\n"),
             Contains("layer") && Contains("yield stress in Pa"));
  // A polymer's ratio stays legal (nylon: E = 2500, yield 75: 3 %).
  CHECK(error_of(kBlock, {{"material.E", "2500"}, {"material.yield_stress", "75"}}).empty());
}
