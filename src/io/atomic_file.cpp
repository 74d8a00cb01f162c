#include "roller/io/atomic_file.hpp"

#include <cerrno>
#include <fstream>
#include <system_error>

#include <fcntl.h>
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

fs::path temporary_of(const fs::path& path) {
  fs::path tmp = path;
  tmp += ".tmp";
  return tmp;
}

}  // namespace

void write_file_atomically(const fs::path& path, std::string_view content, std::string_view what) {
  const fs::path tmp = temporary_of(path);
  {
    errno = 0;
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    if (!out)
      throw_file_error(fmt::format("cannot write {}: cannot create '{}'", named(path, what), tmp.string()), errno);
    out.write(content.data(), static_cast<std::streamsize>(content.size()));
    out.close();
    if (!out) {
      const int err = errno;
      std::error_code ignored;
      fs::remove(tmp, ignored);
      throw_file_error(fmt::format("cannot write {} (through '{}')", named(path, what), tmp.string()), err);
    }
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
  std::size_t done = 0;
  while (done < content.size()) {
    const ssize_t n = ::write(fd, content.data() + done, content.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) break;
    done += static_cast<std::size_t>(n);
  }
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
