#pragma once
// How a solve ended: the one word for every solve (Newton, a contact backend, an NLP's friction
// passes); the driver cuts the step on anything but Converged.
namespace roller {

enum class Termination {
  Converged,
  LimitReached,  // an iteration, pass or stage budget ran out, or the method stalled: a smaller
                 // step (or a larger budget) may succeed
  Failed,        // no usable solution: the strip could not be evaluated, NaN, a solver error
};

}  // namespace roller
