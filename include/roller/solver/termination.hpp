#pragma once
// How a solve ended: the one word for every solve (Newton, a contact backend, an NLP's friction
// passes); the driver cuts the step on anything but Converged.
#include "roller/core/enum_names.hpp"

namespace roller {

enum class Termination {
  Converged,
  LimitReached,  // an iteration, pass or stage budget ran out, or the method stalled: a smaller
                 // step (or a larger budget) may succeed
  Failed,        // no usable solution: the strip could not be evaluated, NaN, a solver error
  Interrupted,   // a stop was requested (SIGINT, SIGTERM): the solve was left, nothing failed
};
template <>
struct EnumNames<Termination> {
  static constexpr std::array<std::pair<Termination, const char*>, 4> names{
      {{Termination::Converged, "converged"},
       {Termination::LimitReached, "limit_reached"},
       {Termination::Failed, "failed"},
       {Termination::Interrupted, "interrupted"}}};
};

}  // namespace roller
