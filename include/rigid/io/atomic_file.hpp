#pragma once

#include <filesystem>
#include <string_view>

namespace rigid::io {

/// Writes `contents` to `path` so that readers see either the old file or the whole
/// new one, never a part: the bytes go to a temporary file in the same directory,
/// are flushed, and the temporary is renamed over `path`. On any failure the
/// temporary is removed and nothing at `path` changes.
/// @throws rigid::Error naming the path and the system's reason if the directory is
///         missing or not writable, or the disk is full.
void write_file_atomically(const std::filesystem::path& path, std::string_view contents);

}  // namespace rigid::io
