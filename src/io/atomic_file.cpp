#include "roller/io/atomic_file.hpp"

#include <cerrno>
#include <system_error>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <fmt/format.h>

#include "roller/core/error.hpp"

namespace roller {

namespace fs = std::filesystem;

namespace {

// How a message names the file: "the state file '<path>'" or "'<path>'".
std::string named(const fs::path& path, std::string_view what) {
  return what.empty() ? fmt::format("'{}'", path.string()) : fmt::format("{} '{}'", what, path.string());
}

// The finished "<path>.tmp" renamed over `path`; on failure the temporary file is removed.
void rename_into_place(const fs::path& tmp, const fs::path& path, std::string_view what) {
  std::error_code ec;
  fs::rename(tmp, path, ec);
  if (!ec) return;
  std::error_code ignored;
  fs::remove(tmp, ignored);
  throw_file_error(fmt::format("cannot write {}: renaming '{}' onto it failed", named(path, what), tmp.string()),
                   ec.value());
}

// Writes as much of `content` to the open file as it takes; the bytes written (fewer: errno says why).
std::size_t write_all(int fd, std::string_view content) {
  std::size_t done = 0;
  while (done < content.size()) {
    const ssize_t n = ::write(fd, content.data() + done, content.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) break;
    done += static_cast<std::size_t>(n);
  }
  return done;
}

fs::path temporary_of(const fs::path& path) {
  fs::path tmp = path;
  tmp += ".tmp";
  return tmp;
}

}  // namespace

void write_file_atomically(const fs::path& path, std::string_view content, std::string_view what) {
  const fs::path tmp = temporary_of(path);
  // The temporary file only as a regular file of ours: never through a symbolic link, and never
  // blocking on a FIFO that stands under its name.
  errno = 0;
  const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_NOFOLLOW | O_NONBLOCK | O_CLOEXEC, 0666);
  struct stat info {};
  const int open_error = fd < 0 ? errno : 0;
  const bool regular = fd >= 0 && ::fstat(fd, &info) == 0 && S_ISREG(info.st_mode);
  if (!regular) {
    if (fd >= 0) ::close(fd);
    // A link (ELOOP), a FIFO without a reader (ENXIO), a folder or a device under the name: the
    // user's folder holds something roller does not write through (exit 2).
    if (fd >= 0 || open_error == ELOOP || open_error == ENXIO || open_error == EISDIR)
      throw InputError(
          fmt::format("cannot write {}: something other than a regular file stands at '{}'; "
                      "remove it (roller never writes through or replaces it)",
                      named(path, what), tmp.string()));
    throw_file_error(fmt::format("cannot write {}: cannot create '{}'", named(path, what), tmp.string()), open_error);
  }
  const std::size_t done = write_all(fd, content);
  const int write_error = done == content.size() ? 0 : (errno != 0 ? errno : EIO);
  const bool closed = ::close(fd) == 0;
  if (write_error != 0 || !closed) {
    const int err = write_error != 0 ? write_error : errno;
    std::error_code ignored;
    fs::remove(tmp, ignored);
    throw_file_error(fmt::format("cannot write {} (through '{}')", named(path, what), tmp.string()), err);
  }
  rename_into_place(tmp, path, what);
}

void copy_file_atomically(const fs::path& from, const fs::path& to, std::string_view what) {
  const fs::path tmp = temporary_of(to);
  std::error_code ec;
  fs::copy_file(from, tmp, fs::copy_options::overwrite_existing, ec);
  if (ec) {
    std::error_code ignored;
    fs::remove(tmp, ignored);
    throw_file_error(fmt::format("cannot write {} (a copy of '{}')", named(to, what), from.string()), ec.value());
  }
  rename_into_place(tmp, to, what);
}

void write_with_reserve(const fs::path& path, const std::string& content, std::size_t reserve) {
  std::string padded = content;
  if (padded.size() < reserve) padded.append(reserve - padded.size() - 1, ' ').push_back('\n');
  write_file_atomically(path, padded);
}

namespace {

// Overwrites the existing file in place from its start and cuts it to `content`; false on failure.
bool overwrite_in_place(const fs::path& path, const std::string& content) {
  const int fd = ::open(path.c_str(), O_WRONLY | O_CLOEXEC);
  if (fd < 0) return false;
  const std::size_t done = write_all(fd, content);
  const bool ok = done == content.size() && ::ftruncate(fd, static_cast<off_t>(content.size())) == 0;
  return ::close(fd) == 0 && ok;
}

}  // namespace

void write_reserved(const fs::path& path, const std::string& content) {
  try {
    write_file_atomically(path, content);
  } catch (const std::exception&) {
    if (!overwrite_in_place(path, content)) throw;
  }
}

}  // namespace roller
