#pragma once
// Files of the output folder that must be whole or absent: written beside and renamed, and a
// small file (summary.json) that must be written even when the disk has filled up meanwhile.
// A failure throws throw_file_error's InputError (the folder cannot be written) or SystemError
// (a full disk), naming the path.
#include <cstddef>
#include <filesystem>
#include <string>
#include <string_view>

namespace roller {

// Writes `content` to "<path>.tmp" and renames it over `path` (atomic on POSIX within one file
// system): the target is either the old file or the complete new one. `what` names the file in
// messages ("the state file"); empty: the path alone.
void write_file_atomically(const std::filesystem::path& path, std::string_view content, std::string_view what = "");

// The same for a copy of the file `from`.
void copy_file_atomically(const std::filesystem::path& from, const std::filesystem::path& to,
                          std::string_view what = "");

// Creates `path` holding `content` padded with blanks to `reserve` bytes, so that the disk's
// blocks for a later write_reserved() are taken now.
void write_with_reserve(const std::filesystem::path& path, const std::string& content, std::size_t reserve);

// Writes `content` to `path` atomically; when that fails (a full disk), overwrites the file
// write_with_reserve() made in place and cuts it to the content, which needs no new block as long
// as the content fits the reserve. Throws the atomic write's error when both fail.
void write_reserved(const std::filesystem::path& path, const std::string& content);

}  // namespace roller
