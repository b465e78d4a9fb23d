#pragma once

// A run's schema as the JSON value summary.json embeds (rigid::io::schema_json's text).

#include <nlohmann/json.hpp>

#include "rigid/io/run_schema.hpp"

namespace rigid::io::detail {

[[nodiscard]] nlohmann::ordered_json schema_to_json(const RunSchema& schema);

}  // namespace rigid::io::detail
