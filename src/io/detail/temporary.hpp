#pragma once

// Names of the temporaries the writers of rigid::io make beside their targets, and the cleanup
// of those a killed process left behind. A temporary is `.NAME.rigid-tmp-PID-XXXXXXXX`: hidden,
// never one of a run's file names, and owned by the process PID, so that a later write to the
// same target can tell an abandoned one (its process is gone) from one being written now.

#include <filesystem>
#include <string>
#include <string_view>

namespace rigid::io::detail {

/// `.NAME.rigid-tmp-PID-XXXXXXXX` for the target named `name` (XXXXXXXX random).
[[nodiscard]] std::string temporary_name(std::string_view name);

/// True when `entry` is a temporary of the target `name` (of any process).
[[nodiscard]] bool is_temporary_of(std::string_view entry, std::string_view name);

/// Removes the temporaries of `name` in `dir` whose process has ended (files or directories);
/// errors are ignored (another process may be removing them too).
void remove_stale_temporaries(const std::filesystem::path& dir, std::string_view name);

}  // namespace rigid::io::detail
