#pragma once

#include <filesystem>
#include <string_view>

namespace rigid::io {

/// Writes `contents` to `path` so that readers see either the old file or the whole
/// new one, never a part: the bytes go to a temporary file in the same directory,
/// are flushed, and the temporary is renamed over `path`. On any failure the
/// temporary is removed and nothing at `path` changes.
///
/// What is at `path` is checked first (check_output_file): a regular file is replaced, a new
/// name is created; a directory, FIFO, socket or device is refused (the rename would put a
/// regular file in its place: `-o /dev/null` run as root would replace /dev/null). A symbolic
/// link is written through, never replaced: the file it names (every link followed) is
/// replaced in its own directory, so the link stays and now names the new file; a dangling
/// link's target is created.
/// @throws rigid::Error naming the path and the system's reason if the directory is
///         missing or not writable, or the disk is full; naming the path, what is there and
///         what was expected (a regular file or a new name) for a special file.
void write_file_atomically(const std::filesystem::path& path, std::string_view contents);

/// The check write_file_atomically makes before writing, for a caller that refuses an output
/// before doing the work: `path` (its symbolic links followed, at most 40) must be a regular
/// file or a new name in an existing directory. Returns the file that a write replaces or
/// creates: `path` itself, or the file its links name.
/// @throws rigid::Error naming `path`, what is there (a directory, a FIFO, a socket, a character
///         or block device; the link's target when it is a link) and what was expected.
[[nodiscard]] std::filesystem::path check_output_file(const std::filesystem::path& path);

}  // namespace rigid::io
