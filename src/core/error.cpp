#include "roller/core/error.hpp"

#include <cerrno>
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

}  // namespace roller
