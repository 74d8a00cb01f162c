#pragma once
// Two tiers of checks (deal.II Assert/AssertThrow, MFEM_ASSERT/MFEM_VERIFY):
//  * ROLLER_ASSERT: pre- and post-conditions of the code, compiled out in release builds;
//  * roller::require / throw InputError / NumericalError: always on, for user input, I/O and
//    module boundaries. Messages say where, what, and the likely fix.
#include <stdexcept>
#include <string>

namespace roller {

// Bad user input: scene files, CLI flags, state files. The message names file, key, value,
// what was expected.
class InputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// A computation that cannot continue (non-finite values, singular matrix, no convergence).
// The driver catches it to cut the step; the message names the cause and the fix.
class NumericalError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// The machine refused (a full disk, an unwritable folder): not the user's input, not the
// physics. The command line exits with 3.
class SystemError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// A file or folder that cannot be written or created. The path the user gave cannot be used (not
// a folder, read-only, too long, not permitted): InputError, exit 2. The machine refused (a
// full disk, a quota, an I/O error, no memory): SystemError, exit 3. `errnum` is the errno of the
// failed call (0 if unknown: the machine's); the message ends with its text.
[[noreturn]] void throw_file_error(const std::string& message, int errnum);

inline void require(bool condition, const std::string& message) {
  if (!condition) throw std::logic_error(message);
}

}  // namespace roller

namespace roller {
// A failed ROLLER_ASSERT: prints where and what and aborts (a bug, not the user's input).
[[noreturn]] void assertion_failed(const char* condition, const char* what, const char* file, int line);
}  // namespace roller

// ROLLER_ASSERT(condition, "what must hold"): a pre- or post-condition of the code itself
// (deal.II's Assert: each one a bug found where it starts, not three calls later). Checked in
// Debug builds (the sanitizer build of CI runs every fast test with them), compiled out in
// Release; it must not have side effects.
#ifdef NDEBUG
#define ROLLER_ASSERT(cond, what) ((void)0)
#else
#define ROLLER_ASSERT(cond, what) ((cond) ? (void)0 : ::roller::assertion_failed(#cond, what, __FILE__, __LINE__))
#endif
