#pragma once

/// Remedies in library terms, worded by each front end in its own.
///
/// A library error that suggests a setting names it as the setting's C++ field in backticks,
/// `` `shell = true` `` or `` `units = "mm"` ``, built by `setting()`. The command line prints
/// it as a flag (`--shell`, `--units mm`), a scene file as its key ('shell = true'), Python
/// as a keyword argument (`shell=True`, `units="mm"`): `word_for()` rewrites every such
/// reference of a message for one surface. The library and C++ users read the message
/// unchanged.

#include <cstddef>
#include <string>
#include <string_view>

namespace rigid {

/// `` `key = true` ``: a boolean setting to switch on.
[[nodiscard]] std::string setting(std::string_view key);
/// `` `key = "value"` ``: a setting with a text value.
[[nodiscard]] std::string setting(std::string_view key, std::string_view value);

/// "1 boundary edge", "2 boundary edges": a count with its noun in the singular or the plural
/// (`plural` defaults to the singular + "s"; give it for "vertex"/"vertices").
[[nodiscard]] std::string counted(std::size_t n, std::string_view singular, std::string_view plural = {});

/// The front ends that word a remedy.
enum class Surface { kLibrary, kCli, kScene, kPython };

/// `message` with every setting reference in the terms of `surface`:
///  - kCli: `--key-with-dashes` for `true`, `--key value` for a text value;
///  - kPython: `key=True`, `key="value"`;
///  - kScene: 'key = true', 'key = "value"' (quoted as the scene's key, no longer a reference,
///    so a scene's error keeps the file's spelling whichever front end shows it);
///  - kLibrary: unchanged.
/// For every surface but kLibrary, the C++ function names that RIGID_REQUIRE puts before a
/// message (`integrate(): `) are left out as well (strip_function_names): they name the C++
/// entry point, which a user of the command line, a scene or Python never called.
[[nodiscard]] std::string word_for(Surface surface, std::string_view message);

/// `message` without the `name(): ` of a C++ function at its start and after each `: ` (where
/// a front end put its context before the library's message): "file:3:1: body 'b':
/// make_primitive(): radius …" becomes "file:3:1: body 'b': radius …".
[[nodiscard]] std::string strip_function_names(std::string_view message);

}  // namespace rigid
