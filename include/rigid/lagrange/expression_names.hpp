#pragma once

/// The names an expression's text uses, read by the expression language's own rule without
/// parsing it and without the symbolic core: what a caller needs to know which parameters a
/// constant expression depends on (a sweep's run reuses a result whose inputs did not change).

#include <string>
#include <string_view>
#include <vector>

namespace rigid::lagrange {

/// Every name in `text`, in order of appearance, repeats included: parameters, coordinates,
/// functions (`sin`) and `pi` alike; a number (`1e-3`, `2.5E+4`, `.5`) is not a name. For a
/// text the parser accepts, these are exactly the names it reads.
[[nodiscard]] std::vector<std::string> names_in(std::string_view text);

}  // namespace rigid::lagrange
