#include "roller/core/error.hpp"

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>

namespace roller {

void throw_file_error(const std::string& message, int errnum) {
  const std::string text = errnum != 0 ? message + ": " + std::strerror(errnum) : message;
  switch (errnum) {
    case EROFS:
    case EACCES:
    case EPERM:
    case ENOTDIR:
    case EISDIR:
    case ENAMETOOLONG:
    case ENOENT:
    case ELOOP:
    case EEXIST:
    case EINVAL: throw InputError(text);
    default: throw SystemError(text);
  }
}

void assertion_failed(const char* condition, const char* what, const char* file, int line) {
  std::fprintf(stderr,
               "roller: internal error: %s:%d: assertion '%s' failed: %s (please report it with the scene file)\n",
               file, line, condition, what);
  std::abort();
}

}  // namespace roller
