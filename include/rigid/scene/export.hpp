#pragma once

// Code export of a scene: its equations of motion as one dependency-free source file.

#include <cstddef>
#include <string>
#include <string_view>

#include "rigid/lagrange/export.hpp"
#include "rigid/scene/model.hpp"

namespace rigid::scene {

/// The equations of motion of a coordinate scene as C++ or Python source
/// (rigid::lagrange::emit_cpp / emit_python), for the scene's parameters (after overrides)
/// as the defaults; `name` is the C++ namespace (default: the scene file's stem); `flat`: C++'s
/// flat layout (lagrange::ExportOptions::flat; `name` then names the helpers' namespace), its
/// derivatives within `max_stack_bytes` of stack (lagrange::ExportOptions::max_stack_bytes), in
/// the namespace `flat_namespace` (lagrange::ExportOptions::flat_namespace; empty: global).
/// @throws rigid::Error for an unknown language (with a close match), a scene of free
///   bodies, which has no generalized coordinates to export, or `flat` with Python.
[[nodiscard]] std::string emit_code(
    const Model& model, std::string_view language, const std::string& name = {}, bool flat = false,
    std::size_t max_stack_bytes = lagrange::ExportOptions::kDefaultMaxStackBytes,
    const std::string& flat_namespace = {});

}  // namespace rigid::scene
